"""Tests of the Python binding against the real libraps (unittest, standard library only).

Environment (CTest sets it): RAPS_LIBRARY, the library to test; RAPS_SHARED_DATA_DIR, the
shared meshes (missing data fails the tests, it never skips them); RAPS_TEST_WITHOUT_NUMPY=1
runs the whole suite as on a machine without numpy (plain sequences in, lists out);
RAPS_TEST_INSTALLED=1 tests the raps installed in this Python (with the library inside the
package, no RAPS_LIBRARY) instead of the source tree's.
"""

import ctypes
import gc
import math
import os
import subprocess
import sys
import threading
import time
import unittest

if os.environ.get("RAPS_TEST_WITHOUT_NUMPY") == "1":
    sys.modules["numpy"] = None  # makes `import numpy` raise ImportError, as if absent

INSTALLED = os.environ.get("RAPS_TEST_INSTALLED") == "1"
if not INSTALLED:
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import raps  # noqa: E402

try:
    import numpy
except ImportError:
    numpy = None
if numpy is None and os.environ.get("RAPS_TEST_WITHOUT_NUMPY") != "1":
    # The numpy run must not pass by leaving the numpy paths out.
    sys.exit("numpy is missing: install python3-numpy, or set RAPS_TEST_WITHOUT_NUMPY=1")

DATA = os.environ.get("RAPS_SHARED_DATA_DIR", "")


def read_off(path):
    """positions [(x, y, z)], triangles [(a, b, c)] of an OFF file (polygons fanned)."""
    with open(path) as stream:
        words = [w for line in stream for w in line.split("#")[0].split()]
    assert words[0] == "OFF", path
    nv, nf = int(words[1]), int(words[2])
    numbers = words[4:]
    positions = [tuple(float(v) for v in numbers[3 * i:3 * i + 3]) for i in range(nv)]
    triangles, at = [], 3 * nv
    for _ in range(nf):
        n = int(numbers[at])
        face = [int(v) for v in numbers[at + 1:at + 1 + n]]
        triangles += [(face[0], face[k], face[k + 1]) for k in range(1, n - 1)]
        at += 1 + n
    return positions, triangles


def icosahedron():
    """A closed mesh: no boundary loop, so the disk domain refuses it."""
    t = (1 + 5 ** 0.5) / 2
    positions = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
                 (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    triangles = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9),
                 (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2),
                 (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10),
                 (8, 6, 7), (9, 8, 1)]
    return positions, triangles


def fan_disk():
    """An open mesh: a hexagonal cap, one vertex raised above the middle of six on a circle."""
    ring = [(math.cos(k * math.pi / 3), math.sin(k * math.pi / 3), 0.0) for k in range(6)]
    return [(0.0, 0.0, 0.5)] + ring, [(0, 1 + k, 1 + (k + 1) % 6) for k in range(6)]


def det(a, b, c):
    """det[a, b, c]: positive when the triangle is counter-clockwise seen from outside."""
    return (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0]))


def rows(values):
    """Output rows as a list of tuples, whether numpy is there or not."""
    return [tuple(row) for row in (values.tolist() if numpy is not None else values)]


def signed_area(a, b, c):
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])


def phase_sequence(calls):
    """The phases of (phase, fraction) progress calls in the order entered, each once: a phase
    entered twice, or calls of two phases interleaved, show up as a repeat."""
    sequence = []
    for phase, _ in calls:
        if not sequence or sequence[-1] != phase:
            sequence.append(phase)
    return sequence


class SharedMesh(unittest.TestCase):
    """camelhead.off, a real disk-shaped scan, through the whole binding."""

    @classmethod
    def setUpClass(cls):
        path = os.path.join(DATA, "meshes", "camelhead.off")
        if not os.path.isfile(path):
            raise AssertionError("shared test data missing: %r (set RAPS_SHARED_DATA_DIR)" % path)
        cls.positions, cls.triangles = read_off(path)
        cls.mesh = raps.Mesh(cls.positions, cls.triangles)

    @classmethod
    def tearDownClass(cls):
        cls.mesh.close()

    def test_mesh_counts(self):
        self.assertEqual(self.mesh.vertex_count, len(self.positions))
        self.assertEqual(self.mesh.triangle_count, len(self.triangles))

    def test_area_monitor_map_is_valid_and_less_distorted(self):
        with raps.Settings(monitor=raps.Monitor.NONE) as plain, raps.Settings() as adaptive:
            self.assertEqual(adaptive.monitor, raps.Monitor.AREA)  # the default
            first = raps.parameterize(self.mesh, plain)
            second = raps.parameterize(self.mesh, adaptive)
        for result in (first, second):
            stats = result.stats()
            self.assertEqual(stats.flipped_triangles, 0)
            self.assertEqual(stats.vertex_count, len(self.positions))
            self.assertEqual(stats.triangle_count, len(self.triangles))
            uvs = rows(result.uvs())
            self.assertEqual(len(uvs), len(self.positions))
            for u, v in uvs:
                self.assertTrue(0.0 <= u <= 1.0 and 0.0 <= v <= 1.0, (u, v))
            # Counter-clockwise in 3D stays counter-clockwise in uv: check it here too.
            for a, b, c in self.triangles[::97]:
                self.assertGreater(signed_area(uvs[a], uvs[b], uvs[c]), 0.0)
            self.assertEqual(rows(result.indices()), [tuple(t) for t in self.triangles])
            self.assertEqual(list(result.vertex_remap()), list(range(len(self.positions))))
        self.assertEqual(first.stats().adaptive_solves, 0)
        self.assertEqual(second.stats().adaptive_solves, 1)
        # The adaptive step equidistributes area: docs/bench-method.md measures 2.509 -> 0.721.
        self.assertLess(second.stats().area_log_mean, 0.5 * first.stats().area_log_mean)
        self.assertGreater(second.phase_ms(raps.Phase.ADAPT), 0.0)
        first.close()
        second.close()

    def test_float32_and_float64_agree(self):
        with raps.parameterize(self.mesh) as result:
            single = rows(result.uvs("float32"))
            double = rows(result.uvs())
        for (u32, v32), (u64, v64) in zip(single, double):
            self.assertAlmostEqual(u32, u64, delta=1e-6)
            self.assertAlmostEqual(v32, v64, delta=1e-6)

    def test_result_is_refilled(self):
        result = raps.Result()
        self.assertIs(raps.parameterize(self.mesh, result=result), result)
        self.assertEqual(result.vertex_count, len(self.positions))
        result.close()

    def test_numpy_strided_and_u16_inputs(self):
        # An interleaved buffer (x, y, z, nx, ny, nz) read through a strided view, float32,
        # and uint16 indices: the library is given the stride and reads in place.
        interleaved = numpy.zeros((len(self.positions), 6), dtype=numpy.float32)
        interleaved[:, :3] = self.positions
        view = interleaved[:, :3]
        self.assertEqual(view.strides[0], 24)
        with raps.Mesh(view, numpy.array(self.triangles, dtype=numpy.uint32)) as packed, \
                raps.Mesh(numpy.ascontiguousarray(view), numpy.array(self.triangles)) as plain:
            a = raps.parameterize(packed).uvs()
            b = raps.parameterize(plain).uvs()
        self.assertTrue(numpy.array_equal(a, b))
        self.assertEqual(a.shape, (len(self.positions), 2))
        self.assertEqual(a.dtype, numpy.float64)

    def test_concurrent_runs_share_mesh_and_settings(self):
        settings = raps.Settings(iterations=2)
        expected = rows(raps.parameterize(self.mesh, settings).uvs())
        outputs = [None] * 4

        def run(k):
            outputs[k] = rows(raps.parameterize(self.mesh, settings).uvs())

        threads = [threading.Thread(target=run, args=(k,)) for k in range(4)]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
        for output in outputs:
            self.assertEqual(output, expected)
        settings.close()

    def test_progress_reports_phases_in_order(self):
        # The disk domain goes through the first five phases; SEGMENT and PACK are the atlas's.
        calls = []
        raps.parameterize(self.mesh, progress=lambda phase, fraction: calls.append(
            (phase, fraction)))
        self.assertEqual(phase_sequence(calls), [
            raps.Phase.VALIDATE, raps.Phase.TOPOLOGY, raps.Phase.INITIAL_MAP, raps.Phase.ADAPT,
            raps.Phase.METRICS])
        self.assertTrue(all(isinstance(p, raps.Phase) for p, _ in calls))
        self.assertTrue(all(0.0 <= f <= 1.0 for _, f in calls))

    def test_progress_cancels_and_handles_stay_usable(self):
        settings = raps.Settings()
        result = raps.Result()
        with self.assertRaises(raps.Error) as caught:
            raps.parameterize(self.mesh, settings, progress=lambda p, f: p < raps.Phase.ADAPT,
                              result=result)
        self.assertEqual(caught.exception.status, raps.Status.CANCELLED)
        self.assertEqual(result.vertex_count, 0)
        # The callback was on a private copy: the shared settings never saw it.
        raps.parameterize(self.mesh, settings, result=result)
        self.assertEqual(result.vertex_count, len(self.positions))
        settings.close()
        result.close()

    def test_progress_state_is_read_and_cancelled_from_another_thread(self):
        # The run works on a thread of its own, as under a user interface; this thread polls
        # the state and cancels once the adaptive solves have begun (100 of them: seconds of
        # work left, where the cancel lands within one solve).
        state = raps.ProgressState()
        self.assertEqual(state.read(), (None, 0.0, 0))
        outcome = []

        def work():
            try:
                with raps.Settings(iterations=100) as settings:
                    raps.parameterize(self.mesh, settings, progress=state).close()
                outcome.append("finished")
            except raps.Error as error:
                outcome.append(error.status)

        thread = threading.Thread(target=work)
        thread.start()
        seen = []
        while thread.is_alive():
            reading = state.read()
            seen.append(reading.phase)
            if reading.phase == raps.Phase.ADAPT:
                state.cancel()
                break
            time.sleep(0.001)
        thread.join()
        self.assertEqual(outcome, [raps.Status.CANCELLED])
        reading = state.read()
        self.assertEqual(reading.phase, raps.Phase.ADAPT)  # stopped inside the phase
        self.assertLess(reading.fraction, 0.5)
        self.assertIn(raps.Phase.INITIAL_MAP, seen + [None])
        # Cancelled until reset: a new run stops at its first report.
        with self.assertRaises(raps.Error) as caught:
            raps.parameterize(self.mesh, progress=state)
        self.assertEqual(caught.exception.status, raps.Status.CANCELLED)
        self.assertEqual(state.read().phase, raps.Phase.VALIDATE)
        # Reset, it follows a whole run, whose map is the one without any progress.
        state.reset()
        self.assertEqual(state.read(), (None, 0.0, 0))
        with raps.parameterize(self.mesh, progress=state) as polled, \
                raps.parameterize(self.mesh) as plain:
            self.assertEqual(rows(polled.uvs()), rows(plain.uvs()))
        reading = state.read()
        self.assertEqual((reading.phase, reading.fraction), (raps.Phase.METRICS, 1.0))
        self.assertGreater(reading.reports, 5)
        state.close()

    def test_exception_in_progress_propagates(self):
        class Stop(Exception):
            pass

        def fail(phase, fraction):
            raise Stop()

        with self.assertRaises(Stop):
            raps.parameterize(self.mesh, progress=fail)


