"""The figures behind the method's choices (docs/method.md), measured with raps-param on the
shared meshes: the disk domain's distortion per setting and iteration mode, flips per weights and
monitor, the sphere domain's robust and literal methods, the cap on sweeps, and the octahedral
unfold. Prints Markdown; numbers are printed, never judged.

usage: method_bench.py RAPS_PARAM SHARED_DATA_DIR
"""
import json
import os
import subprocess
import sys
import tempfile

DISKS = ['alligator.obj', 'camelhead.off', 'face.obj', 'lion.off']
SPHERES = ['bunny.off', 'cheburashka.off', 'decimated-max.obj', 'fandisk.obj', 'spot.obj']


class Failed(Exception):
    """raps-param refused or failed: the row says so instead of the figures."""


def run(raps_param, mesh, *flags):
    with tempfile.TemporaryDirectory() as tmp:
        p = subprocess.run([raps_param, mesh, '-o', os.path.join(tmp, 'out.obj')] + list(flags),
                           capture_output=True, text=True)
    if p.returncode != 0:
        message = ' '.join(p.stderr.split()).replace('|', '/')
        raise Failed('`%s` failed (exit %d): %s' % (' '.join(flags), p.returncode, message))
    return json.loads(p.stdout)


def row(mesh, make):
    """Prints the row `make` builds for `mesh`, or the failure that stopped it."""
    try:
        print(make())
    except Failed as failure:
        print('| %s | %s |' % (name(mesh), failure))


def name(mesh):
    return os.path.splitext(os.path.basename(mesh))[0]


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    raps_param, data = sys.argv[1], sys.argv[2]
    disks = [os.path.join(data, 'meshes', m) for m in DISKS]
    spheres = [os.path.join(data, 'meshes', m) for m in SPHERES]

    def settings_row(mesh):
        cells = []
        for flags in (['--monitor', 'none'], [], ['--alpha', '2'], ['--iterations', '10']):
            s = run(raps_param, mesh, *flags)
            cells.append('%.3f (%d)' % (s['stats']['area_log_mean'], s['stats']['flipped_triangles']))
        return '| %s | %d | %s |' % (name(mesh), s['triangles'], ' | '.join(cells))

    def iteration_row(mesh):
        cells = []
        for mode in ('accumulate', 'reapply'):
            values, flips = [], 0
            for k in (1, 2, 3, 5, 10):
                s = run(raps_param, mesh, '--iterations', str(k), '--iteration-mode', mode)
                values.append('%.3f' % s['stats']['area_log_mean'])
                flips = max(flips, s['stats']['flipped_triangles'])
            cells.append('%s (%d)' % (', '.join(values), flips))
        return '| %s | %s |' % (name(mesh), ' | '.join(cells))

    def flips_row(mesh):
        cells = []
        for weights in ('mvc', 'uniform'):
            for monitor in ('none', 'area', 'length', 'angle'):
                s = run(raps_param, mesh, '--weights', weights, '--monitor', monitor)
                cells.append(str(s['stats']['flipped_triangles']))
        return '| %s | %s |' % (name(mesh), ' | '.join(cells))

    def sphere_row(mesh):
        a = run(raps_param, mesh, '--sphere', '--monitor', 'none')['stats']
        s = run(raps_param, mesh, '--sphere')
        b = s['stats']
        return ('| %s | %d | %.3f, %.1f | %.3f, %.1f | %d | %d | %.0f |'
                % (name(mesh), s['triangles'], a['area_log_mean'], a['angle_mean_deg'],
                   b['area_log_mean'], b['angle_mean_deg'], b['flipped_triangles'],
                   b['relaxation_sweeps'], s['time_ms']['library_total']))

    def sweeps_row(mesh):
        cells = []
        for sweeps in (100, 200, 400):
            s = run(raps_param, mesh, '--sphere', '--max-sweeps', str(sweeps))
            cells.append('%.3f' % s['stats']['area_log_mean'])
        return '| %s | %s |' % (name(mesh), ' | '.join(cells))

    def literal_row(mesh):
        s = run(raps_param, mesh, '--sphere', '--sphere-method', 'literal')
        b = s['stats']
        return ('| %s | %d | %.0f | %d | %.3f |'
                % (name(mesh), b['relaxation_sweeps'], s['time_ms']['library_total'],
                   b['flipped_triangles'], b['area_log_mean']))

    def unfold_row(mesh):
        plain = run(raps_param, mesh, '--sphere')
        s = run(raps_param, mesh, '--sphere', '--sphere-uv', 'octahedral')
        b = s['stats']
        return ('| %s | %d | %.3f | %.2f | %.2f | %d |'
                % (name(mesh), s['vertices'] - plain['vertices'], b['area_log_mean'],
                   b['stretch_l2'], b['stretch_linf'], b['flipped_triangles']))

    sections = [
        ('Disk domain: area distortion per setting',
         'Mean value weights, circle boundary (the defaults); area monitor unless "none". '
         'Flipped triangles in brackets.',
         '| mesh | triangles | monitor none | area, alpha 1 | area, alpha 2 | '
         'area, 10 accumulated iterations |\n|---|---:|---:|---:|---:|---:|', disks, settings_row),
        ('Disk domain: accumulating against re-applying the monitor',
         'Area mean |log r| after K adaptive solves (`--iterations K --iteration-mode MODE`), '
         'K = 1, 2, 3, 5, 10; the most flipped triangles over the five runs in brackets.',
         '| mesh | accumulate | reapply |\n|---|---|---|', disks, iteration_row),
        ('Disk domain: flipped triangles per weights and monitor', '',
         '| mesh | ' + ' | '.join('%s, %s' % (w, m) for w in ('mvc', 'uniform')
                                  for m in ('none', 'area', 'length', 'angle')) +
         ' |\n|---|' + '---:|' * 8, disks, flips_row),
        ('Sphere domain, robust method (the default)',
         'Spherical area distortion (3D-area-weighted mean |log r|, exact spherical triangle '
         'areas) and mean angle distortion in degrees (angles between great-circle arcs), of the '
         'initial map (`--sphere --monitor none`) and of the default run (`--sphere`).',
         '| mesh | triangles | initial: area, angle | adapted: area, angle | flipped | sweeps | '
         'library ms |\n|---|---:|---:|---:|---:|---:|---:|', spheres, sphere_row),
        ('Sphere domain: most sweeps per relaxation',
         'Adapted spherical area distortion with `--sphere --max-sweeps N` (the robust default '
         'is 100).', '| mesh | 100 | 200 | 400 |\n|---|---:|---:|---:|', spheres, sweeps_row),
        ('Sphere domain: algorithm 7.1 as written (`--sphere --sphere-method literal`)', '',
         '| mesh | sweeps, all relaxations | library ms | flipped | area |\n'
         '|---|---:|---:|---:|---:|', spheres, literal_row),
        ('Sphere domain: the octahedral unfold (`--sphere --sphere-uv octahedral`)',
         'Statistics of the unfolded uvs; the output vertices beyond the input\'s are the '
         'cut\'s duplicates.',
         '| mesh | vertices added | area | L2 stretch | Linf stretch | flipped |\n'
         '|---|---:|---:|---:|---:|---:|', spheres, unfold_row),
    ]
    for number, (title, text, header, meshes, make) in enumerate(sections):
        print(('\n' if number else '') + '## ' + title + '\n')
        if text:
            print(text + '\n')
        print(header)
        for mesh in meshes:
            row(mesh, lambda: make(mesh))
            sys.stdout.flush()

if __name__ == '__main__':
    main()
