#!/usr/bin/python3
"""The atlas as the judge's tool sees it: raps-param --atlas on every shared mesh, each OBJ
measured by shared/tools/uvmetrics.py (the vt lines as written), one row per mesh.

usage: atlas_uvmetrics.py RAPS_PARAM DATA_DIR [--reference OTHER_RAPS_PARAM] [-- FLAGS...]

Prints, per mesh, uvmetrics' charts, unit-square coverage, L2 and Linf stretch and mean angle
distortion, and raps-param's pack time (ms); with --reference, the same for that binary on the
line above (A/B in one run). FLAGS after `--` go to both binaries (default: --threads 2).
Needs /usr/bin/python3 with numpy (uvmetrics).
"""

import json
import os
import statistics
import subprocess
import sys
import tempfile

COLUMNS = ('n_charts', 'unit_square_coverage', 'stretch_l2', 'stretch_linf', 'angle_mean_deg')


def measure(binary, mesh, flags, out, tool):
    run = subprocess.run([binary, '--atlas', mesh, '-o', out] + flags, capture_output=True,
                         text=True)
    if run.returncode != 0:
        return None
    pack = json.loads(run.stdout)['time_ms']['pack']
    metrics = json.loads(subprocess.run(['/usr/bin/python3', tool, out], capture_output=True,
                                        text=True, check=True).stdout)
    return [metrics[c] for c in COLUMNS] + [pack]


def main(argv):
    flags = ['--threads', '2']
    if '--' in argv:
        flags = argv[argv.index('--') + 1:]
        argv = argv[:argv.index('--')]
    reference = None
    if '--reference' in argv:
        at = argv.index('--reference')
        reference = argv[at + 1]
        del argv[at:at + 2]
    if len(argv) != 2:
        sys.exit(__doc__)
    binary, data = argv
    meshes = sorted(os.listdir(os.path.join(data, 'meshes')))
    tool = os.path.join(data, '..', 'tools', 'uvmetrics.py')  # shared/tools beside shared/data
    runs = [('reference', reference)] if reference else []
    runs.append(('candidate', binary))
    print('%-22s %-9s %6s %8s %7s %6s %7s %8s' % ('mesh', 'binary', 'charts', 'coverage', 'L2',
                                                  'Linf', 'angle', 'pack ms'))
    sums = {name: [] for name, _ in runs}
    with tempfile.TemporaryDirectory() as scratch:
        for mesh in meshes:
            for name, path in runs:
                row = measure(path, os.path.join(data, 'meshes', mesh), flags,
                              os.path.join(scratch, 'atlas.obj'), tool)
                if row is None:
                    print('%-22s %-9s refused' % (mesh, name))
                    continue
                sums[name].append(row)
                print('%-22s %-9s %6d %8.4f %7.4f %6.2f %7.2f %8.1f' % ((mesh, name) + tuple(row)))
    for name, rows in sums.items():
        if rows:
            print('%-22s %-9s %6.1f %8.4f %7.4f %6.2f %7.2f %8.1f' % (
                ('median', name) + tuple(statistics.median(r[k] for r in rows)
                                         for k in range(len(COLUMNS) + 1))))


if __name__ == '__main__':
    main(sys.argv[1:])