class Atlas(unittest.TestCase):
    """The atlas domain on bunny.off, a closed mesh the disk domain refuses."""

    @classmethod
    def setUpClass(cls):
        path = os.path.join(DATA, "meshes", "bunny.off")
        if not os.path.isfile(path):
            raise AssertionError("shared test data missing: %r (set RAPS_SHARED_DATA_DIR)" % path)
        cls.positions, cls.triangles = read_off(path)
        cls.mesh = raps.Mesh(cls.positions, cls.triangles)

    @classmethod
    def tearDownClass(cls):
        cls.mesh.close()

    def run_atlas(self, threads, progress=None):
        with raps.Settings(domain=raps.Domain.ATLAS, threads=threads) as settings:
            self.assertEqual(settings.domain, raps.Domain.ATLAS)
            self.assertEqual(settings.threads, threads)
            return raps.parameterize(self.mesh, settings, progress=progress)

    def test_closed_mesh_becomes_a_valid_atlas(self):
        with self.assertRaises(raps.Error) as caught:
            raps.parameterize(self.mesh)  # the disk domain needs a boundary
        self.assertEqual(caught.exception.status, raps.Status.NO_BOUNDARY)
        with self.run_atlas(threads=1) as result:
            stats = result.stats()
            uvs = rows(result.uvs())
            indices = rows(result.indices())
            remap = list(result.vertex_remap())
            charts = list(result.chart_ids())
        # The input triangles, in input order, over vertices duplicated along seams.
        self.assertEqual(len(indices), len(self.triangles))
        self.assertEqual(stats.triangle_count, len(self.triangles))
        self.assertEqual(stats.vertex_count, len(uvs))
        self.assertEqual(len(remap), len(uvs))
        self.assertGreaterEqual(len(uvs), len(self.positions))
        self.assertTrue(all(0 <= r < len(self.positions) for r in remap))
        for output, triangle in zip(indices, self.triangles):
            self.assertEqual(tuple(remap[i] for i in output), tuple(triangle))
        # One chart id per triangle, below the chart count.
        self.assertEqual(len(charts), len(self.triangles))
        self.assertGreaterEqual(stats.chart_count, 1)
        self.assertTrue(all(0 <= c < stats.chart_count for c in charts))
        for u, v in uvs:
            self.assertTrue(0.0 <= u <= 1.0 and 0.0 <= v <= 1.0, (u, v))
        self.assertEqual(stats.flipped_triangles, 0)
        self.assertGreater(stats.atlas_width, 0)
        self.assertGreater(stats.atlas_height, 0)
        self.assertTrue(0.0 < stats.utilization <= 1.0, stats.utilization)

    def test_threads_do_not_change_the_map(self):
        with self.run_atlas(threads=1) as one, self.run_atlas(threads=2) as two:
            self.assertEqual(rows(one.uvs()), rows(two.uvs()))
            self.assertEqual(list(one.chart_ids()), list(two.chart_ids()))

    def test_progress_reports_the_atlas_phases(self):
        calls = []
        inside = [0]
        overlaps = [0]

        def record(phase, fraction):
            # Chart progress comes from the worker threads: calls must still never overlap.
            inside[0] += 1
            overlaps[0] += inside[0] > 1
            calls.append((phase, fraction))
            time.sleep(0.0005)  # lets another thread run, were it allowed in
            inside[0] -= 1

        with self.run_atlas(threads=2, progress=record) as result:
            self.assertGreater(result.phase_ms(raps.Phase.SEGMENT), 0.0)
            self.assertGreater(result.phase_ms(raps.Phase.PACK), 0.0)
        self.assertEqual(phase_sequence(calls), [
            raps.Phase.VALIDATE, raps.Phase.TOPOLOGY, raps.Phase.SEGMENT,
            raps.Phase.INITIAL_MAP, raps.Phase.PACK, raps.Phase.METRICS])
        self.assertTrue(all(0.0 <= f <= 1.0 for _, f in calls))
        self.assertEqual(overlaps[0], 0)

    def test_exception_from_a_worker_thread_propagates(self):
        # With threads != 1 the atlas reports chart progress from its worker threads too; an
        # exception raised there still cancels the run and is raised by parameterize.
        class Stop(Exception):
            pass

        def fail(phase, fraction):
            if phase == raps.Phase.INITIAL_MAP and fraction > 0.0:
                raise Stop()

        result = raps.Result()
        with raps.Settings(domain="atlas", threads=2) as settings:
            with self.assertRaises(Stop):
                raps.parameterize(self.mesh, settings, progress=fail, result=result)
        self.assertEqual(result.vertex_count, 0)
        result.close()

    def test_atlas_settings(self):
        expected = {"threads": (False, 0, 1024, 0), "atlas_resolution": (False, 16, 16384, 1024),
                    "atlas_padding": (False, 0, 64, 1), "weld_tolerance": (True, 0.0, None, 0.0),
                    "hard_edge_angle": (True, 0.0, 180.0, 180.0),
                    "atlas_max_l2_stretch": (True, 1.0, 10.0, 1.01),
                    "atlas_max_linf_stretch": (True, 1.0, 1000.0, 2.9)}
        with raps.Settings() as settings:
            for name, (is_float, low, high, default) in expected.items():
                info = raps.Settings.param_info(raps.Param[name.upper()])
                self.assertEqual(info.name, name)
                self.assertEqual((info.is_float, info.min, info.default),
                                 (is_float, low, default), name)
                if high is not None:
                    self.assertEqual(info.max, high, name)
                self.assertEqual(getattr(settings, name), default, name)
                self.assertIsInstance(getattr(settings, name), float if is_float else int)
        with raps.Settings(threads=2, atlas_resolution=512, atlas_padding=4,
                           weld_tolerance=1e-6, hard_edge_angle=60.0, atlas_max_l2_stretch=1.5,
                           atlas_max_linf_stretch=4.0) as settings:
            copy = settings.clone()
            self.assertEqual(
                {name: getattr(copy, name) for name in expected},
                {"threads": 2, "atlas_resolution": 512, "atlas_padding": 4,
                 "weld_tolerance": 1e-6, "hard_edge_angle": 60.0, "atlas_max_l2_stretch": 1.5,
                 "atlas_max_linf_stretch": 4.0})
            copy.close()
            for name, bad in (("threads", -1), ("atlas_resolution", 8), ("atlas_padding", 65),
                              ("hard_edge_angle", 181.0), ("atlas_max_l2_stretch", 0.5)):
                with self.assertRaises(raps.Error) as caught:
                    setattr(settings, name, bad)
                self.assertEqual(caught.exception.status, raps.Status.INVALID_ARGUMENT)
            self.assertEqual(settings.atlas_resolution, 512)  # a failed setter changes nothing

    def test_disk_results_have_one_chart(self):
        with raps.Mesh(*read_off(os.path.join(DATA, "meshes", "camelhead.off"))) as mesh, \
                raps.parameterize(mesh) as result:
            stats = result.stats()
            self.assertEqual(stats.chart_count, 1)
            self.assertEqual((stats.atlas_width, stats.atlas_height), (0, 0))
            self.assertEqual(set(result.chart_ids()), {0})
            self.assertEqual(len(result.chart_ids()), result.triangle_count)


