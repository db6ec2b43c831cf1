"""raps-gltf benchmark: bakes every shared glTF asset (and the demo scene when given) several
times and prints, per asset, the median wall time of the whole tool (load, bake, write) and of
the library alone, the same per million triangles, and the atlas figures of the last run.
Numbers are printed, never judged.

With --scene, each asset is baked with --group scene (one atlas for every mesh its default scene
draws, at its world scale; --scene-flags adds raps-gltf flags, e.g. "--texels-per-unit 64
--max-size 1024") and the table gives per asset its time, charts, atlas (page) size, pages,
utilization, texels per world unit and the density spread: (max - min) / min over the charts not
shrunk to fit a page of sqrt(texel area / world area), from the report's chart records.

usage: gltf_bench.py RAPS_GLTF SHARED_DATA_DIR [--runs N] [--threads N] [--extra ASSET...]
                     [--scene [--scene-flags FLAGS]]
"""
import argparse
import glob
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument('raps_gltf')
    parser.add_argument('data')
    parser.add_argument('--runs', type=int, default=3)
    parser.add_argument('--threads', type=int, default=0)
    parser.add_argument('--extra', nargs='*', default=[])
    parser.add_argument('--scene', action='store_true')
    parser.add_argument('--scene-flags', default='')
    args = parser.parse_args()
    assets = sorted(glob.glob(os.path.join(args.data, 'gltf', '*.gl*')) +
                    glob.glob(os.path.join(args.data, 'gltf', '*', '*.gltf'))) + args.extra
    if not assets:
        sys.exit('no glTF assets under ' + args.data)
    if args.scene:
        scene_table(args, assets)
        return
    print(f'raps-gltf, median of {args.runs} runs, --threads {args.threads}, output .glb, whole tool'
          ' from load to write; "lib ms" is the library\'s own time, summed over the atlases\n')
    print('| asset | triangles | charts | utilization | area mean abs log | L2 stretch | tool ms |'
          ' lib ms | s per M triangles |')
    print('|---|---:|---:|---:|---:|---:|---:|---:|---:|')
    total_tris = total_ms = 0.0
    with tempfile.TemporaryDirectory() as tmp:
        for asset in assets:
            out = os.path.join(tmp, 'out.glb')
            wall, library, report, failed = [], [], None, False
            for _ in range(args.runs):
                start = time.perf_counter()
                p = subprocess.run([args.raps_gltf, '--no-progress', '--overwrite', '--threads',
                                    str(args.threads), asset, out], capture_output=True, text=True)
                wall.append(1000 * (time.perf_counter() - start))
                if p.returncode != 0:
                    message = ' '.join(p.stderr.split()).replace('|', '/')
                    print(f'| {os.path.basename(asset)} | failed (exit {p.returncode}): {message} |')
                    failed = True
                    break
                report = json.loads(p.stdout)
                library.append(sum(g.get('time_ms', {}).get('total', 0) for g in report['groups']))
            if failed or report is None:
                continue
            tris = report['baked']['triangles']
            groups = [g for g in report['groups'] if 'reused_from_mesh' not in g]
            charts = sum(g['charts'] for g in groups)
            util = statistics.mean(g['utilization'] for g in groups)
            area = sum(g['distortion']['area_log_mean'] * g['triangles'] for g in groups) / \
                max(1, sum(g['triangles'] for g in groups))
            l2 = max(g['distortion']['stretch_l2'] for g in groups)
            ms = statistics.median(wall)
            lib = statistics.median(library)
            total_tris += tris
            total_ms += ms
            # Below 1,000 triangles fixed costs (process start, loading) dominate: no rate.
            rate = f'{ms / 1000 / (tris / 1e6):.1f}' if tris >= 1000 else '—'
            print(f'| {os.path.basename(asset)} | {tris} | {charts} | {util:.2f} | {area:.3f} |'
                  f' {l2:.3f} | {ms:.0f} | {lib:.0f} | {rate} |')
    if total_tris:
        print(f'| all | {int(total_tris)} | | | | | {total_ms:.0f} | |'
              f' {total_ms / 1000 / (total_tris / 1e6):.1f} |')


def bake_runs(args, asset, out, flags):
    """Runs raps-gltf args.runs times: (median wall ms, last report) or (None, error message)."""
    wall, report = [], None
    for _ in range(args.runs):
        start = time.perf_counter()
        p = subprocess.run([args.raps_gltf, '--no-progress', '--overwrite', '--threads',
                            str(args.threads), *flags, asset, out], capture_output=True,
                           text=True)
        wall.append(1000 * (time.perf_counter() - start))
        if p.returncode != 0:
            return None, f'exit {p.returncode}: ' + ' '.join(p.stderr.split()).replace('|', '/')
        report = json.loads(p.stdout)
    return statistics.median(wall), report


def density_spread(scene):
    densities = [(c['area_texels'] / c['area_3d']) ** 0.5 for c in scene['chart_list']
                 if not c['scaled_down'] and c['area_3d'] > 0 and c['area_texels'] > 0]
    # No chart left at the density (all shrunk to fit): no spread to give.
    return (max(densities) - min(densities)) / min(densities) if densities else float('nan')


def scene_table(args, assets):
    flags = ['--group', 'scene', *args.scene_flags.split()]
    print(f'raps-gltf {" ".join(flags)}, median of {args.runs} runs, --threads {args.threads},'
          ' output .glb, whole tool from load to write\n')
    print('| asset | meshes | triangles | charts | atlas | pages | utilization | texels per unit |'
          ' density spread | shrunk | tool ms |')
    print('|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|')
    with tempfile.TemporaryDirectory() as tmp:
        for asset in assets:
            ms, report = bake_runs(args, asset, os.path.join(tmp, 'out.glb'), flags)
            name = os.path.basename(asset)
            if ms is None:
                print(f'| {name} | failed ({report}) |')
                continue
            scene = report.get('scene')
            if not scene or not report['groups']:
                print(f'| {name} | nothing to bake |')
                continue
            spread = density_spread(scene)
            spread = '—' if spread != spread else f'{100 * spread:.4f} %'
            print(f'| {name} | {len(scene["meshes"])} | {report["baked"]["triangles"]} |'
                  f' {scene["charts"]} | {scene["atlas"][0]} x {scene["atlas"][1]} |'
                  f' {scene["page_count"]} | {scene["utilization"]:.3f} |'
                  f' {scene["texels_per_unit"]:.4g} | {spread} |'
                  f' {scene["scaled_down_charts"]} | {ms:.0f} |')


if __name__ == '__main__':
    main()
