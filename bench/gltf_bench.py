"""raps-gltf benchmark: bakes every shared glTF asset (and the demo scene when given) several
times and prints, per asset, the median wall time of the whole tool (load, bake, write) and of
the library alone, the same per million triangles, and the atlas figures of the last run.
Numbers are printed, never judged.

usage: gltf_bench.py RAPS_GLTF SHARED_DATA_DIR [--runs N] [--threads N] [--extra ASSET...]
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
    args = parser.parse_args()
    assets = sorted(glob.glob(os.path.join(args.data, 'gltf', '*.gl*')) +
                    glob.glob(os.path.join(args.data, 'gltf', '*', '*.gltf'))) + args.extra
    if not assets:
        sys.exit('no glTF assets under ' + args.data)
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


if __name__ == '__main__':
    main()
