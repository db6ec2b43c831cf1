"""raps-param --atlas on quad meshes with each face kept whole (the default) and with
--split-polygons: charts, utilization, L2 stretch and the input faces split across charts (whose
corners get more than one vt at a vertex), as the rows of docs/raps-param-polygons.md.

usage: raps_param_polygons.py RAPS_PARAM SHARED_DATA_DIR [WORK_DIR]
"""
import json
import os
import subprocess
import sys
import tempfile

MESHES = ('halftunnel.off', 'suzanne.obj', 'horse_quad.obj')


def face_sizes(path):
    """Corners per face of an OBJ or OFF file, in order."""
    with open(path) as fh:
        if path.endswith('.obj'):
            return [len(line.split()) - 1 for line in fh if line.split()[:1] == ['f']]
        words = [line.split() for line in fh if line.strip() and not line.startswith('#')]
    vertices, faces = int(words[1][0]), int(words[1][1])
    return [int(w[0]) for w in words[2 + vertices:2 + vertices + faces]]


def output_faces(path):
    """The written OBJ's faces as (v, vt) pairs, indices counted across the file."""
    with open(path) as fh:
        return [[tuple(int(x) for x in c.split('/')[:2]) for c in line.split()[1:]]
                for line in fh if line.startswith('f ')]


def split_faces(sizes, faces):
    """Input faces written as triangles whose corners disagree on a vertex's vt (raps-param
    writes each face whole, or as its fan triangles where a seam crosses it)."""
    split, at = 0, 0
    for n in sizes:
        parts = [faces[at]] if len(faces[at]) == n else faces[at:at + n - 2]
        at += len(parts)
        vt_of = {}
        for v, vt in (c for face in parts for c in face):
            vt_of.setdefault(v, set()).add(vt)
        split += any(len(vts) > 1 for vts in vt_of.values())
    return split


def row(exe, inputs, flags, work):
    out = os.path.join(work, 'out.obj')
    p = subprocess.run([exe, '--atlas', *inputs, '-o', out, *flags], capture_output=True,
                       text=True, check=True)
    stats = json.loads(p.stdout)['stats']
    sizes = sum((face_sizes(i) for i in inputs), [])
    label = ' '.join(os.path.basename(i) for i in inputs)
    return (f"| {label} | {' '.join(flags) or 'whole (default)'} | {len(sizes)} | "
            f"{sum(n > 3 for n in sizes)} | {stats['charts']} | {stats['utilization']:.3f} | "
            f"{stats['stretch_l2']:.4f} | {split_faces(sizes, output_faces(out))} |")


def main():
    exe, data = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as tmp:
        work = sys.argv[3] if len(sys.argv) > 3 else tmp
        print('| input | mode | input faces | of them polygons | charts | utilization | L2 | '
              'faces split |')
        print('|---|---|---:|---:|---:|---:|---:|---:|')
        cases = [[os.path.join(data, 'meshes', m)] for m in MESHES]
        cases.append([os.path.join(data, 'meshes', m) for m in MESHES])
        for inputs in cases:
            for flags in ([], ['--split-polygons']):
                print(row(exe, inputs, flags, work))
        twice = [os.path.join(data, 'meshes', m) for m in ('halftunnel.off', 'halftunnel.off')]
        for flags in (['--stack'], ['--stack', '--split-polygons']):
            print(row(exe, twice, flags, work))


if __name__ == '__main__':
    main()
