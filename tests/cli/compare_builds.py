"""Two builds of raps-param give the same bits (issue 19, docs/reproducibility.md): the same
shared meshes, in every domain, through a reference and a candidate build (another architecture
under an emulator, another compiler, the static library), and the output OBJ files must be equal
byte for byte, the statistics equal, and a refused input refused with the same error.

usage: compare_builds.py --data SHARED_DATA_DIR --reference CMD --candidate CMD
                         [--cases subset|all] [--jobs N]

CMD is a command line, split like a shell's: the raps-param executable, behind an emulator if it
needs one, e.g. "qemu-aarch64-static -L /usr/aarch64-linux-gnu build-aarch64/samples/raps-param".
Prints one line per case and exits with 1 if any case differs.
"""
import argparse
import concurrent.futures
import json
import os
import re
import shlex
import subprocess
import sys
import tempfile
import time

DISKS = ['alligator.obj', 'camelhead.off', 'face.obj', 'lion.off']
CLOSED_GENUS_0 = ['bunny.off', 'cheburashka.off', 'cow.off', 'decimated-knight.off',
                  'decimated-max.obj', 'fandisk.obj', 'horse_quad.obj', 'spot.obj']
OTHERS = ['3holes.off', 'beetle.off', 'fertility.off', 'halftunnel.off', 'rocker-arm.obj',
          'suzanne.obj', 'teapot.obj']

# (mesh, raps-param options): every shared mesh in every domain it belongs to, and the options
# whose code paths call the elementary functions (angle monitor: atan2; square boundary; the
# octahedral unfolding: tan, and rotations; hard edges: cos).
ALL = ([(m, []) for m in DISKS] +
       [('alligator.obj', o) for o in (['--monitor', 'angle'], ['--monitor', 'length'],
                                       ['--weights', 'cotan'], ['--boundary', 'square'],
                                       ['--iterations', '3'])] +
       [(m, ['--atlas']) for m in DISKS + CLOSED_GENUS_0 + OTHERS] +
       [('fandisk.obj', ['--atlas', '--hard-edge-angle', '40'])] +
       [(m, ['--sphere']) for m in CLOSED_GENUS_0] +
       [(m, ['--sphere', '--sphere-uv', 'octahedral']) for m in CLOSED_GENUS_0] +
       [('decimated-knight.off', ['--sphere', '--sphere-method', 'literal',
                                  '--max-sweeps', '2000'])])

# A few seconds natively and well under a minute under qemu: one or two cases per domain.
SUBSET = [('alligator.obj', ['--monitor', 'angle']),
          ('halftunnel.off', ['--atlas']),
          ('decimated-knight.off', ['--atlas', '--hard-edge-angle', '40']),
          ('decimated-knight.off', ['--sphere', '--sphere-uv', 'octahedral']),
          ('bunny.off', ['--sphere'])]


def run(command, data, mesh, options, output):
    start = time.monotonic()
    p = subprocess.run(command + options + [os.path.join(data, 'meshes', mesh), '-o', output],
                       capture_output=True, text=True, timeout=3600)
    seconds = time.monotonic() - start
    try:
        report = json.loads(p.stdout)
    except ValueError:
        report = {'unreadable stdout': p.stdout[-500:], 'stderr': p.stderr[-500:]}
    obj = None
    if os.path.exists(output):
        with open(output, 'rb') as fh:
            obj = fh.read()
    # Everything a run returns but what may differ: where and how long, and the thread count.
    report.pop('input', None)
    report.pop('output', None)
    report.pop('time_ms', None)
    return p.returncode, report, obj, seconds


NUMBER = re.compile(rb'-?[0-9][0-9.e+-]*')


def describe_difference(a, b):
    """The largest difference between corresponding numbers, if the files differ only there."""
    lines_a, lines_b = a.split(b'\n'), b.split(b'\n')
    if len(lines_a) != len(lines_b):
        return '%d against %d lines' % (len(lines_a), len(lines_b))
    largest, differing = 0.0, 0
    for x, y in zip(lines_a, lines_b):
        if x == y:
            continue
        differing += 1
        if NUMBER.sub(b'#', x) != NUMBER.sub(b'#', y):
            return 'line structure differs: %r against %r' % (x[:60], y[:60])
        for u, v in zip(NUMBER.findall(x), NUMBER.findall(y)):
            largest = max(largest, abs(float(u) - float(v)))
    return '%d lines differ, by at most %.3g' % (differing, largest)


def compare(reference, candidate, data, case, folder):
    mesh, options = case
    name = ' '.join([mesh] + options)
    stem = os.path.join(folder, re.sub(r'[^A-Za-z0-9]+', '_', name))
    rc_a, report_a, obj_a, t_a = run(reference, data, mesh, options, stem + '_a.obj')
    rc_b, report_b, obj_b, t_b = run(candidate, data, mesh, options, stem + '_b.obj')
    if rc_a != rc_b or report_a != report_b:
        verdict = 'DIFFERS: exit %d/%d, reports %s / %s' % (rc_a, rc_b, json.dumps(report_a),
                                                            json.dumps(report_b))
    elif obj_a != obj_b:
        verdict = 'DIFFERS: OBJ ' + (describe_difference(obj_a, obj_b)
                                     if obj_a is not None and obj_b is not None
                                     else 'written by one build only')
    else:
        verdict = 'same bits' if rc_a == 0 else 'same error'
    return name, verdict, t_a, t_b


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--data', required=True)
    parser.add_argument('--reference', required=True)
    parser.add_argument('--candidate', required=True)
    parser.add_argument('--cases', choices=['subset', 'all'], default='subset')
    parser.add_argument('--jobs', type=int, default=1)
    args = parser.parse_args()
    reference, candidate = shlex.split(args.reference), shlex.split(args.candidate)
    cases = SUBSET if args.cases == 'subset' else ALL
    differing = 0
    with tempfile.TemporaryDirectory() as folder, \
            concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        for name, verdict, t_a, t_b in pool.map(
                lambda case: compare(reference, candidate, args.data, case, folder), cases):
            print('%-60s %-14s reference %6.1f s, candidate %6.1f s' % (name, verdict, t_a, t_b)
                  if not verdict.startswith('DIFFERS') else '%-60s %s' % (name, verdict),
                  flush=True)
            differing += verdict.startswith('DIFFERS')
    print('%d of %d cases differ' % (differing, len(cases)))
    return 1 if differing else 0


if __name__ == '__main__':
    sys.exit(main())
