"""The add-on's own cost against the library's, in one Blender process (docs/blender.md).

  blender -b --factory-startup --python bench/blender_addon_overhead.py -- \
      --zip build/bindings/blender/raps_uv.zip --meshes ../shared/data/meshes \
      [--repeat 15] [--lightmap-pack-max-faces 7000] [suzanne.obj halftunnel.off ...]

For each mesh (a fresh object per call, as bench/blender_unwrappers.py makes them) and the
lightmap preset: the operator's call (bpy.ops.raps.lightmap, headless: no progress callback),
the library's run alone on the same arrays (raps.parameterize with the preset's settings, the
mesh handle made outside the timing), that run with a Python progress callback that does
nothing (what the menu's path, with its progress bar and Esc, cost per call until it polled a
progress state), and with a raps.ProgressState (what the menu's path adds now); and Blender's
Lightmap Pack on the same mesh (its call alone, in edit mode, all faces selected; only on meshes
of at most --lightmap-pack-max-faces faces, as in bench/blender_unwrappers.py). Prints
medians of wall-clock and process CPU milliseconds (CPU: every thread of Blender's process, so
that other jobs on a loaded machine count less), and the number of progress calls; first, the
time enabling the add-on took.
"""

import argparse
import os
import statistics
import sys
import time

import bpy

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))


def _arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser()
    parser.add_argument("--zip", required=True)
    parser.add_argument("--meshes", required=True)
    parser.add_argument("--repeat", type=int, default=15)
    parser.add_argument("--lightmap-pack-max-faces", type=int, default=7000)
    parser.add_argument("names", nargs="*",
                        default=["suzanne.obj", "halftunnel.off", "horse_quad.obj", "spot.obj"])
    return parser.parse_args(argv)


ARGS = _arguments()


def timed(call):
    """Median wall and CPU milliseconds of call() over ARGS.repeat calls; call may return a
    function that prepares the next (its time is not counted)."""
    wall, cpu = [], []
    for _ in range(ARGS.repeat):
        prepare = call.prepare() if hasattr(call, "prepare") else None
        w, c = time.perf_counter(), time.process_time()
        call(prepare)
        wall.append(1000 * (time.perf_counter() - w))
        cpu.append(1000 * (time.process_time() - c))
    return statistics.median(wall), statistics.median(cpu)


class Operator:
    def __init__(self, fresh):
        self.fresh = fresh

    def prepare(self):
        self.fresh()

    def __call__(self, _prepared):
        bpy.ops.raps.lightmap(uv_map="UVMap")


class LightmapPack:
    def __init__(self, fresh):
        self.fresh = fresh

    def prepare(self):
        self.fresh()
        bpy.ops.object.mode_set(mode="EDIT")
        bpy.ops.mesh.select_all(action="SELECT")

    def __call__(self, _prepared):
        bpy.ops.uv.lightmap_pack()


class Library:
    def __init__(self, data, options, progress):
        self.data, self.options, self.progress = data, options, progress

    def prepare(self):
        from raps_uv import unwrap
        return unwrap._raps_mesh(self.data), self.options.settings()

    def __call__(self, prepared):
        from raps_uv.native import raps
        mesh, settings = prepared
        raps.parameterize(mesh, settings, progress=self.progress).close()
        mesh.close()
        settings.close()


def main():
    bpy.ops.preferences.addon_install(filepath=ARGS.zip, overwrite=True)
    started = time.perf_counter()
    bpy.ops.preferences.addon_enable(module="raps_uv")  # imports the binding, loads libraps
    print("Enabling the add-on: %.0f ms\n" % (1000 * (time.perf_counter() - started)))
    from blender_unwrappers import fresh_object, read_mesh_file
    from raps_uv import mesh_io, unwrap
    print("Milliseconds, medians of %d calls: wall / CPU\n" % ARGS.repeat)
    print("| mesh | faces | Lightmap with raps | library alone | library + Python progress "
          "| library + progress state | progress calls | Lightmap Pack |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for name in ARGS.names:
        verts, faces = read_mesh_file(os.path.join(ARGS.meshes, name))
        base = bpy.data.meshes.new(name)
        base.from_pydata(verts, [], faces)
        operator = timed(Operator(lambda: fresh_object(base, "raps")))
        data = mesh_io.read_mesh(fresh_object(base, "raps"))
        options = unwrap.Options(lightmap=True, rotation="QUARTER", padding=2)
        calls = []
        Library(data, options, lambda phase, fraction: calls.append(1))(
            Library(data, options, None).prepare())
        library = timed(Library(data, options, None))
        with_progress = timed(Library(data, options, lambda phase, fraction: True))
        from raps_uv.native import raps
        with_state = timed(Library(data, options, raps.ProgressState()))
        pack = None
        if len(faces) <= ARGS.lightmap_pack_max_faces:  # minutes on the larger meshes
            pack = timed(LightmapPack(lambda: fresh_object(base, "pack")))
            bpy.ops.object.mode_set(mode="OBJECT")
        print("| %s | %d | %.0f / %.0f | %.0f / %.0f | %.0f / %.0f | %.0f / %.0f | %d | %s |" % (
            name, len(faces), *operator, *library, *with_progress, *with_state, len(calls),
            "%.0f / %.0f" % pack if pack else "-"))
        bpy.data.meshes.remove(base)


main()
