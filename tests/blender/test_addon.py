"""The raps_uv add-on in Blender itself, headless (CTest's blender_addon):

  blender -b --factory-startup --python-exit-code 1 --python tests/blender/test_addon.py -- \
      --zip build/bindings/blender/raps_uv.zip --meshes ../shared/data/meshes \
      --uvmetrics ../shared/tools/uvmetrics.py --python3 /usr/bin/python3 --work DIR

Installs the built zip as a user would (into $BLENDER_USER_SCRIPTS), then unwraps shared meshes
(triangles, quads and n-gons; one object and several) and checks what a user relies on: every
face has uvs, with no flipped or overlapping triangle (uvmetrics on an exported OBJ), the
artist's seams and materials stay chart boundaries, Esc's cancellation and errors leave every
UV map as it was, Ctrl-Z restores it, and Blender's other data (UV maps, materials, modifiers)
is left alone.
"""

import argparse
import json
import os
import shutil
import subprocess
import sys
import threading
import time
import unittest

import bpy
import numpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import loop_triangle_obj  # noqa: E402
import mesh_file  # noqa: E402


def _arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser()
    for name in ("--zip", "--meshes", "--uvmetrics", "--python3", "--work"):
        parser.add_argument(name, required=True)
    parser.add_argument("tests", nargs="*", help="test names to run (default: all)")
    return parser.parse_args(argv)


ARGS = _arguments()
# uvmetrics: the overlap fraction of an injective map is raster noise, of order 1/1024.
OVERLAP_NOISE = 2e-3


# ------------------------------------------------------------------------------------------------
# Scene helpers
# ------------------------------------------------------------------------------------------------


def clear_scene():
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    for mesh in list(bpy.data.meshes):
        bpy.data.meshes.remove(mesh)


def load(name):
    """A shared mesh as one object (its faces as they are in the file: triangles or quads)."""
    bpy.ops.object.select_all(action="DESELECT")
    bpy.ops.import_scene.obj(filepath=os.path.join(ARGS.meshes, name), split_mode="OFF")
    obj = bpy.context.selected_objects[0]
    bpy.context.view_layer.objects.active = obj
    return obj