class Scene(unittest.TestCase):
    """Several meshes in one atlas (parameterize_scene): an open cap and the icosahedron, the
    cap twice, once scaled by 2."""

    def meshes(self):
        cap, ico = raps.Mesh(*fan_disk()), raps.Mesh(*icosahedron())
        big = raps.Mesh(*fan_disk())
        big.set_transform([[2, 0, 0, 0], [0, 2, 0, 0], [0, 0, 2, 3], [0, 0, 0, 1]])
        return cap, ico, big

    def test_each_mesh_reads_as_its_own_result_at_one_density(self):
        cap, ico, big = self.meshes()
        with raps.Settings(domain="atlas", threads=1, atlas_padding=2) as settings:
            result = raps.parameterize_scene([cap, ico, big], settings)
        self.assertEqual(result.mesh_count, 3)
        remap, indices = list(result.vertex_remap()), rows(result.indices())
        next_vertex = 0
        for m, (mesh, (_, triangles)) in enumerate(zip([cap, ico, big],
                                                       [fan_disk(), icosahedron(), fan_disk()])):
            where = result.mesh_range(m)
            self.assertEqual(where.first_vertex, next_vertex)
            self.assertEqual(where.index_count, 3 * len(triangles))
            own = indices[where.first_index // 3:(where.first_index + where.index_count) // 3]
            for output, triangle in zip(own, triangles):
                self.assertEqual(tuple(remap[where.first_vertex + i] for i in output),
                                 tuple(triangle))
            next_vertex += where.vertex_count
        self.assertEqual(next_vertex, result.vertex_count)
        charts = result.charts()
        self.assertEqual(len(charts), result.stats().chart_count)
        self.assertEqual(sorted({chart.mesh for chart in charts}), [0, 1, 2])
        texels = [sum(c.area_texels for c in charts if c.mesh == m) for m in (0, 2)]
        self.assertAlmostEqual(texels[1] / texels[0], 4.0, delta=0.08)  # scaled by 2
        density = result.stats().texels_per_unit ** 2
        for chart in charts:
            self.assertAlmostEqual(chart.area_texels / chart.area_3d / density, 1.0, delta=0.02)
        for mesh in (cap, ico, big):
            mesh.close()
        result.close()

    def test_pages_at_a_density_and_the_rotation_policy(self):
        cap, ico, big = self.meshes()
        with raps.Settings(domain="atlas", atlas_texels_per_unit=40.0, atlas_max_width=64,
                           atlas_max_height=64, atlas_rotation="none") as settings:
            self.assertEqual(settings.atlas_rotation, raps.Rotation.NONE)
            result = raps.parameterize_scene([cap, ico, big], settings)
        stats = result.stats()
        self.assertGreaterEqual(stats.page_count, 2)
        self.assertLessEqual(max(stats.atlas_width, stats.atlas_height), 64)
        self.assertEqual(stats.texels_per_unit, 40.0)
        for chart in result.charts():
            self.assertLess(chart.page, stats.page_count)
            self.assertEqual(chart.rotation_deg, 0.0)
            self.assertEqual(chart.scaled_down, chart.area_texels < 0.98 * 1600 * chart.area_3d)
        self.assertEqual(sum(c.scaled_down for c in result.charts()), stats.scaled_down_charts)
        for mesh in (cap, ico, big):
            mesh.close()
        result.close()

    def test_bad_scenes_and_transforms_are_refused(self):
        cap, ico, _ = self.meshes()
        with self.assertRaises(raps.Error) as caught:
            cap.set_transform([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0])  # flattens z
        self.assertEqual(caught.exception.status, raps.Status.INVALID_TRANSFORM)
        with self.assertRaises(raps.Error) as caught:
            cap.set_transform([1, 0, 0, float("nan"), 0, 1, 0, 0, 0, 0, 1, 0])
        self.assertEqual(caught.exception.status, raps.Status.INVALID_TRANSFORM)
        with raps.Settings(domain="atlas") as settings:
            with self.assertRaises(raps.Error) as caught:
                raps.parameterize_scene([], settings)
            self.assertEqual(caught.exception.status, raps.Status.EMPTY_MESH)
        with raps.Settings() as disk:
            with self.assertRaises(raps.Error) as caught:
                raps.parameterize_scene([cap, ico], disk)
            self.assertEqual(caught.exception.status, raps.Status.INVALID_ARGUMENT)
            self.assertIn("RAPS_DOMAIN_ATLAS", str(caught.exception))
        cap.close()
        ico.close()


class Seams(unittest.TestCase):
    """The artist's seams in an atlas: triangle groups and seam edges on the hexagonal cap."""

    def test_groups_split_charts_and_bad_seams_are_refused(self):
        with raps.Mesh(*fan_disk()) as cap, raps.Settings(domain="atlas") as settings:
            self.assertEqual(raps.parameterize(cap, settings).stats().chart_count, 1)
            cap.set_triangle_groups([0, 0, 0, 1, 1, 1])
            charts = raps.parameterize(cap, settings).chart_ids()
            self.assertEqual(len(set(list(charts)[:3]) & set(list(charts)[3:])), 0)
            cap.set_triangle_groups([0, 1])
            with self.assertRaises(raps.Error) as caught:
                raps.parameterize(cap, settings)
            self.assertEqual(caught.exception.status, raps.Status.GROUP_COUNT)
            cap.set_triangle_groups(None)
            cap.set_seam_edges([(0, 1), (0, 4)])  # rim to rim through the apex: two halves
            self.assertEqual(raps.parameterize(cap, settings).stats().chart_count, 2)
            cap.set_seam_edges([(1, 3)])
            with self.assertRaises(raps.Error) as caught:
                raps.parameterize(cap, settings)
            self.assertEqual(caught.exception.status, raps.Status.SEAM_NOT_AN_EDGE)
            self.assertIn("seam edge 0 (1, 3)", str(caught.exception))
            cap.set_seam_edges([0, 9])
            with self.assertRaises(raps.Error) as caught:
                raps.parameterize(cap, settings)
            self.assertEqual(caught.exception.status, raps.Status.INDEX_OUT_OF_RANGE)
            settings.atlas_keep_input_seams = 1
            self.assertEqual(settings.atlas_keep_input_seams, 1)

    def test_polygons_reach_the_library(self):
        # What they do is the C suite's (test_atlas_polygons); here: a numpy array or a list
        # gets there, and a wrong count is refused when the mesh is used.
        with raps.Mesh(*fan_disk()) as cap, raps.Settings(domain="atlas") as settings:
            polygons = [0, 0, 1, 1, 2, 2]  # the cap's six triangles as three quads
            if raps.numpy is not None:
                polygons = raps.numpy.array(polygons, dtype=raps.numpy.int64)
            cap.set_triangle_polygons(polygons)
            self.assertEqual(len(raps.parameterize(cap, settings).chart_ids()), 6)
            cap.set_triangle_polygons([0, 1])
            with self.assertRaises(raps.Error) as caught:
                raps.parameterize(cap, settings)
            self.assertEqual(caught.exception.status, raps.Status.GROUP_COUNT)
            self.assertIn("polygons number 2", str(caught.exception))
            with self.assertRaises(ValueError):
                cap.set_triangle_polygons([-1])
            cap.set_triangle_polygons(None)
            self.assertEqual(raps.parameterize(cap, settings).stats().chart_count, 1)


class Repack(unittest.TestCase):
    """Existing uvs repacked (atlas_repack): the islands of a hexagonal cap's corner uvs come
    back as charts, each only moved, turned and uniformly scaled; bad uvs are refused."""

    def corner_uvs(self):
        # Two islands: triangles 0-2 as the cap lies (x, y), triangles 3-5 mirrored and moved.
        positions, indices = fan_disk()
        corners = []
        for t, triangle in enumerate(indices):
            for v in triangle:
                x, y = positions[v][0], positions[v][1]
                corners.append((x, y) if t < 3 else (5.0 - 2.0 * x, 2.0 * y))
        return corners

    def test_islands_keep_their_shape(self):
        corners = self.corner_uvs()
        source = numpy.array(corners, dtype=numpy.float32) if numpy is not None else corners
        with raps.Mesh(*fan_disk()) as cap, \
                raps.Settings(domain="atlas", atlas_repack=1, threads=1) as settings:
            cap.set_corner_uvs(source)
            self.assertEqual(settings.atlas_repack, 1)
            result = raps.parameterize(cap, settings)
            stats = result.stats()
            self.assertEqual((stats.chart_count, stats.flipped_triangles), (2, 3))
            uv = [tuple(p) for p in result.uvs()]
            texel = [complex(u * stats.atlas_width, v * stats.atlas_height) for u, v in uv]
            ids = list(result.chart_ids())
            indices = [tuple(t) for t in result.indices()]
            for chart in set(ids):
                pairs = [(complex(*corners[3 * t + k]), texel[indices[t][k]])
                         for t in range(6) if ids[t] == chart for k in range(3)]
                a0, b0 = pairs[0]
                a1, b1 = max(pairs, key=lambda p: abs(p[0] - a0))
                z = (b1 - b0) / (a1 - a0)
                for a, b in pairs:
                    self.assertLess(abs(b - (b0 + z * (a - a0))), 1e-3 * abs(b1 - b0))
            densities = [c.area_texels / c.area_3d for c in result.charts()]
            self.assertAlmostEqual(densities[0] / densities[1], 1.0, places=6)

    def test_bad_uvs_are_refused(self):
        with raps.Mesh(*fan_disk()) as cap, raps.Settings(domain="atlas", atlas_repack=1) as s:
            with self.assertRaises(raps.Error) as caught:
                raps.parameterize(cap, s)
            self.assertEqual(caught.exception.status, raps.Status.UV_COUNT)
            corners = self.corner_uvs()
            corners[4] = (float("nan"), 0.0)
            with self.assertRaises(raps.Error) as caught:
                cap.set_corner_uvs(corners)
            self.assertEqual(caught.exception.status, raps.Status.NON_FINITE_UV)
            self.assertIn("corner 4", str(caught.exception))
            flat = [(0.0, 0.0)] * 18  # every island a point: no uv area
            cap.set_corner_uvs(flat)
            with self.assertRaises(raps.Error) as caught:
                raps.parameterize(cap, s)
            self.assertEqual(caught.exception.status, raps.Status.DEGENERATE_UV_CHART)
            cap.set_corner_uvs(None)
            with self.assertRaises(raps.Error) as caught:
                raps.parameterize(cap, s)
            self.assertEqual(caught.exception.status, raps.Status.UV_COUNT)


class Stack(unittest.TestCase):
    """Stacking: the cap given twice to a scene (the copy moved) costs no texels: every chart of
    the copy is stacked on the original's and has its uvs, corner for corner."""

    def test_a_repeated_mesh_shares_its_originals_texels(self):
        with raps.Mesh(*fan_disk()) as cap, raps.Mesh(*fan_disk()) as copy, \
                raps.Settings(domain="atlas", atlas_stack="rigid") as settings:
            self.assertEqual(settings.atlas_stack, raps.Stacking.RIGID)
            copy.set_transform([[0, -1, 0, 4], [1, 0, 0, 0], [0, 0, 1, 0]])
            scene = raps.parameterize_scene([cap, copy], settings)
            charts = scene.charts()
            self.assertEqual(sum(1 for c in charts if c.stacked), len(charts) // 2)
            for index, chart in enumerate(charts):
                self.assertEqual(chart.stacked, chart.mesh == 1)
                self.assertEqual(chart.stacked_on != index, chart.stacked)
            uv = [tuple(p) for p in scene.uvs()]
            first, second = scene.mesh_range(0), scene.mesh_range(1)
            indices = [v for t in scene.indices() for v in t]
            own = [uv[first.first_vertex + v] for v in indices[:18]]
            copied = [uv[second.first_vertex + v] for v in indices[18:]]
            self.assertEqual(own, copied)
            settings.atlas_stack = raps.Stacking.MIRRORED
            settings.atlas_stack_tolerance = 0.01
            self.assertEqual(settings.atlas_stack_tolerance, 0.01)


class Sphere(unittest.TestCase):
    """The sphere domain on a built icosahedron and on bunny.off, closed genus-0 meshes."""

    @classmethod
    def setUpClass(cls):
        path = os.path.join(DATA, "meshes", "bunny.off")
        if not os.path.isfile(path):
            raise AssertionError("shared test data missing: %r (set RAPS_SHARED_DATA_DIR)" % path)
        cls.bunny = read_off(path)

    def check_sphere_map(self, result, positions, triangles):
        """One unit point (x, y, z) per input vertex, every input triangle counter-clockwise
        seen from outside on them, the input triangles and an identity remap; the stats."""
        points = rows(result.sphere_points())
        self.assertEqual(len(points), len(positions))
        for i, p in enumerate(points):
            self.assertAlmostEqual(math.sqrt(sum(c * c for c in p)), 1.0, delta=1e-9, msg=i)
        for t, (a, b, c) in enumerate(triangles):
            self.assertGreater(det(points[a], points[b], points[c]), 0.0, "triangle %d" % t)
        for single, double in zip(rows(result.sphere_points("float32")), points):
            for x, y in zip(single, double):
                self.assertAlmostEqual(x, y, delta=1e-6)
        stats = result.stats()
        self.assertEqual(stats.flipped_triangles, 0)
        self.assertGreater(stats.relaxation_sweeps, 0)
        self.assertEqual(stats.vertex_count, len(positions))
        self.assertEqual(stats.chart_count, 1)
        self.assertEqual(stats.utilization, 0.0)  # no uvs, no uv area
        self.assertEqual(rows(result.indices()), [tuple(t) for t in triangles])
        self.assertEqual(list(result.vertex_remap()), list(range(len(positions))))
        return stats

    def test_icosahedron_maps_onto_the_unit_sphere(self):
        positions, triangles = icosahedron()
        with raps.Mesh(positions, triangles) as mesh, \
                raps.Settings(domain=raps.Domain.SPHERE) as settings:
            self.assertEqual(settings.sphere_method, raps.SphereMethod.ROBUST)
            self.assertEqual(settings.sphere_uv, raps.SphereUv.NONE)
            result = raps.parameterize(mesh, settings)
        stats = self.check_sphere_map(result, positions, triangles)
        # The area monitor's iteration reached through 2 relaxations (sphere_alpha_steps).
        self.assertEqual(stats.adaptive_solves, 2)
        if numpy is not None:
            points = result.sphere_points()
            self.assertEqual((points.shape, points.dtype), ((12, 3), numpy.float64))
            self.assertEqual(result.sphere_points("float32").dtype, numpy.float32)
        # Without the octahedral unfold a sphere map has no uvs, and says so.
        for dtype in ("float64", "float32"):
            with self.assertRaises(raps.Error) as caught:
                result.uvs(dtype)
            self.assertEqual(caught.exception.status, raps.Status.INVALID_OPERATION)
            self.assertIn("OCTAHEDRAL", caught.exception.message)
            self.assertIn("sphere_points", caught.exception.message)
        result.close()

    def test_literal_method_keeps_the_icosahedrons_gauss_map(self):
        # Its Gauss map, which the symmetric icosahedron keeps: vertex i's point is its
        # position normalised, x, y, z in that order.
        positions, triangles = icosahedron()
        with raps.Mesh(positions, triangles) as mesh, \
                raps.Settings(domain="sphere", sphere_method="literal", monitor="none") as s, \
                raps.parameterize(mesh, s) as result:
            self.check_sphere_map(result, positions, triangles)
            for point, position in zip(rows(result.sphere_points()), positions):
                norm = math.sqrt(sum(c * c for c in position))
                for x, y in zip(point, position):
                    self.assertAlmostEqual(x, y / norm, delta=1e-9)

    def test_shared_mesh_maps_bijectively_and_equidistributes_area(self):
        positions, triangles = self.bunny
        with raps.Mesh(positions, triangles) as mesh, \
                raps.Settings(domain=raps.Domain.SPHERE, monitor=raps.Monitor.NONE) as plain, \
                raps.Settings(domain=raps.Domain.SPHERE) as adaptive, \
                raps.Settings(domain=raps.Domain.SPHERE, sphere_max_sweeps=3,
                              sphere_alpha_steps=2) as capped:
            first = raps.parameterize(mesh, plain)
            second = raps.parameterize(mesh, adaptive)
            before = self.check_sphere_map(first, positions, triangles)
            after = self.check_sphere_map(second, positions, triangles)
            self.assertEqual(before.adaptive_solves, 0)
            # Spherical area distortion, measured in tests/test_sphere.c: 1.638 -> 0.667.
            self.assertLess(after.area_log_mean, 0.5 * before.area_log_mean)
            self.assertGreater(second.phase_ms(raps.Phase.ADAPT), 0.0)
            # sphere_max_sweeps and sphere_alpha_steps reach the library: 2 adaptive
            # relaxations, at most 3 sweeps in each of the 3 relaxations.
            with raps.parameterize(mesh, capped) as result:
                stats = result.stats()
            self.assertEqual(stats.adaptive_solves, 2)
            self.assertTrue(0 < stats.relaxation_sweeps <= 9, stats.relaxation_sweeps)
            self.assertGreater(after.relaxation_sweeps, 9)
            first.close()
            second.close()

    def test_octahedral_unfold_gives_one_chart_in_the_square(self):
        for positions, triangles in (icosahedron(), self.bunny):
            n = len(positions)
            with raps.Mesh(positions, triangles) as mesh, \
                    raps.Settings(domain="sphere") as plain, \
                    raps.Settings(domain="sphere", sphere_uv=raps.SphereUv.OCTAHEDRAL) as s, \
                    raps.parameterize(mesh, plain) as sphere, \
                    raps.parameterize(mesh, s) as result:
                self.assertEqual(s.sphere_uv, raps.SphereUv.OCTAHEDRAL)
                count = result.vertex_count
                # The cut's vertices are duplicated: more output vertices than input.
                self.assertGreater(count, n)
                uvs = rows(result.uvs())
                remap = list(result.vertex_remap())
                indices = rows(result.indices())
                points = rows(result.sphere_points())
                original = rows(sphere.sphere_points())
                stats = result.stats()
            self.assertEqual((len(uvs), len(remap), len(points)), (count, count, count))
            for u, v in uvs:
                self.assertTrue(0.0 <= u <= 1.0 and 0.0 <= v <= 1.0, (u, v))
            self.assertEqual(len(indices), len(triangles))
            for output, triangle in zip(indices, triangles):
                self.assertEqual(tuple(remap[i] for i in output), tuple(triangle))
            for a, b, c in indices:
                self.assertGreater(signed_area(uvs[a], uvs[b], uvs[c]), 0.0)
            for o, r in enumerate(remap):
                self.assertEqual(points[o], original[r], o)
            self.assertEqual(stats.flipped_triangles, 0)
            self.assertEqual(stats.vertex_count, count)
            self.assertEqual(stats.chart_count, 1)
            self.assertGreater(stats.relaxation_sweeps, 0)
            self.assertTrue(0.0 < stats.utilization <= 1.0, stats.utilization)

    def test_open_mesh_is_refused_with_its_boundary_counted(self):
        result = raps.Result()
        with raps.Mesh(*fan_disk()) as mesh, raps.Settings(domain=raps.Domain.SPHERE) as s:
            with self.assertRaises(raps.Error) as caught:
                raps.parameterize(mesh, s, result=result)
            error = caught.exception
            self.assertEqual(error.status, raps.Status.OPEN_MESH)
            self.assertIsInstance(error.status, raps.Status)
            self.assertIn("closed mesh", error.message)
            self.assertIn("1 boundary loop", error.message)
            self.assertTrue(error.name)
            self.assertNotEqual(error.name, "unknown status")
            self.assertIn(error.name, str(error))
            self.assertEqual(result.vertex_count, 0)
            with self.assertRaises(raps.Error) as caught:
                result.sphere_points()
            self.assertEqual(caught.exception.status, raps.Status.INVALID_OPERATION)
            # The disk domain maps the same mesh; its result has uvs but no sphere points.
            raps.parameterize(mesh, result=result)
            with self.assertRaises(raps.Error) as caught:
                result.sphere_points()
            self.assertEqual(caught.exception.status, raps.Status.INVALID_OPERATION)
            self.assertIn("sphere points", caught.exception.message)
        result.close()

    def test_progress_reports_the_sphere_phases_and_cancels(self):
        calls = []
        inside = [0]
        overlaps = [0]

        def record(phase, fraction):
            inside[0] += 1
            overlaps[0] += inside[0] > 1
            calls.append((phase, fraction))
            time.sleep(0.0005)  # lets another thread run, were it allowed in
            inside[0] -= 1

        with raps.Mesh(*self.bunny) as mesh, \
                raps.Settings(domain=raps.Domain.SPHERE, threads=2) as settings:
            raps.parameterize(mesh, settings, progress=record).close()
            # The disk domain's five phases: the initial map and its relaxation, then the
            # adaptive relaxations.
            self.assertEqual(phase_sequence(calls), [
                raps.Phase.VALIDATE, raps.Phase.TOPOLOGY, raps.Phase.INITIAL_MAP,
                raps.Phase.ADAPT, raps.Phase.METRICS])
            self.assertTrue(all(0.0 <= f <= 1.0 for _, f in calls))
            self.assertEqual(overlaps[0], 0)
            result = raps.Result()
            with self.assertRaises(raps.Error) as caught:
                raps.parameterize(mesh, settings, progress=lambda p, f: p < raps.Phase.ADAPT,
                                  result=result)
            self.assertEqual(caught.exception.status, raps.Status.CANCELLED)
            self.assertEqual(result.vertex_count, 0)
            raps.parameterize(mesh, settings, result=result)
            self.assertEqual(result.vertex_count, len(self.bunny[0]))
            result.close()

    def test_sphere_settings(self):
        # As raps_param_info reports them (src/c_api.cpp); (0, 1] has the smallest normal
        # double as its lower bound.
        expected = {"sphere_method": (False, 0, 1, 1), "sphere_uv": (False, 0, 1, 0),
                    "sphere_damping": (True, sys.float_info.min, 1.0, 1.0),
                    "sphere_tolerance": (True, 1e-12, 1.0, 1e-4),
                    "sphere_max_sweeps": (False, 0, 10000000, 0),
                    "sphere_alpha_steps": (False, 1, 100, 2)}
        with raps.Settings() as settings:
            for name, (is_float, low, high, default) in expected.items():
                info = raps.Settings.param_info(raps.Param[name.upper()])
                self.assertEqual(info, (name, is_float, low, high, default))
                self.assertEqual(getattr(settings, name), default, name)
                self.assertIsInstance(getattr(settings, name), float if is_float else int)
            self.assertIs(settings.sphere_method, raps.SphereMethod.ROBUST)
            self.assertIs(settings.sphere_uv, raps.SphereUv.NONE)
        domain = raps.Settings.param_info(raps.Param.DOMAIN)
        self.assertEqual((domain.min, domain.max), (raps.Domain.DISK, raps.Domain.ATLAS))
        self.assertTrue(raps.Domain.DISK < raps.Domain.SPHERE < raps.Domain.ATLAS)
        self.assertEqual({m.name for m in raps.SphereMethod}, {"LITERAL", "ROBUST"})
        self.assertEqual({m.name for m in raps.SphereUv}, {"NONE", "OCTAHEDRAL"})
        with raps.Settings(domain="sphere", sphere_method="literal", sphere_uv="octahedral",
                           sphere_damping=0.5, sphere_tolerance=1e-6,
                           sphere_max_sweeps=10000000, sphere_alpha_steps=100) as settings:
            copy = settings.clone()
            self.assertEqual(
                {name: getattr(copy, name) for name in expected},
                {"sphere_method": raps.SphereMethod.LITERAL,
                 "sphere_uv": raps.SphereUv.OCTAHEDRAL, "sphere_damping": 0.5,
                 "sphere_tolerance": 1e-6, "sphere_max_sweeps": 10000000,
                 "sphere_alpha_steps": 100})
            self.assertEqual(copy.domain, raps.Domain.SPHERE)
            copy.close()
            for name, bad in (("sphere_method", 2), ("sphere_uv", 2), ("sphere_damping", 0.0),
                              ("sphere_damping", 1.5), ("sphere_tolerance", 1e-13),
                              ("sphere_tolerance", 2.0), ("sphere_max_sweeps", -1),
                              ("sphere_max_sweeps", 10000001), ("sphere_alpha_steps", 0),
                              ("sphere_alpha_steps", 101)):
                with self.assertRaises(raps.Error) as caught:
                    setattr(settings, name, bad)
                self.assertEqual(caught.exception.status, raps.Status.INVALID_ARGUMENT)
                self.assertIn(name, caught.exception.message)
            with self.assertRaises(ValueError) as caught:
                settings.sphere_uv = "cube"  # not a member's name
            self.assertIn("'octahedral'", str(caught.exception))
            # A failed setter changes nothing.
            self.assertEqual(settings.sphere_method, raps.SphereMethod.LITERAL)
            self.assertEqual(settings.sphere_damping, 0.5)
            self.assertEqual(settings.sphere_alpha_steps, 100)


class Errors(unittest.TestCase):
    def test_closed_mesh_has_no_boundary(self):
        positions, triangles = icosahedron()
        with raps.Mesh(positions, triangles) as mesh:
            with self.assertRaises(raps.Error) as caught:
                raps.parameterize(mesh)
        error = caught.exception
        self.assertEqual(error.status, raps.Status.NO_BOUNDARY)
        self.assertTrue(error.name)
        self.assertNotEqual(error.name, "unknown status")
        self.assertTrue(error.message)
        self.assertIn(error.name, str(error))
        self.assertIn(error.message, str(error))

    def test_index_out_of_range_names_the_triangle(self):
        positions, triangles = icosahedron()
        triangles[3] = (0, 7, 12)
        with raps.Mesh(positions, triangles) as mesh:
            with self.assertRaises(raps.Error) as caught:
                raps.parameterize(mesh)
        self.assertEqual(caught.exception.status, raps.Status.INDEX_OUT_OF_RANGE)
        self.assertIn("12", caught.exception.message)

    def test_setter_errors_carry_the_mesh_message(self):
        with raps.Mesh() as mesh:
            with self.assertRaises(raps.Error) as caught:
                mesh.set_indices([0, 1, 2, 3])
            self.assertEqual(caught.exception.status, raps.Status.INDEX_COUNT)
            self.assertTrue(caught.exception.message)
            with self.assertRaises(raps.Error) as caught:
                mesh.set_positions([(0.0, float("nan"), 0.0)])
            self.assertEqual(caught.exception.status, raps.Status.NON_FINITE_POSITION)
            self.assertEqual(mesh.vertex_count, 0)  # a failed setter changes nothing
            with self.assertRaises(ValueError):
                mesh.set_indices([0, -1, 2])
            with self.assertRaises(ValueError):
                mesh.set_positions([0.0, 1.0])

    def test_settings_reject_bad_values_and_stay_unchanged(self):
        with raps.Settings(alpha=2.0) as settings:
            with self.assertRaises(raps.Error) as caught:
                settings.alpha = -1.0
            self.assertEqual(caught.exception.status, raps.Status.INVALID_ARGUMENT)
            self.assertIn("alpha", caught.exception.message)
            self.assertEqual(settings.alpha, 2.0)
            with self.assertRaises(raps.Error):
                settings.iterations = 0
            self.assertEqual(settings.iterations, 1)
            # Past 64 bits ctypes would wrap: 2**64 + 5 became 5, silently.
            for value in (2**64 + 5, -2**63 - 1):
                with self.assertRaises(ValueError) as caught:
                    settings.iterations = value
                self.assertIn("iterations", str(caught.exception))
            self.assertEqual(settings.iterations, 1)
        with self.assertRaises(TypeError):
            raps.Settings(no_such_parameter=1)

    def test_ids_and_indices_are_integers_in_range(self):
        mesh = raps.Mesh([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [(0, 1, 2)])
        fractions = [[1.5]] + ([numpy.full(1, 1.5)] if numpy is not None else [])
        for groups in fractions:  # 1.5 and 1.7 would be one group
            with self.assertRaises(TypeError):
                mesh.set_triangle_groups(groups)
        mesh.set_triangle_groups([7] if numpy is None else numpy.array([7], dtype=numpy.int64))
        with raps.Result() as result:
            with self.assertRaises(ValueError):
                result.mesh_range(2**64)  # once read as mesh 0
            with self.assertRaises(ValueError):
                result.phase_ms(2**32 + 2)  # once read as phase 2

    def test_index_arrays_are_rows_of_three(self):
        # A (t, 4) array was read as 4t/3 triangles, and 1.5 as index 1.
        with raps.Mesh([(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)], [(0, 1, 2)]) as mesh:
            quads = [(0, 1, 3, 2), (0, 1, 3, 2), (0, 1, 3, 2)]
            cases = [(quads, ValueError, "3 values"), ([0, 1.5, 2], TypeError, "an index")]
            if numpy is not None:
                cases = [(numpy.array(quads), ValueError, "indices must have shape (t, 3)"),
                         (numpy.array([[0, 1], [2, 1], [3, 2]]), ValueError, "(3, 2)"),
                         (numpy.zeros((1, 3, 1), dtype=numpy.int32), ValueError, "(t, 3)")] + cases
            for indices, error, words in cases:
                with self.assertRaises(error) as caught:
                    mesh.set_indices(indices)
                self.assertIn(words, str(caught.exception))
                self.assertEqual(mesh.triangle_count, 1)  # unchanged
            pairs = [[(0, 1, 2), (2, 3, 1)], [0, 1, 2]]  # so were seam edges of three columns
            if numpy is not None:
                pairs += [numpy.array(pairs[0]), numpy.array(pairs[1])]
            for edges in pairs:
                with self.assertRaises(ValueError) as caught:
                    mesh.set_seam_edges(edges)
                self.assertIn("seam edges", str(caught.exception))
            # Flat and (t, 3) input stay accepted; a flat count not a multiple of 3 stays the
            # library's INDEX_COUNT (test_setter_errors_carry_the_mesh_message).
            flat = [0, 1, 3, 0, 3, 2]
            for indices in [flat, [flat[:3], flat[3:]]] + (
                    [numpy.array(flat), numpy.array(flat, dtype=numpy.uint16).reshape(2, 3)]
                    if numpy is not None else []):
                mesh.set_indices(indices)
                self.assertEqual(mesh.triangle_count, 2)
                mesh.set_indices([0, 1, 2])

    def test_result_dtypes_are_float32_or_float64(self):
        with raps.Mesh(*fan_disk()) as cap, raps.parameterize(cap) as result:
            # Any other dtype returned float64 under its name.
            bad = ["int32", "float16", "single", ctypes.c_int]
            if numpy is not None:
                bad += [numpy.int32, numpy.dtype("float16")]
            for dtype in bad:
                for read in (result.uvs, result.sphere_points):
                    with self.assertRaises(ValueError) as caught:
                        read(dtype=dtype)
                    self.assertIn("dtype", str(caught.exception))
                    self.assertIn("float32 or float64", str(caught.exception))
            single = ["float32", ctypes.c_float] + (
                [numpy.float32, numpy.dtype("float32")] if numpy is not None else [])
            double = ["float64", float, ctypes.c_double] + (
                [numpy.float64, numpy.dtype("float64")] if numpy is not None else [])
            for dtypes, expected in ((single, "float32"), (double, "float64")):
                for dtype in dtypes:
                    uvs = result.uvs(dtype=dtype)
                    self.assertEqual(len(uvs), 7)
                    if numpy is not None:
                        self.assertEqual(uvs.dtype, numpy.dtype(expected))

    def test_complex_numbers_are_refused(self):
        # numpy and ctypes took a complex number's real part, with at most a warning.
        with raps.Mesh(*fan_disk()) as cap, raps.Settings(alpha=2.0) as settings:
            positions = [(0.0, 0.0, 1j), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)]
            calls = [(lambda: cap.set_positions(positions), "positions"),
                     (lambda: cap.set_positions([c for p in positions for c in p]), "positions"),
                     (lambda: cap.set_corner_uvs([(0.0, 1j)] * 18), "corner uvs"),
                     (lambda: cap.set_transform([[1j, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]),
                      "transform"),
                     (lambda: settings.set(raps.Param.ALPHA, 1j), "alpha"),
                     (lambda: settings.set(raps.Param.ITERATIONS, 3j), "iterations")]
            if numpy is not None:
                calls += [
                    (lambda: cap.set_positions(numpy.array(positions)), "positions"),
                    (lambda: cap.set_positions([numpy.complex64(2 + 1j), 0.0, 0.0]), "positions"),
                    (lambda: cap.set_corner_uvs(numpy.zeros((18, 2), dtype=numpy.complex64)),
                     "corner uvs"),
                    (lambda: cap.set_transform(numpy.eye(4, dtype=complex)), "transform"),
                    (lambda: settings.set(raps.Param.ALPHA, numpy.complex128(3 + 1j)), "alpha"),
                    (lambda: settings.set(raps.Param.ITERATIONS, numpy.complex128(3)),
                     "iterations")]
            for call, words in calls:
                with self.assertRaises(TypeError) as caught:
                    call()
                self.assertIn(words, str(caught.exception))
                self.assertIn("real", str(caught.exception))
            self.assertEqual(cap.vertex_count, 7)  # unchanged
            self.assertEqual((settings.alpha, settings.iterations), (2.0, 1))

    def test_unknown_parameter_ids_are_named(self):
        with raps.Settings(iterations=3) as settings:
            before = settings.as_dict()
            for call in (lambda: settings.set(999, 1), lambda: settings.get(999),
                         lambda: raps.Settings.param_info(999)):
                with self.assertRaises(raps.Error) as caught:
                    call()
                self.assertEqual(caught.exception.status, raps.Status.INVALID_ARGUMENT)
                self.assertIn("unknown parameter id 999", str(caught.exception))
            # ctypes wrapped 2**32 + 2 to parameter 2 and truncated 1.5 to parameter 1.
            with self.assertRaises(ValueError) as caught:
                settings.set(2**32 + int(raps.Param.ITERATIONS), 5)
            self.assertIn("parameter id", str(caught.exception))
            with self.assertRaises(TypeError) as caught:
                settings.set(int(raps.Param.ITERATIONS) + 0.5, 5)
            self.assertIn("parameter id", str(caught.exception))
            self.assertEqual(settings.as_dict(), before)

    def test_unknown_enumerated_names_list_the_known_ones(self):
        with self.assertRaises(ValueError) as caught:
            raps.Settings(domain="bogus")
        for words in ("domain", "'bogus'", "'disk'", "'sphere'", "'atlas'"):
            self.assertIn(words, str(caught.exception))
        with raps.Settings(monitor="angle") as settings:
            for name, value in (("monitor", "bogus"), ("atlas_stack", "stacked")):
                with self.assertRaises(ValueError) as caught:
                    setattr(settings, name, value)
                self.assertIn(name, str(caught.exception))
                self.assertIn("'none'", str(caught.exception))
            with self.assertRaises(ValueError) as caught:
                settings.set(raps.Param.MONITOR, "bogus")  # was int("bogus")'s message
            self.assertIn("'area'", str(caught.exception))
            self.assertEqual(settings.monitor, raps.Monitor.ANGLE)  # unchanged
            settings.set(raps.Param.DOMAIN, "atlas")  # names work here too, as in properties
            self.assertEqual(settings.domain, raps.Domain.ATLAS)

    def test_empty_result_cannot_be_read(self):
        with raps.Result() as result:
            for read in (result.uvs, result.indices, result.vertex_remap, result.chart_ids,
                         result.stats):
                with self.assertRaises(raps.Error) as caught:
                    read()
                self.assertEqual(caught.exception.status, raps.Status.INVALID_OPERATION)


class Handles(unittest.TestCase):
    def test_close_twice_and_use_after_close(self):
        for make in (raps.Mesh, raps.Settings, raps.Result):
            handle = make()
            handle.close()
            handle.close()  # no double free
            self.assertTrue(handle.closed)
        with self.assertRaises(ValueError):
            handle.vertex_count
        mesh = raps.Mesh()
        mesh.close()
        with self.assertRaises(ValueError):
            raps.parameterize(mesh)

    def test_collected_without_close(self):
        # Many handles left to the collector: each destroyed once (a double free or a leak of
        # this size would show under ASan or valgrind; here it must at least not crash).
        for _ in range(2000):
            raps.Mesh([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [(0, 1, 2)])
            raps.Settings(alpha=3.0).clone()
        gc.collect()

    def test_settings_properties_and_clone(self):
        settings = raps.Settings(weights="uniform", monitor=raps.Monitor.ANGLE, iterations=3,
                                 iteration_mode=raps.IterationMode.REAPPLY, boundary="square")
        copy = settings.clone()
        settings.iterations = 7
        self.assertEqual(copy.iterations, 3)
        self.assertEqual(copy.weights, raps.Weights.UNIFORM)
        self.assertEqual(copy.boundary, raps.Boundary.SQUARE)
        self.assertEqual(copy.iteration_mode, raps.IterationMode.REAPPLY)
        self.assertEqual(settings.as_dict()["iterations"], 7)
        info = raps.Settings.param_info(raps.Param.ALPHA)
        self.assertEqual(info.name, "alpha")
        self.assertTrue(info.is_float)
        self.assertEqual(info.default, 1.0)
        self.assertEqual(copy.domain, raps.Domain.DISK)
        settings.close()
        copy.close()

    def test_version(self):
        self.assertEqual(raps.version()[0], 0)
        self.assertEqual(raps.version_string(), "%d.%d.%d" % raps.version())

    def test_plain_lists_are_accepted(self):
        # Sequences in either shape, also when numpy is present.
        ring = [(math.cos(k * math.pi / 3), math.sin(k * math.pi / 3), 0.0) for k in range(6)]
        flat = [c for p in [(0.0, 0.0, 0.5)] + ring for c in p]
        triangles = [i for k in range(6) for i in (0, 1 + k, 1 + (k + 1) % 6)]
        with raps.Mesh(flat, triangles) as mesh:
            uvs = rows(raps.parameterize(mesh).uvs())
        self.assertAlmostEqual(uvs[0][0], 0.5, delta=1e-12)
        self.assertAlmostEqual(uvs[0][1], 0.5, delta=1e-12)

    def test_found_through_the_loader_path_too(self):
        # Without RAPS_LIBRARY, the module asks the dynamic loader (LD_LIBRARY_PATH here).
        env = dict(os.environ)
        folder = os.path.dirname(os.path.abspath(raps.library_path))
        env.pop("RAPS_LIBRARY", None)
        env["LD_LIBRARY_PATH"] = folder
        code = "import raps; print(raps.library_path, raps.version_string())"
        output = subprocess.run([sys.executable, "-c", code], env=env, check=True,
                                cwd=os.path.join(os.path.dirname(__file__), ".."),
                                stdout=subprocess.PIPE, universal_newlines=True).stdout
        self.assertIn(raps.version_string(), output)
        # And an explicit RAPS_LIBRARY that does not load is an error, not a fallback.
        env["RAPS_LIBRARY"] = os.path.join(folder, "no-such-libraps.so")
        failed = subprocess.run([sys.executable, "-c", code], env=env,
                                cwd=os.path.join(os.path.dirname(__file__), ".."),
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        self.assertNotEqual(failed.returncode, 0)
        self.assertIn(b"no-such-libraps.so", failed.stderr)

    def test_installed_package_carries_its_library(self):
        package = os.path.dirname(os.path.abspath(raps.__file__))
        source_tree = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "raps")
        if INSTALLED:
            self.assertNotIn("RAPS_LIBRARY", os.environ)
            self.assertNotEqual(package, os.path.realpath(source_tree))
            self.assertEqual(raps.library_path, os.path.join(package, "libraps.so"))
        else:
            self.assertEqual(package, os.path.realpath(source_tree))

    def test_numpy_is_used_when_present(self):
        with raps.Mesh(*icosahedron()[:1], [(0, 11, 5), (0, 5, 1), (0, 1, 7)]) as mesh:
            self.assertEqual(mesh.triangle_count, 3)
        if os.environ.get("RAPS_TEST_WITHOUT_NUMPY") == "1":
            self.assertIsNone(raps.numpy)
        else:
            self.assertIsNotNone(raps.numpy)


if numpy is None:
    # Without numpy there are no arrays to give: the plain run has no such test (not a skip).
    del SharedMesh.test_numpy_strided_and_u16_inputs

if __name__ == "__main__":
    unittest.main()
