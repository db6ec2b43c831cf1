"""raps's add-on against Blender's own unwrappers, in one Blender process (docs/blender.md).

  blender -b --factory-startup --python bench/blender_unwrappers.py -- \
      --zip build/bindings/blender/raps_uv.zip --meshes ../shared/data/meshes \
      --uvmetrics ../shared/tools/uvmetrics.py --python3 /usr/bin/python3 \
      --work build/bench-blender [--lightmap-pack-max-faces 7000]

For every shared mesh (OBJ or OFF, built with Mesh.from_pydata, its polygons as they are) and
every operator: a fresh object with a copy of the mesh and no UV map, the operator's call alone
timed (entering edit mode and selecting every face, which Blender's operators need, is not), the
result written as an OBJ of the faces' loop triangles (tests/blender/loop_triangle_obj.py) and
measured by uvmetrics.py. Prints markdown: medians per
operator, then a row per mesh and operator. Lightmap Pack only runs on meshes of at most
--lightmap-pack-max-faces faces (it takes minutes on the larger ones).
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import time

import bpy

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests",
                                "blender"))
import loop_triangle_obj  # noqa: E402
from mesh_file import read_mesh_file  # noqa: E402,F401  (also this module's, for others)


def _arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser()
    for name in ("--zip", "--meshes", "--uvmetrics", "--work"):
        parser.add_argument(name, required=True)
    parser.add_argument("--python3", default="/usr/bin/python3")
    parser.add_argument("--lightmap-pack-max-faces", type=int, default=7000)
    return parser.parse_args(argv)


def fresh_object(base, name):
    """A new object with a copy of base (no UV map), the only one selected and active."""
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    mesh = base.copy()
    mesh.name = name
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj
    return obj


def in_edit_mode(call):
    """Blender's unwrappers work on the selected faces of edit mode; the call alone is timed."""
    def run():
        bpy.ops.object.mode_set(mode="EDIT")
        bpy.ops.mesh.select_all(action="SELECT")
        started = time.perf_counter()
        call()
        elapsed = time.perf_counter() - started
        bpy.ops.object.mode_set(mode="OBJECT")
        return elapsed
    return run


def in_object_mode(call):
    def run():
        started = time.perf_counter()
        call()
        return time.perf_counter() - started
    return run


OPERATORS = [
    ("raps (Unwrap with raps)", in_object_mode(lambda: bpy.ops.raps.unwrap())),
    ("raps (Lightmap with raps)", in_object_mode(lambda: bpy.ops.raps.lightmap(uv_map="UVMap"))),
    ("Smart UV Project", in_edit_mode(lambda: bpy.ops.uv.smart_project())),
    ("Smart UV Project, margin 0.002",
     in_edit_mode(lambda: bpy.ops.uv.smart_project(island_margin=0.002))),
    ("Unwrap (angle based)", in_edit_mode(lambda: bpy.ops.uv.unwrap(method="ANGLE_BASED"))),
    ("Lightmap Pack", in_edit_mode(lambda: bpy.ops.uv.lightmap_pack())),
]
FIGURES = ("n_charts", "n_flipped", "uv_overlap_fraction", "unit_square_coverage", "stretch_l2",
           "stretch_linf", "area_mean_abs_log", "angle_mean_deg")


def measure(args, obj, tag):
    path = os.path.join(args.work, tag + ".obj")
    loop_triangle_obj.write([obj], path)
    out = subprocess.run([args.python3, args.uvmetrics, path], capture_output=True, text=True)
    os.remove(path)
    return json.loads(out.stdout.splitlines()[0])


def main():
    args = _arguments()
    os.makedirs(args.work, exist_ok=True)
    bpy.ops.preferences.addon_install(filepath=args.zip, overwrite=True)
    bpy.ops.preferences.addon_enable(module="raps_uv")
    rows = []
    for file_name in sorted(os.listdir(args.meshes)):
        if not file_name.endswith((".obj", ".off")):
            continue
        verts, faces = read_mesh_file(os.path.join(args.meshes, file_name))
        base = bpy.data.meshes.new("base")
        base.from_pydata(verts, [], faces)
        base.validate()
        for label, run in OPERATORS:
            if label == "Lightmap Pack" and len(base.polygons) > args.lightmap_pack_max_faces:
                continue
            obj = fresh_object(base, file_name.split(".")[0])
            seconds = run()
            row = {"mesh": file_name, "faces": len(base.polygons), "operator": label,
                   "time_s": seconds}
            m = measure(args, obj, "%s_%d" % (obj.name, len(rows)))
            row.update({k: m.get(k) for k in FIGURES})
            rows.append(row)
            print(json.dumps(row), flush=True)
        bpy.data.meshes.remove(base)
    with open(os.path.join(args.work, "rows.json"), "w") as stream:
        json.dump(rows, stream, indent=1)
    print_tables(rows, args)


def _fmt(value, digits=3):
    if value is None:
        return "-"
    if isinstance(value, int):
        return "{:,}".format(value)
    return "%.*f" % (digits, value)


def _time(seconds):
    return "%.0f ms" % (1000 * seconds) if seconds < 1 else "%.1f s" % seconds


def print_tables(rows, args):
    print("\n| operator | meshes | time | charts | flipped | overlap | coverage | L2 | Linf |"
          " area mean abs log | angle mean (deg) |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for label, _ in OPERATORS:
        mine = [r for r in rows if r["operator"] == label]
        if not mine:
            continue

        def median(key):
            values = [r[key] for r in mine if r[key] is not None]
            return statistics.median(values) if values else None
        print("| %s | %d | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            label, len(mine), _time(median("time_s")), _fmt(median("n_charts"), 0),
            _fmt(median("n_flipped"), 0), _fmt(median("uv_overlap_fraction")),
            _fmt(median("unit_square_coverage")), _fmt(median("stretch_l2")),
            _fmt(median("stretch_linf"), 2), _fmt(median("area_mean_abs_log")),
            _fmt(median("angle_mean_deg"), 1)))
    print("\n| mesh | faces | operator | time | charts | flipped | overlap | coverage | L2 |"
          " Linf | area mean abs log |")
    print("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        print("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            r["mesh"], _fmt(r["faces"]), r["operator"], _time(r["time_s"]),
            _fmt(r["n_charts"]), _fmt(r["n_flipped"]), _fmt(r["uv_overlap_fraction"]),
            _fmt(r["unit_square_coverage"]), _fmt(r["stretch_l2"]), _fmt(r["stretch_linf"], 2),
            _fmt(r["area_mean_abs_log"])))


if __name__ == "__main__":  # also a module: bench/blender_addon_overhead.py
    main()