def load_polygons(name):
    """A shared mesh as one object built from its polygons (OFF too, which Blender's importer
    does not read)."""
    verts, faces = mesh_file.read_mesh_file(os.path.join(ARGS.meshes, name))
    mesh = bpy.data.meshes.new(name.split(".")[0])
    mesh.from_pydata(verts, [], faces)
    obj = bpy.data.objects.new(mesh.name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def select(*objects):
    bpy.ops.object.select_all(action="DESELECT")
    for obj in objects:
        obj.select_set(True)
    bpy.context.view_layer.objects.active = objects[0]


def grid(name, size=12):
    """A size x size grid of quads over the unit square, bent along x (a developable
    surface: its map is near an isometry, so its faces keep their shapes), as one object."""
    verts = [(x / size, y / size, 0.5 * (x / size - 0.5) ** 2) for y in range(size + 1)
             for x in range(size + 1)]
    faces = [(y * (size + 1) + x, y * (size + 1) + x + 1, (y + 1) * (size + 1) + x + 1,
              (y + 1) * (size + 1) + x) for y in range(size) for x in range(size)]
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(verts, [], faces)
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def uv_array(obj, layer=None):
    mesh = bpy.data.objects[obj if isinstance(obj, str) else obj.name].data
    data = (mesh.uv_layers[layer] if layer else mesh.uv_layers.active).data
    values = numpy.empty(2 * len(data), dtype=numpy.float32)
    data.foreach_get("uv", values)
    return values.reshape(-1, 2)


def metrics(*objects):
    """uvmetrics's figures of the objects' active UV maps, written together as one OBJ."""
    path = os.path.join(ARGS.work, "_".join(o.name for o in objects) + ".obj")
    loop_triangle_obj.write(objects, path)
    out = subprocess.run([ARGS.python3, ARGS.uvmetrics, path], capture_output=True, text=True)
    if out.returncode != 0:
        raise AssertionError("uvmetrics failed: " + out.stdout + out.stderr)
    return json.loads(out.stdout)


def split_at_edge(obj, edge_index, layer=None):
    """Whether the two faces of an edge give both its vertices different uvs (a chart
    boundary runs along it); None for an edge without two faces."""
    mesh = obj.data
    uv = uv_array(obj, layer)
    ends = set(mesh.edges[edge_index].vertices)
    corners = []
    for polygon in mesh.polygons:
        loops = [i for i in polygon.loop_indices if mesh.loops[i].edge_index == edge_index]
        if loops:
            corners.append({mesh.loops[i].vertex_index: tuple(uv[i])
                            for i in polygon.loop_indices if mesh.loops[i].vertex_index in ends})
    if len(corners) != 2:
        return None
    return all(corners[0][v] != corners[1][v] for v in ends)


def raps_phase(name):
    from raps_uv.native import raps
    return getattr(raps.Phase, name)


class _FakeOperator:
    """The properties and report() an operator call gives operators.Run, for the tests that
    drive the menu's path without Blender's event loop (which a headless Blender lacks)."""

    def __init__(self, **options):
        from raps_uv import operators
        self.one_atlas, self.uv_map, self.new_uv_map = False, "", False
        self.monitor, self.alpha, self.iterations = "AREA", 1.0, 1
        self.size_mode, self.resolution, self.texels_per_unit = "RESOLUTION", 1024, 1.0
        self.padding, self.rotation, self.lightmap = 1, "ANY", False
        self.use_seams, self.use_materials = True, False
        self.show_new_map = True
        for key, value in options.items():
            setattr(self, key, value)
        self.reports = []
        # The operators' own methods (raps_options, layer_name), on these properties.
        for method in ("raps_options", "layer_name"):
            setattr(self, method, getattr(operators.UnwrapProperties, method).__get__(self))

    def report(self, kind, text):
        self.reports.append((kind, text))


# ------------------------------------------------------------------------------------------------
# Tests
# ------------------------------------------------------------------------------------------------


class AddonTest(unittest.TestCase):

    def setUp(self):
        clear_scene()

    def assert_valid_map(self, *objects):
        """Every face has finite uvs in the unit square, none flipped, no two overlapping."""
        for obj in objects:
            uv = uv_array(obj)
            self.assertTrue(numpy.isfinite(uv).all(), obj.name)
            self.assertGreaterEqual(uv.min(), 0.0, obj.name)
            self.assertLessEqual(uv.max(), 1.0, obj.name)
        m = metrics(*objects)
        self.assertEqual(m.get("n_faces_without_uv", 0), 0, "faces without uvs")
        self.assertEqual(m["n_nonfinite_uv"], 0)
        self.assertEqual(m["n_flipped"], 0, "flipped triangles")
        self.assertLess(m["uv_overlap_fraction"], OVERLAP_NOISE, "overlapping triangles")
        return m

    def test_addon_uses_its_bundled_library(self):
        import raps_uv.native
        folder = os.path.dirname(raps_uv.native.__file__)
        self.assertEqual(raps_uv.native.raps.library_path, os.path.join(folder, "libraps.so"))
        self.assertTrue(hasattr(bpy.types, "RAPS_OT_unwrap"))
        self.assertTrue(hasattr(bpy.types, "RAPS_OT_lightmap"))

    def test_triangle_mesh_gets_a_valid_atlas(self):
        obj = load("teapot.obj")
        self.assertEqual(bpy.ops.raps.unwrap(), {"FINISHED"})
        m = self.assert_valid_map(obj)
        self.assertGreater(m["n_charts"], 1)
        self.assertGreater(m["unit_square_coverage"], 0.5)

    def test_quads_and_ngons_stay_whole(self):
        # suzanne: quads and triangles (two quads folded onto each other); horse_quad and
        # halftunnel: quads, whose diagonals raps's charts cut unless told the polygons; the
        # grid's middle is dissolved into one n-gon (with collinear corners). One run each, and no face needed the add-on's fallback
        # (made an island of its own): raps kept every polygon in one chart.
        ngon = grid("ngon")
        bpy.context.view_layer.objects.active = ngon
        bpy.ops.object.mode_set(mode="EDIT")
        bpy.ops.mesh.select_all(action="DESELECT")
        bpy.ops.object.mode_set(mode="OBJECT")
        for polygon in ngon.data.polygons:
            polygon.select = 0.3 < polygon.center.x < 0.7 and 0.3 < polygon.center.y < 0.7
        bpy.ops.object.mode_set(mode="EDIT")
        bpy.ops.mesh.dissolve_faces()
        bpy.ops.object.mode_set(mode="OBJECT")
        self.assertTrue(any(len(p.vertices) > 4 for p in ngon.data.polygons))
        from raps_uv import operators
        for obj in (load("suzanne.obj"), load("horse_quad.obj"), load_polygons("halftunnel.off"),
                    ngon):
            select(obj)
            operator = _FakeOperator()
            run = operators.Run(operator, bpy.context)
            self.assertIsNone(run.prepare())
            run.job.run()
            self.assertEqual(run.finish(bpy.context), {"FINISHED"})
            self.assertEqual(run.job.outcomes[0].repaired_polygons, 0, obj.name)
            self.assertNotIn("islands", operator.reports[0][1])
            self.assert_valid_map(obj)

    def test_edit_mode_unwraps_and_stays_in_edit_mode(self):
        obj = load("teapot.obj")
        bpy.ops.object.mode_set(mode="EDIT")
        self.assertEqual(bpy.ops.raps.unwrap(), {"FINISHED"})
        self.assertEqual(bpy.context.mode, "EDIT_MESH")
        bpy.ops.object.mode_set(mode="OBJECT")  # the edit mesh's uvs are what the mesh keeps
        self.assert_valid_map(obj)

    def test_several_objects_one_atlas_at_one_density(self):
        small, large = load("spot.obj"), load("spot.obj")
        large.scale = (2.0, 2.0, 2.0)
        large.location.x = 5.0
        select(small, large)
        self.assertEqual(bpy.ops.raps.unwrap(one_atlas=True, uv_map="atlas"), {"FINISHED"})
        # One atlas: the two objects' charts do not overlap each other either.
        m = self.assert_valid_map(small, large)
        self.assertGreater(m["unit_square_coverage"], 0.5)
        areas = [metrics(o)["uv_area"] for o in (small, large)]
        # World scale applied: twice the size, four times the texels (within packing's rounding).
        self.assertAlmostEqual(areas[1] / areas[0], 4.0, delta=0.2)

    def test_several_objects_one_atlas_each(self):
        first, second = load("spot.obj"), load("teapot.obj")
        select(first, second)
        self.assertEqual(bpy.ops.raps.unwrap(), {"FINISHED"})
        for obj in (first, second):
            self.assertGreater(self.assert_valid_map(obj)["unit_square_coverage"], 0.5)

    def test_seams_are_chart_boundaries(self):
        bpy.ops.mesh.primitive_uv_sphere_add(segments=32, ring_count=16)
        sphere = bpy.context.active_object
        equator = [e.index for e in sphere.data.edges
                   if all(abs(sphere.data.vertices[v].co.z) < 1e-6 for v in e.vertices)]
        self.assertEqual(len(equator), 32)
        self.assertEqual(bpy.ops.raps.unwrap(use_seams=False), {"FINISHED"})
        # The test can fail: without the seams some equator edge lies inside a chart.
        self.assertFalse(all(split_at_edge(sphere, e) for e in equator))
        for e in equator:
            sphere.data.edges[e].use_seam = True
        self.assertEqual(bpy.ops.raps.unwrap(), {"FINISHED"})
        self.assertTrue(all(split_at_edge(sphere, e) for e in equator))
        self.assert_valid_map(sphere)

    def test_materials_apart_when_asked(self):
        obj = grid("two_materials")
        for name in ("left", "right"):
            obj.data.materials.append(bpy.data.materials.new(name))
        for polygon in obj.data.polygons:
            polygon.material_index = 1 if polygon.center.x > 0.5 else 0
        between = [e.index for e in obj.data.edges
                   if all(abs(obj.data.vertices[v].co.x - 0.5) < 1e-6 for v in e.vertices)]
        select(obj)
        self.assertEqual(bpy.ops.raps.unwrap(use_materials=True), {"FINISHED"})
        self.assertTrue(all(split_at_edge(obj, e) for e in between))
        self.assert_valid_map(obj)

    def test_esc_cancels_mid_run_and_leaves_nothing_to_undo(self):
        # The menu's path as Blender's event loop drives it (operators.ModalRun: what the
        # operator's modal does with each event), with Esc arriving while the library maps the
        # charts. The job's progress goes into a raps.ProgressState; a library progress callback
        # beside it (the state records each report first) holds the run at the charts' maps
        # until Esc has been handled, so the cancel lands mid-run whatever the machine's speed.
        from raps_uv import operators
        from raps_uv.native import raps
        obj = load("spot.obj")
        name = obj.name
        loaded = uv_array(obj).copy()
        bpy.ops.ed.undo_push(message="loaded")
        bpy.ops.raps.unwrap()  # a map to keep: the state before the cancelled run
        bpy.ops.ed.undo_push(message="first unwrap")
        layers_before = [layer.name for layer in obj.data.uv_layers]
        before = uv_array(obj).copy()
        operator = _FakeOperator(lightmap=True, uv_map="Lightmap")
        run = operators.Run(operator, bpy.context)
        self.assertIsNone(run.prepare())
        inside, esc_handled = threading.Event(), threading.Event()

        def wait_for_esc(_user, phase, _fraction):
            if phase == raps_phase("INITIAL_MAP") and not inside.is_set():
                inside.set()
                esc_handled.wait()
            return 1
        gate = raps._native.raps_progress_fn(wait_for_esc)
        job_settings = run.job.options.settings

        def gated_settings():
            settings = job_settings()
            raps._lib.raps_settings_set_progress(settings._ptr(), gate, None)
            return settings
        run.job.options.settings = gated_settings
        modal = operators.ModalRun(run, bpy.context)
        try:
            self.assertTrue(inside.wait(60), "the library never reached its charts' maps")
            self.assertEqual(modal.handle("TIMER", bpy.context), {"RUNNING_MODAL"})  # progress
            fraction = run.job.fraction
            self.assertEqual(modal.handle("ESC", bpy.context), {"RUNNING_MODAL"})
        finally:
            esc_handled.set()  # never leave the worker waiting, even when the test fails
        self.assertGreater(fraction, 0.0)
        self.assertLess(fraction, 1.0)
        result = {"RUNNING_MODAL"}
        while result == {"RUNNING_MODAL"}:
            modal.thread.join(0.05)
            result = modal.handle("TIMER", bpy.context)
        self.assertEqual(result, {"CANCELLED"})
        self.assertTrue(run.job.cancelled)
        self.assertEqual(operator.reports, [({"WARNING"}, "raps: cancelled, no UV map changed")])
        # Nothing half-written: no lightmap layer added, the other maps as they were.
        self.assertEqual([layer.name for layer in obj.data.uv_layers], layers_before)
        self.assertTrue(numpy.array_equal(uv_array(name), before))
        # CANCELLED pushes no undo step (Blender's rule for operators): Ctrl-Z goes back
        # past the first unwrap, and redo brings it back.
        bpy.ops.ed.undo()
        self.assertTrue(numpy.array_equal(uv_array(name), loaded))
        bpy.ops.ed.redo()
        self.assertTrue(numpy.array_equal(uv_array(name), before))

    def test_undo_restores_the_uv_map(self):
        obj = load("spot.obj")
        name = obj.name
        before = uv_array(obj).copy()
        self.assertIn("UNDO", bpy.types.RAPS_OT_unwrap.bl_options)
        bpy.ops.ed.undo_push(message="before raps")
        self.assertEqual(bpy.ops.raps.unwrap(), {"FINISHED"})
        self.assertFalse(numpy.array_equal(uv_array(name), before))
        # Blender pushes the operator's undo step (its UNDO option) only when a window runs
        # it; headless, the test pushes it, and Ctrl-Z's undo must then bring the map back.
        bpy.ops.ed.undo_push(message="Unwrap with raps")
        bpy.ops.ed.undo()
        self.assertTrue(numpy.array_equal(uv_array(name), before))

    def test_errors_name_the_object_and_change_nothing(self):
        good = load("spot.obj")
        before = uv_array(good).copy()
        # Vertex 0 is loose (raps never sees it): the message must still say Blender's 3.
        broken_mesh = bpy.data.meshes.new("broken")
        broken_mesh.from_pydata([(9, 9, 9), (0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)], [],
                                [(1, 2, 3, 4)])
        broken = bpy.data.objects.new("broken", broken_mesh)
        bpy.context.scene.collection.objects.link(broken)
        broken.data.vertices[3].co.x = float("nan")
        for one_atlas in (False, True):
            select(good, broken)
            with self.assertRaises(RuntimeError) as caught:
                bpy.ops.raps.unwrap(one_atlas=one_atlas)
            self.assertIn("broken", str(caught.exception))
            self.assertIn("vertex 3 has a non-finite coordinate", str(caught.exception))
            self.assertTrue(numpy.array_equal(uv_array(good), before))
            self.assertEqual(len(broken.data.uv_layers), 0)
        empty_mesh = bpy.data.meshes.new("no_faces")
        empty_mesh.from_pydata([(0, 0, 0), (1, 0, 0)], [(0, 1)], [])
        empty = bpy.data.objects.new("no_faces", empty_mesh)
        bpy.context.scene.collection.objects.link(empty)
        select(good, empty)
        with self.assertRaises(RuntimeError) as caught:
            bpy.ops.raps.unwrap()
        self.assertIn("no_faces: has no faces", str(caught.exception))
        self.assertTrue(numpy.array_equal(uv_array(good), before))
        # Blender holds at most 8 UV maps: asking for a ninth is refused before raps runs.
        while len(good.data.uv_layers) < 8:
            good.data.uv_layers.new()
        select(good)
        with self.assertRaises(RuntimeError) as caught:
            bpy.ops.raps.unwrap(new_uv_map=True)
        self.assertIn("already has 8 UV maps", str(caught.exception))
        self.assertEqual(len(good.data.uv_layers), 8)

    def test_other_blender_data_is_left_alone(self):
        obj = load("spot.obj")
        mesh = obj.data
        mesh.uv_layers.new(name="Other")
        other = uv_array(obj, "Other").copy()
        first = uv_array(obj, "UVMap" if "UVMap" in mesh.uv_layers else mesh.uv_layers[0].name)
        first_name = mesh.uv_layers[0].name
        materials = [m.name if m else None for m in mesh.materials]
        modifier = obj.modifiers.new("Subdivision", "SUBSURF")
        modifier.levels = 2
        modifier.show_viewport = False  # kept, not evaluated: the test's time is raps's
        positions = numpy.empty(3 * len(mesh.vertices), dtype=numpy.float32)
        mesh.vertices.foreach_get("co", positions)
        self.assertEqual(bpy.ops.raps.unwrap(new_uv_map=True, uv_map="raps"), {"FINISHED"})
        self.assertEqual([layer.name for layer in mesh.uv_layers], [first_name, "Other", "raps"])
        self.assertEqual(mesh.uv_layers.active.name, "raps")
        self.assertTrue(numpy.array_equal(uv_array(obj, "Other"), other))
        self.assertTrue(numpy.array_equal(uv_array(obj, first_name), first))
        self.assertEqual([m.name if m else None for m in mesh.materials], materials)
        self.assertEqual([(m.name, m.type, m.levels, m.show_viewport) for m in obj.modifiers],
                         [("Subdivision", "SUBSURF", 2, False)])
        after = numpy.empty_like(positions)
        mesh.vertices.foreach_get("co", after)
        self.assertTrue(numpy.array_equal(after, positions))
        self.assert_valid_map(obj)

    def test_lightmap_goes_into_a_second_uv_map(self):
        obj = load("spot.obj")
        first = uv_array(obj).copy()
        self.assertEqual(bpy.ops.raps.lightmap(resolution=256), {"FINISHED"})
        names = [layer.name for layer in obj.data.uv_layers]
        self.assertEqual(names[1:], ["Lightmap"])
        self.assertTrue(numpy.array_equal(uv_array(obj, names[0]), first))
        obj.data.uv_layers.active = obj.data.uv_layers["Lightmap"]
        self.assert_valid_map(obj)

    def test_density_spreads_over_udim_tiles(self):
        obj = load("teapot.obj")
        # Two pages of 512 x 498 texels, no chart shrunk to fit one (raps-param --atlas
        # teapot.obj --texels-per-unit 64 --max-size 512; at 56 the charts fit one page).
        self.assertEqual(bpy.ops.raps.unwrap(size_mode="DENSITY", texels_per_unit=64,
                                             resolution=512), {"FINISHED"})
        uv = uv_array(obj)
        self.assertGreaterEqual(uv.min(), 0.0)
        self.assertLessEqual(uv[:, 1].max(), 1.0)
        # A whole chart, so each face, lies on one page: one tile.
        obj.data.calc_loop_triangles()
        loops = numpy.array([t.loops[:] for t in obj.data.loop_triangles])
        u = uv[loops, 0]
        tiles = numpy.floor(u.mean(axis=1))[:, None]
        self.assertTrue(((u >= tiles) & (u <= tiles + 1)).all())
        self.assertGreater(tiles.max(), 0)
        # Each tile is a square texture of the resolution: u and v at one scale, so the map's
        # L2 stretch is the library's (1.0071), not the cropped page's aspect (1.32) on top.
        self.assertLess(metrics(obj)["stretch_l2"], 1.0101)


class _TimedResult(unittest.TextTestResult):
    """Prints each test's seconds, so that a slow one shows in CTest's log."""

    def startTest(self, test):
        self._started = time.perf_counter()
        super().startTest(test)

    def stopTest(self, test):
        super().stopTest(test)
        self.stream.write("  %.2f s  %s\n" % (time.perf_counter() - self._started,
                                               test.id().split(".")[-1]))


def main():
    if os.path.isdir(ARGS.work):
        shutil.rmtree(ARGS.work)
    os.makedirs(ARGS.work)
    # A user's installation: the zip through the add-on preferences' Install button.
    bpy.ops.preferences.addon_install(filepath=ARGS.zip, overwrite=True)
    bpy.ops.preferences.addon_enable(module="raps_uv")
    loader = unittest.defaultTestLoader
    suite = loader.loadTestsFromNames(["AddonTest." + name for name in ARGS.tests],
                                      sys.modules[__name__]) if ARGS.tests else \
        loader.loadTestsFromTestCase(AddonTest)
    outcome = unittest.TextTestRunner(stream=sys.stdout, verbosity=2,
                                      resultclass=_TimedResult).run(suite)
    if not outcome.wasSuccessful():
        raise SystemExit(1)


main()
