"""raps-gltf benchmark: bakes every shared glTF asset (and the demo scene when given) several
times and prints, per asset, the median wall time of the whole tool (load, bake, write) and of
the library alone, the same per million triangles, and the atlas figures of the last run.
Numbers are printed, never judged.

With --scene, each asset is baked with --group scene (one atlas for every mesh its default scene
draws, at its world scale; --scene-flags adds raps-gltf flags, e.g. "--texels-per-unit 64
--max-size 1024") and the table gives per asset its time, charts, atlas (page) size, pages,
utilization, texels per world unit and the density spread: (max - min) / min over the charts not
shrunk to fit a page of sqrt(texel area / world area), from the report's chart records.

With --large K, the table is of one asset the benchmark builds: SheenCloth.glb (115,200
triangles) 1-to-4 subdivided K times (default 2: 1,843,200 triangles), every attribute
interpolated, written as a .glb; raps-gltf's own load, bake and write times are added, and the
rate in triangles per second end to end (issue 20 asks for a million or more).

usage: gltf_bench.py RAPS_GLTF SHARED_DATA_DIR [--runs N] [--threads N] [--extra ASSET...]
                     [--scene [--scene-flags FLAGS]] [--large [K]]
"""
import argparse
import glob
import json
import os
import statistics
import struct
import subprocess
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'tests', 'cli'))
from gltf_reader import Gltf  # noqa: E402


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument('raps_gltf')
    parser.add_argument('data')
    parser.add_argument('--runs', type=int, default=3)
    parser.add_argument('--threads', type=int, default=0)
    parser.add_argument('--extra', nargs='*', default=[])
    parser.add_argument('--scene', action='store_true')
    parser.add_argument('--scene-flags', default='')
    parser.add_argument('--large', type=int, nargs='?', const=2, default=None)
    args = parser.parse_args()
    if args.large is not None:
        large_table(args)
        return
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


def subdivide(attributes, triangles):
    """One 1-to-4 midpoint subdivision: each edge's midpoint interpolates every attribute
    (normals renormalised, a tangent's xyz too, its handedness w kept)."""
    t = triangles
    edges = np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]])
    unique, inverse = np.unique(np.sort(edges, axis=1), axis=0, return_inverse=True)
    n = len(attributes['POSITION'])
    out = {}
    for name, values in attributes.items():
        mid = 0.5 * (values[unique[:, 0]] + values[unique[:, 1]])
        if name in ('NORMAL', 'TANGENT'):
            mid[:, :3] /= np.maximum(np.linalg.norm(mid[:, :3], axis=1), 1e-30)[:, None]
            if name == 'TANGENT':
                mid[:, 3] = values[unique[:, 0], 3]
        out[name] = np.concatenate([values, mid]).astype(np.float32)
    m = n + inverse.reshape(3, -1).T  # per triangle, the midpoints of edges 01, 12, 20
    a, b, c = t[:, 0], t[:, 1], t[:, 2]
    ab, bc, ca = m[:, 0], m[:, 1], m[:, 2]
    tris = np.concatenate([np.stack(x, 1) for x in ((a, ab, ca), (ab, b, bc), (ca, bc, c),
                                                      (ab, bc, ca))])
    return out, tris.astype(np.uint32)


def write_glb(path, attributes, triangles):
    """One mesh, one node, no material: the attributes and uint32 indices in one buffer."""
    blob, views, accessors = b'', [], []
    kinds = {1: 'SCALAR', 2: 'VEC2', 3: 'VEC3', 4: 'VEC4'}

    def add(array, component, kind, target, bounds=False):
        nonlocal blob
        data = array.tobytes()
        views.append({'buffer': 0, 'byteOffset': len(blob), 'byteLength': len(data),
                      'target': target})
        accessor = {'bufferView': len(views) - 1, 'componentType': component,
                    'count': len(array), 'type': kind}
        if bounds:
            accessor['min'] = array.min(axis=0).tolist()
            accessor['max'] = array.max(axis=0).tolist()
        accessors.append(accessor)
        blob += data + b'\0' * (-len(data) % 4)
        return len(accessors) - 1

    indices = add(triangles.reshape(-1), 5125, 'SCALAR', 34963)
    names = {name: add(values, 5126, kinds[values.shape[1]], 34962, name == 'POSITION')
             for name, values in attributes.items()}
    doc = {'asset': {'version': '2.0', 'generator': 'bench/gltf_bench.py --large'},
           'scene': 0, 'scenes': [{'nodes': [0]}], 'nodes': [{'mesh': 0}],
           'meshes': [{'primitives': [{'attributes': names, 'indices': indices}]}],
           'buffers': [{'byteLength': len(blob)}], 'bufferViews': views, 'accessors': accessors}
    text = json.dumps(doc, separators=(',', ':')).encode()
    text += b' ' * (-len(text) % 4)
    with open(path, 'wb') as fh:
        fh.write(struct.pack('<4sII', b'glTF', 2, 12 + 8 + len(text) + 8 + len(blob)))
        fh.write(struct.pack('<I4s', len(text), b'JSON') + text)
        fh.write(struct.pack('<I4s', len(blob), b'BIN\0') + blob)


def large_table(args):
    source = Gltf(os.path.join(args.data, 'gltf', 'SheenCloth.glb'))
    prim = source.json['meshes'][0]['primitives'][0]
    attributes = {name: source.accessor(index).astype(np.float64)
                  for name, index in prim['attributes'].items()}
    triangles = source.accessor(prim['indices']).reshape(-1, 3).astype(np.int64)
    for _ in range(args.large):
        attributes, triangles = subdivide(attributes, triangles)
        triangles = triangles.astype(np.int64)
    print(f'raps-gltf on SheenCloth.glb subdivided {args.large} times, median of {args.runs} runs,'
          f' --threads {args.threads}, output .glb; phases from the tool\'s report\n')
    print('| asset | triangles | charts | utilization | L2 stretch | load ms | bake ms | write ms |'
          ' tool ms | M triangles per s |')
    print('|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|')
    with tempfile.TemporaryDirectory() as tmp:
        asset = os.path.join(tmp, f'SheenCloth_x{4 ** args.large}.glb')
        write_glb(asset, attributes, triangles.astype(np.uint32))
        wall, phases, report = [], {'load': [], 'bake': [], 'write': []}, None
        for _ in range(args.runs):
            ms, report = bake_runs(argparse.Namespace(**{**vars(args), 'runs': 1}), asset,
                                   os.path.join(tmp, 'out.glb'), [])
            if ms is None:
                print(f'| {os.path.basename(asset)} | failed ({report}) |')
                return
            wall.append(ms)
            for name in phases:
                phases[name].append(report['time_ms'][name])
        tris, group = report['baked']['triangles'], report['groups'][0]
        ms = statistics.median(wall)
        print(f'| {os.path.basename(asset)} | {tris} | {group["charts"]} |'
              f' {group["utilization"]:.3f} | {group["distortion"]["stretch_l2"]:.3f} |'
              + ''.join(f' {statistics.median(v):.0f} |' for v in phases.values())
              + f' {ms:.0f} | {tris / ms / 1000:.2f} |')


if __name__ == '__main__':
    main()
