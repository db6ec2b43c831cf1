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
    print(f'raps-gltf, median of {args.runs} runs, --threads {args.threads}, output .glb')
    header = (f"{'asset':<28}{'tris':>8}{'charts':>8}{'util':>6}{'area|log r|':>12}{'L2':>7}"
              f"{'tool ms':>9}{'lib ms':>9}{'s/Mtri':>8}")
    print(header)
    print('-' * len(header))
    total_tris = total_ms = 0.0
    with tempfile.TemporaryDirectory() as tmp:
        for asset in assets:
            out = os.path.join(tmp, 'out.glb')
            wall, library, report = [], [], None
            for _ in range(args.runs):
                start = time.perf_counter()
                p = subprocess.run([args.raps_gltf, '--no-progress', '--overwrite', '--threads',
                                    str(args.threads), asset, out], capture_output=True, text=True)
                wall.append(1000 * (time.perf_counter() - start))
                if p.returncode != 0:
                    print(f'{os.path.basename(asset):<28} failed: {p.stderr.strip()}')
                    break
                report = json.loads(p.stdout)
                library.append(sum(g.get('time_ms', {}).get('total', 0) for g in report['groups']))
            if report is None or len(wall) < args.runs:
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
            print(f'{os.path.basename(asset):<28}{tris:>8}{charts:>8}{util:>6.2f}{area:>12.3f}{l2:>7.3f}'
                  f'{ms:>9.0f}{lib:>9.0f}{ms / 1000 / (tris / 1e6):>8.1f}')
    print('-' * len(header))
    print(f"{'all':<28}{int(total_tris):>8}{'':>8}{'':>6}{'':>12}{'':>7}{total_ms:>9.0f}{'':>9}"
          f'{total_ms / 1000 / (total_tris / 1e6):>8.1f}')


if __name__ == '__main__':
    main()
