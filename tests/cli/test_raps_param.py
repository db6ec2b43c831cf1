"""raps-param's contract: OBJ/OFF in, OBJ out with the input's vertices and faces in order plus
one vt per vertex; one JSON object on stdout; clear errors, exit codes, and no output file on
failure. Its statistics are cross-checked against the project's reference metrics tool,
shared/tools/uvmetrics.py. With --sphere: the points on the unit sphere as v lines, and with
--sphere-uv octahedral one vt per output vertex (the seams' vertices once per side). With --atlas
and several inputs: one atlas, one `o` per input in order, per input, page and chart figures.
With --repack the inputs' own vt islands come back only moved, turned and uniformly scaled.

usage: test_raps_param.py RAPS_PARAM SHARED_DATA_DIR
"""
import json
import math
import os
import stat
import subprocess
import sys
import tempfile
import threading
import unittest

RAPS_PARAM = None
DATA = None


def run(*args):
    p = subprocess.run([RAPS_PARAM, *args], capture_output=True, text=True, timeout=600)
    return p.returncode, p.stdout, p.stderr


def obj_records(path):
    v, vt, f = [], [], []
    with open(path) as fh:
        for line in fh:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == 'v':
                v.append(tuple(map(float, parts[1:4])))
            elif parts[0] == 'vt':
                vt.append(tuple(map(float, parts[1:3])))
            elif parts[0] == 'f':
                f.append([tuple(int(x) for x in c.split('/')) for c in parts[1:]])
    return v, vt, f


class RapsParamTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.out = os.path.join(self.dir.name, 'out.obj')

    def tearDown(self):
        self.dir.cleanup()

    def mesh(self, name):
        return os.path.join(DATA, 'meshes', name)

    def test_obj_out_keeps_vertices_and_faces_in_order(self):
        rc, out, err = run(self.mesh('alligator.obj'), '-o', self.out)
        self.assertEqual(rc, 0, err)
        v_in, _, f_in = obj_records(self.mesh('alligator.obj'))
        v_out, vt_out, f_out = obj_records(self.out)
        self.assertEqual(v_out, v_in)
        self.assertEqual(len(vt_out), len(v_out))
        self.assertEqual([[c[0] for c in face] for face in f_out], [[c[0] for c in face] for face in f_in])
        for face in f_out:
            for c in face:
                self.assertEqual(c[0], c[1])  # one uv per vertex: vt index = v index
        for u, w in vt_out:
            self.assertTrue(0.0 <= u <= 1.0 and 0.0 <= w <= 1.0)

    def test_polygons_are_written_back_as_polygons(self):
        # halftunnel.off is all quads, but has 3 boundary loops: use a quad disk made here.
        src = os.path.join(self.dir.name, 'quads.obj')
        with open(src, 'w') as fh:
            n = 6
            for j in range(n + 1):
                for i in range(n + 1):
                    fh.write(f'v {i} {j} {0.1 * i * j}\n')
            for j in range(n):
                for i in range(n):
                    a = j * (n + 1) + i + 1
                    fh.write(f'f {a} {a + 1} {a + n + 2} {a + n + 1}\n')
        rc, out, err = run(src, '-o', self.out)
        self.assertEqual(rc, 0, err)
        stats = json.loads(out)
        self.assertEqual(stats['polygons'], 36)
        self.assertEqual(stats['triangles'], 72)
        _, _, f_out = obj_records(self.out)
        self.assertEqual(len(f_out), 36)
        self.assertTrue(all(len(face) == 4 for face in f_out))

    def test_polygons_with_corners_in_a_straight_line_are_mapped(self):
        """CAD n-gons keep corners along their straight edges: a strip of rectangles 1, 2 and 3
        cells long (4-, 6- and 8-gons, up to 4 corners in a line). Fanned from the first corner
        they gave zero-area triangles, which the disk domain refused; they are cut into
        triangles with area, and written back whole."""
        src = os.path.join(self.dir.name, 'ngons.obj')
        nx, ny = 12, 4
        with open(src, 'w') as fh:
            for j in range(ny + 1):
                for i in range(nx + 1):
                    fh.write(f'v {i} {j} {0.05 * i * j}\n')
            faces = 0
            for j in range(ny):
                i, k = 0, 0
                while i < nx:
                    w = min((1, 2, 3)[k % 3], nx - i)
                    k += 1
                    bottom = [j * (nx + 1) + i + a + 1 for a in range(w + 1)]
                    top = [(j + 1) * (nx + 1) + i + w - a + 1 for a in range(w + 1)]
                    fh.write('f ' + ' '.join(map(str, bottom + top)) + '\n')
                    faces += 1
                    i += w
        for flags in ((), ('--atlas',)):
            rc, out, err = run(src, '-o', self.out, *flags)
            self.assertEqual(rc, 0, (flags, err))
            stats = json.loads(out)
            self.assertEqual(stats['stats']['flipped_triangles'], 0, flags)
            self.assertEqual(stats['stats']['zero_area_triangles'], 0, flags)
            _, _, f_out = obj_records(self.out)
            self.assertEqual(len(f_out), faces, flags)

    def test_an_output_that_is_a_pipe_or_a_link_is_written_through(self):
        """A pipe (or /dev/null, /dev/stdout) is written into, not replaced by a regular file
        renamed over it (as root that would replace /dev/null itself); a symbolic link is
        followed, so the file it names gets the OBJ and the link stays a link."""
        fifo = os.path.join(self.dir.name, 'pipe.obj')
        os.mkfifo(fifo)
        got = []
        reader = threading.Thread(target=lambda: got.append(open(fifo).read()), daemon=True)
        reader.start()
        rc, _, err = run(self.mesh('alligator.obj'), '-o', fifo)
        reader.join(timeout=60)
        self.assertEqual(rc, 0, err)
        self.assertTrue(stat.S_ISFIFO(os.stat(fifo).st_mode))
        self.assertEqual(len(got), 1)
        rc, _, err = run(self.mesh('alligator.obj'), '-o', self.out)
        self.assertEqual(rc, 0, err)
        with open(self.out) as fh:
            self.assertEqual(got[0], fh.read())
        os.mkdir(os.path.join(self.dir.name, 'real'))
        target = os.path.join(self.dir.name, 'real', 'mesh.obj')
        open(target, 'w').close()
        link = os.path.join(self.dir.name, 'link.obj')
        os.symlink(target, link)
        rc, _, err = run(self.mesh('alligator.obj'), '-o', link)
        self.assertEqual(rc, 0, err)
        self.assertTrue(os.path.islink(link))
        with open(target) as fh:
            self.assertEqual(got[0], fh.read())
        self.assertEqual(sorted(os.listdir(self.dir.name)), ['link.obj', 'out.obj', 'pipe.obj', 'real'])

    def test_vertices_no_face_uses_are_left_out_of_the_disk_and_the_sphere(self):
        """OBJ files may hold vertices no face uses (left by an editor, or a shared vertex list).
        The library's disk and sphere domains refuse them (RAPS_ERROR_ISOLATED_VERTEX); raps-param
        maps the vertices faces use, writes their vt in vertex order, and keeps every v line."""
        for name, flags in (('alligator.obj', ()), ('bunny.off', ('--sphere',))):
            v_in, _, f_in = obj_records(self.mesh(name)) if name.endswith('.obj') else (None, None, None)
            src = os.path.join(self.dir.name, 'stray.obj')
            rc, _, err = run(self.mesh(name), '-o', os.path.join(self.dir.name, 'plain.obj'), *flags)
            self.assertEqual(rc, 0, err)
            plain_v, _, plain_f = obj_records(os.path.join(self.dir.name, 'plain.obj'))
            # The mesh again with a stray vertex before its first and after its last.
            with open(src, 'w') as fh:
                fh.write('v 100 100 100\n')
                if name.endswith('.obj'):
                    for p in v_in:
                        fh.write('v %r %r %r\n' % p)
                    faces = [[c[0] + 1 for c in face] for face in f_in]
                else:
                    with open(self.mesh(name)) as off:
                        words = off.read().split()
                    nv, nf = int(words[1]), int(words[2])
                    numbers = words[4:]
                    for k in range(nv):
                        fh.write('v %s %s %s\n' % tuple(numbers[3 * k:3 * k + 3]))
                    faces, at = [], 3 * nv
                    for _ in range(nf):
                        n = int(numbers[at])
                        faces.append([int(x) + 2 for x in numbers[at + 1:at + 1 + n]])
                        at += n + 1
                fh.write('v -100 -100 -100\n')
                for face in faces:
                    fh.write('f ' + ' '.join(map(str, face)) + '\n')
            rc, out, err = run(src, '-o', self.out, *flags)
            self.assertEqual(rc, 0, (name, err))
            self.assertEqual(json.loads(out)['stats']['flipped_triangles'], 0)
            v_out, vt_out, f_out = obj_records(self.out)
            self.assertEqual(len(v_out), len(plain_v) + 2)
            self.assertEqual(v_out[0], (100.0, 100.0, 100.0))
            self.assertEqual(v_out[-1], (-100.0, -100.0, -100.0))
            self.assertEqual([[c[0] for c in f] for f in f_out], [[c[0] + 1 for c in f] for f in plain_f])
            if not flags:
                self.assertEqual(len(vt_out), len(plain_v))
                self.assertTrue(all(c[1] == c[0] - 1 for f in f_out for c in f))
            else:
                self.assertEqual(v_out[1:-1], plain_v)  # the same points on the sphere

    def test_json_reports_settings_stats_and_phase_times(self):
        rc, out, err = run(self.mesh('lion.off'), '-o', self.out, '--weights', 'uniform',
                           '--monitor', 'length', '--alpha', '1.5', '--iterations', '2',
                           '--iteration-mode', 'reapply', '--boundary', 'square')
        self.assertEqual(rc, 0, err)
        d = json.loads(out)
        self.assertEqual(d['settings'], {'domain': 'disk', 'weights': 'uniform', 'monitor': 'length',
                                         'alpha': 1.5, 'iterations': 2, 'iteration_mode': 'reapply',
                                         'boundary': 'square', 'max_triangles': 2147483647,
                                         'threads': 0})
        self.assertEqual(d['vertices'], 8356)
        self.assertEqual(d['triangles'], 16674)
        self.assertEqual(d['stats']['flipped_triangles'], 0)
        self.assertEqual(d['stats']['adaptive_solves'], 2)
        for phase in ('read', 'validate', 'topology', 'initial_map', 'adapt', 'metrics', 'write'):
            self.assertGreaterEqual(d['time_ms'][phase], 0.0)

    def test_atlas_writes_seams_as_separate_vt_and_echoes_its_settings(self):
        rc, out, err = run(self.mesh('teapot.obj'), '-o', self.out, '--atlas', '--threads', '2',
                           '--resolution', '512', '--padding', '3', '--hard-edge-angle', '80',
                           '--max-l2-stretch', '1.02', '--max-linf-stretch', '2.5', '--weld-tolerance', '1e-9')
        self.assertEqual(rc, 0, err)
        d = json.loads(out)
        s = d['settings']
        self.assertEqual((s['domain'], s['threads'], s['resolution'], s['padding']), ('atlas', 2, 512, 3))
        self.assertEqual((s['hard_edge_angle'], s['max_l2_stretch'], s['max_linf_stretch'], s['weld_tolerance']),
                         (80, 1.02, 2.5, 1e-9))
        st = d['stats']
        self.assertEqual(max(st['atlas_width'], st['atlas_height']), 512)
        self.assertLessEqual(st['stretch_linf'], 2.5)
        self.assertEqual(st['flipped_triangles'], 0)
        v_in, _, f_in = obj_records(self.mesh('teapot.obj'))
        v_out, vt_out, f_out = obj_records(self.out)
        self.assertEqual(v_out, v_in)
        self.assertEqual(len(f_out), len(f_in))  # teapot is all triangles: faces come back in order
        self.assertEqual([[c[0] for c in face] for face in f_out], [[c[0] for c in face] for face in f_in])
        self.assertGreater(len(vt_out), len(v_in) - 1)  # seams duplicate uv vertices
        for u, w in vt_out:
            self.assertTrue(0.0 <= u <= 1.0 and 0.0 <= w <= 1.0)
        ref = json.loads(subprocess.run(['/usr/bin/python3', os.path.join(DATA, '..', 'tools', 'uvmetrics.py'),
                                         '--raster', '2048', self.out], capture_output=True, text=True).stdout)
        self.assertEqual(ref['n_flipped'], 0)
        self.assertLess(ref['uv_overlap_fraction'], 0.002)  # raster noise only

    def assert_reference_metrics(self, ours, obj, relative, label):
        """Our statistics against uvmetrics.py's figures of `obj`, to `relative` precision."""
        p = subprocess.run(['/usr/bin/python3', os.path.join(DATA, '..', 'tools', 'uvmetrics.py'),
                            '--raster', '0', obj], capture_output=True, text=True, timeout=600)
        self.assertEqual(p.returncode, 0, p.stderr)
        ref = json.loads(p.stdout)
        self.assertEqual(ours['flipped_triangles'], ref['n_flipped'])
        self.assertEqual(ours['zero_area_triangles'], ref['n_degenerate_uv'])
        for key, ref_key in (('area_log_mean', 'area_mean_abs_log'), ('area_max', 'area_max'),
                             ('angle_mean_deg', 'angle_mean_deg'), ('angle_max_deg', 'angle_max_deg'),
                             ('stretch_l2', 'stretch_l2'), ('stretch_linf', 'stretch_linf')):
            self.assertAlmostEqual(ours[key], ref[ref_key], delta=relative * max(1.0, abs(ref[ref_key])),
                                   msg=f'{label} {key}')
        return ref

    def test_statistics_match_the_reference_metrics(self):
        for mesh, flags in (('camelhead.off', []), ('face.obj', ['--monitor', 'none']),
                            ('alligator.obj', ['--monitor', 'angle', '--alpha', '2'])):
            rc, out, err = run(self.mesh(mesh), '-o', self.out, *flags)
            self.assertEqual(rc, 0, err)
            # The OBJ stores uv with float-to-text rounding: agree to 1e-6 relative.
            self.assert_reference_metrics(json.loads(out)['stats'], self.out, 1e-6, mesh)

    def test_atlas_statistics_are_the_reference_metrics_in_texel_space(self):
        # At a resolution the atlas is square and uvs are texels over the resolution on both
        # axes: uvmetrics measures the vt lines as written, and finds the library's statistics
        # (alligator's one chart is 5.7 times as long as wide, so an atlas normalised per axis
        # would show it stretched 5.7 times). Pages at a density are cropped to their charts
        # and normalised per axis: uvmetrics agrees once the vt lines are scaled back by width
        # and height.
        texel_obj = os.path.join(self.dir.name, 'texels.obj')
        for mesh in ('alligator.obj', 'fandisk.obj'):
            rc, out, err = run('--atlas', self.mesh(mesh), '-o', self.out)
            self.assertEqual(rc, 0, err)
            ours = json.loads(out)['stats']
            self.assertEqual((ours['atlas_width'], ours['atlas_height']), (1024, 1024))
            # Measured: equal to 1e-10 relative (the JSON prints 10 significant digits).
            ref = self.assert_reference_metrics(ours, self.out, 1e-8, mesh)
            self.assertEqual(ours['charts'], ref['n_charts'])
            density = 0.7 * ours['texels_per_unit']
            rc, out, err = run('--atlas', self.mesh(mesh), '-o', self.out,
                               '--texels-per-unit', repr(density), '--max-size', '1024')
            self.assertEqual(rc, 0, err)
            ours = json.loads(out)['stats']
            width, height = ours['atlas_width'], ours['atlas_height']
            self.assertNotEqual(width, height)
            with open(self.out) as src, open(texel_obj, 'w') as dst:
                for line in src:
                    if line.startswith('vt '):
                        u, w = map(float, line.split()[1:3])
                        line = f'vt {u * width!r} {w * height!r}\n'
                    dst.write(line)
            ref = self.assert_reference_metrics(ours, texel_obj, 1e-8, mesh)
            self.assertEqual(ours['charts'], ref['n_charts'])

    def test_memory_cap_refuses_before_any_work_without_output(self):
        rc, out, err = run(self.mesh('face.obj'), '-o', self.out, '--max-memory-mb', '10')
        self.assertEqual(rc, 1)
        d = json.loads(out)
        self.assertEqual(d['error']['status_name'], 'mesh too large')
        self.assertIn('RAPS_PARAM_MAX_MEMORY_MB = 10', d['error']['message'])
        self.assertFalse(os.path.exists(self.out))
        rc, out, err = run(self.mesh('face.obj'), '-o', self.out, '--max-memory-mb', '1000')
        self.assertEqual(rc, 0, err)

    def test_bad_input_fails_cleanly_without_output(self):
        closed = self.mesh('bunny.off')
        rc, out, err = run(closed, '-o', self.out)
        self.assertEqual(rc, 1)
        d = json.loads(out)
        self.assertEqual(d['error']['status_name'], 'no boundary')
        self.assertIn('closed', d['error']['message'])
        self.assertIn('closed', err)
        self.assertFalse(os.path.exists(self.out))
        self.assertEqual(os.listdir(self.dir.name), [])  # no temporary file left behind

    def test_an_existing_output_survives_a_failed_run(self):
        with open(self.out, 'w') as fh:
            fh.write('keep me\n')
        rc, _, _ = run(self.mesh('teapot.obj'), '-o', self.out)
        self.assertEqual(rc, 1)
        with open(self.out) as fh:
            self.assertEqual(fh.read(), 'keep me\n')

    def test_malformed_files_are_reported_with_their_line(self):
        src = os.path.join(self.dir.name, 'broken.obj')
        with open(src, 'w') as fh:
            fh.write('v 0 0 0\nv 1 0 0\nv 0 1 zero\nf 1 2 3\n')
        rc, out, err = run(src, '-o', self.out)
        self.assertEqual(rc, 1)
        self.assertIn('broken.obj:3', err)
        with open(src, 'w') as fh:
            fh.write('v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n')
        rc, out, err = run(src, '-o', self.out)
        self.assertEqual(rc, 1)
        self.assertEqual(json.loads(out)['error']['status_name'], 'index out of range')
        rc, out, err = run(os.path.join(self.dir.name, 'missing.obj'), '-o', self.out)
        self.assertEqual(rc, 1)
        self.assertIn('cannot open', err)
        # Vertices without faces: named as such in every domain (the disk keeps no vertex
        # that no face uses, which once made it "no vertices").
        with open(src, 'w') as fh:
            fh.write('v 0 0 0\nv 1 0 0\nv 0 1 0\n')
        for domain in ([], ['--atlas'], ['--sphere']):
            rc, out, err = run(src, '-o', self.out, *domain)
            self.assertEqual(rc, 1)
            self.assertIn('broken.obj: no faces', json.loads(out)['error']['message'])
        src = os.path.join(self.dir.name, 'negative.off')
        with open(src, 'w') as fh:
            fh.write('OFF\n-3 1 0\n')
        rc, out, err = run(src, '-o', self.out)
        self.assertEqual(rc, 1)
        self.assertIn('negative.off:2: the vertex count is negative', err)
        self.assertFalse(os.path.exists(self.out))

    def test_obj_and_off_as_exporters_write_them(self):
        """The forms real files take read as the plain file does: a byte order mark, comments
        after a face, line continuations, CRLF, lines ended by CR alone (classic Mac OS), tabs, no
        final newline, relative indices, vt/vn corners; Geomview's COFF and NOFF (numbers after
        x y z), and ModelNet's header with the vertex count run into it. 4D and binary OFF are
        refused by name."""
        points = ['0 0 0', '1 0 0', '1 1 0.2', '0 1 0', '0.5 0.5 0.1']
        faces = [(1, 2, 5), (2, 3, 5), (3, 4, 5), (4, 1, 5)]
        plain = ''.join('v %s\n' % p for p in points) + ''.join('f %d %d %d\n' % f for f in faces)
        obj_forms = {
            'bom': '\ufeff' + plain,
            'comments': plain.replace('f 2 3 5', 'f 2 3 5 # quad half').replace('v 1 0 0', 'v 1 0 0 1'),
            'continuation': plain.replace('f 3 4 5', 'f 3 \\\n 4 \\\r\n5'),
            'crlf_tabs': plain.replace('\n', '\r\n').replace(' ', '\t').rstrip(),
            'cr': plain.replace('\n', '\r'),
            'relative': ''.join('v %s\n' % p for p in points) +
                        ''.join('f %d/%d/1 %d//1 -1\n' % (a - 6, a, b) for a, b, _ in faces) +
                        'vn 0 0 1\n',
        }
        off = ['%d %d 0' % (len(points), len(faces))] + points + \
              ['3 %d %d %d' % tuple(i - 1 for i in f) for f in faces]
        off_forms = {
            'coff': 'COFF\n' + '\n'.join(off[:1] + [p + ' 255 0 0 255' for p in points] + off[6:]),
            'noff': 'NOFF\n' + '\n'.join(off[:1] + [p + ' 0 0 1' for p in points] + off[6:]),
            'modelnet': 'OFF' + '\n'.join(off) + '\n',
            'crlf': 'OFF\r\n' + '\r\n'.join(off),
            'cr': '# exported\rOFF\r' + '\r'.join(off),
        }
        expected = None
        for name, text in [('plain.obj', plain)] + [(k + '.obj', v) for k, v in obj_forms.items()] + \
                [(k + '.off', v) for k, v in off_forms.items()]:
            src = os.path.join(self.dir.name, name)
            with open(src, 'w', encoding='utf-8', newline='') as fh:
                fh.write(text)
            rc, out, err = run(src, '-o', self.out)
            self.assertEqual(rc, 0, name + ': ' + err)
            v, _, f = obj_records(self.out)
            got = (v, [[c[0] for c in face] for face in f])
            expected = expected or got
            self.assertEqual(got, expected, name)
        os.remove(self.out)
        for name, text in (('four.off', '4OFF\n1 0 0\n0 0 0 0\n'),
                           ('binary.off', 'OFF BINARY\n')):
            src = os.path.join(self.dir.name, name)
            with open(src, 'w') as fh:
                fh.write(text)
            rc, out, err = run(src, '-o', self.out)
            self.assertEqual(rc, 1)
            self.assertIn('4OFF' if name == 'four.off' else 'binary OFF', err)
            self.assertFalse(os.path.exists(self.out))

    def test_ply_reads_as_the_same_mesh_in_every_encoding(self):
        """A real mesh written as ASCII and both binary byte orders of PLY (with a colour per
        vertex, another element, other list types) maps as its OFF does; PLY whose counts or
        lists run past the file, negative or fractional indices, or no faces are refused."""
        import struct
        rc, _, err = run(self.mesh('lion.off'), '--atlas', '-o', self.out)
        self.assertEqual(rc, 0, err)
        expected = obj_records(self.out)
        with open(self.mesh('lion.off')) as fh:
            tokens = [t for line in fh for t in line.split('#')[0].split()]
        nv, nf = int(tokens[1]), int(tokens[2])
        points = [tuple(map(float, tokens[4 + 3 * i:7 + 3 * i])) for i in range(nv)]
        at, faces = 4 + 3 * nv, []
        for _ in range(nf):
            k = int(tokens[at])
            faces.append(tuple(int(x) for x in tokens[at + 1:at + 1 + k]))
            at += 1 + k

        def header(fmt, face='property list uchar int vertex_indices', tail=''):
            return ('ply\nformat %s 1.0\ncomment test\nelement vertex %d\nproperty double x\n'
                    'property double y\nproperty double z\nproperty uchar red\nelement face %d\n'
                    '%s\n%send_header\n' % (fmt, nv, nf, face, tail)).encode()
        files = {'ascii.ply': header('ascii') +
                 b''.join(b'%r %r %r 7\n' % p for p in points) +
                 b''.join(b'%d %s\n' % (len(q), ' '.join(map(str, q)).encode()) for q in faces)}
        for name, e in (('little.ply', '<'), ('big.ply', '>')):
            files[name] = header('binary_%s_endian' % name[:-4]) + \
                b''.join(struct.pack(e + 'dddB', *p, 7) for p in points) + \
                b''.join(struct.pack(e + 'B%di' % len(q), len(q), *q) for q in faces)
        files['lists.ply'] = header('binary_little_endian', 'property list ushort uint vertex_index',
                                    'element edge 1\nproperty int a\n') + \
            b''.join(struct.pack('<dddB', *p, 7) for p in points) + \
            b''.join(struct.pack('<H%dI' % len(q), len(q), *q) for q in faces) + b'\0' * 4
        for name, data in files.items():
            src = os.path.join(self.dir.name, name)
            with open(src, 'wb') as fh:
                fh.write(data)
            rc, _, err = run(src, '--atlas', '-o', self.out)
            self.assertEqual(rc, 0, name + ': ' + err)
            self.assertEqual(obj_records(self.out), expected, name)
        os.remove(self.out)
        small = header('ascii').replace(b'vertex %d' % nv, b'vertex 3').replace(b'face %d' % nf, b'face 1')
        for name, data, words in (
                ('huge.ply', header('binary_little_endian'), 'more than the file holds'),
                ('negative.ply', small + b'0 0 0 1\n1 0 0 1\n0 1 0 1\n3 0 1 -2\n', 'invalid vertex index'),
                ('fraction.ply', small + b'0 0 0 1\n1 0 0 1\n0 1 0 1\n3 0 1 1.5\n', 'invalid vertex index'),
                ('cut.ply', small + b'0 0 0 1\n1 0 0 1\n0 1 0 1\n3 0 1', 'ends inside'),
                ('points.ply', b'ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n'
                               b'property float y\nproperty float z\nend_header\n0 0 0\n', 'no face')):
            src = os.path.join(self.dir.name, name)
            with open(src, 'wb') as fh:
                fh.write(data)
            rc, out, err = run(src, '--atlas', '-o', self.out)
            self.assertEqual(rc, 1, name)
            self.assertIn(words, err, name)
            self.assertFalse(os.path.exists(self.out), name)

    def test_usage_errors_exit_2(self):
        for args in ([], [self.mesh('lion.off')], [self.mesh('lion.off'), '-o', self.out, '--monitor', 'bogus'],
                     [self.mesh('lion.off'), '-o', self.out, '--alpha', '-1'],
                     [self.mesh('lion.off'), '-o', self.out, '--iterations', '2.5'],
                     [self.mesh('lion.off'), '-o', self.out, '--frobnicate']):
            rc, out, err = run(*args)
            self.assertEqual(rc, 2, args)
            self.assertIn('error', json.loads(out))
            self.assertFalse(os.path.exists(self.out))

    def test_help_documents_every_flag(self):
        rc, out, _ = run('--help')
        self.assertEqual(rc, 0)
        for flag in ('--output', '--weights', '--monitor', '--alpha', '--iterations',
                     '--iteration-mode', '--boundary', '--max-triangles', '--max-memory-mb',
                     '--version',
                     '--sphere', '--sphere-method', '--sphere-uv', '--threads', '--damping',
                     '--tolerance', '--max-sweeps', '--alpha-steps', '--texels-per-unit',
                     '--max-size', '--rotate', '--margin', '--block-align', '--mesh-per-page',
                     '--whole-texels', '--lightmap', '--keep-uv-seams', '--obj-groups', '--repack',
                     '--stack', '--stack-mirrored', '--stack-tolerance'):
            self.assertIn(flag, out)

    def test_sphere_writes_the_points_on_the_unit_sphere(self):
        rc, out, err = run('--sphere', self.mesh('spot.obj'), '-o', self.out)
        self.assertEqual(rc, 0, err)
        d = json.loads(out)
        self.assertEqual(d['settings']['domain'], 'sphere')
        self.assertEqual(d['settings']['sphere_method'], 'robust')
        self.assertEqual(d['settings']['sphere_uv'], 'none')
        self.assertEqual(d['stats']['flipped_triangles'], 0)
        self.assertGreater(d['stats']['relaxation_sweeps'], 0)
        self.assertLess(d['stats']['area_log_mean'], 0.72)  # measured 0.689 (docs/bench-method.md)
        for phase in ('validate', 'topology', 'initial_map', 'adapt', 'metrics'):
            self.assertGreaterEqual(d['time_ms'][phase], 0.0)
        v_in, _, f_in = obj_records(self.mesh('spot.obj'))
        v_out, vt_out, f_out = obj_records(self.out)
        self.assertEqual(len(v_out), len(v_in))
        self.assertEqual(vt_out, [])
        self.assertEqual([[c[0] for c in face] for face in f_out], [[c[0] for c in face] for face in f_in])
        for p in v_out:
            self.assertAlmostEqual(sum(x * x for x in p), 1.0, delta=1e-12)

    def test_sphere_octahedral_uvs_are_one_chart_with_seams(self):
        rc, out, err = run('--sphere', self.mesh('spot.obj'), '-o', self.out,
                           '--sphere-uv', 'octahedral', '--threads', '1')
        self.assertEqual(rc, 0, err)
        d = json.loads(out)
        self.assertEqual(d['settings']['sphere_uv'], 'octahedral')
        self.assertEqual(d['stats']['flipped_triangles'], 0)
        v_in, _, f_in = obj_records(self.mesh('spot.obj'))
        v_out, vt_out, f_out = obj_records(self.out)
        self.assertEqual(len(v_out), len(v_in))     # v: the sphere points, input order
        self.assertEqual(len(vt_out), d['vertices'])  # vt: one per output vertex
        self.assertGreater(len(vt_out), len(v_in))    # the seams' vertices, once per side
        self.assertEqual([[c[0] for c in face] for face in f_out], [[c[0] for c in face] for face in f_in])
        signed = 0.0
        for face in f_out:
            a, b, c = (vt_out[corner[1] - 1] for corner in face)
            area = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
            self.assertGreater(area, 0.0)
            signed += area
        self.assertAlmostEqual(signed, 1.0, delta=1e-6)  # the whole square, once
        for u, w in vt_out:
            self.assertTrue(0.0 <= u <= 1.0 and 0.0 <= w <= 1.0)

    def test_sphere_literal_method_and_its_settings(self):
        rc, out, err = run('--sphere', self.mesh('spot.obj'), '-o', self.out,
                           '--sphere-method', 'literal', '--monitor', 'none', '--damping', '0.5',
                           '--max-sweeps', '200', '--tolerance', '1e-6', '--threads', '2',
                           '--alpha-steps', '2')
        self.assertEqual(rc, 0, err)
        d = json.loads(out)
        self.assertEqual(d['settings'], {'domain': 'sphere', 'weights': 'mvc', 'monitor': 'none',
                                         'alpha': 1, 'iterations': 1, 'iteration_mode': 'accumulate',
                                         'sphere_method': 'literal', 'sphere_uv': 'none', 'threads': 2,
                                         'damping': 0.5, 'tolerance': 1e-6, 'max_sweeps': 200,
                                         'alpha_steps': 2, 'max_triangles': 2147483647})
        self.assertEqual(d['stats']['relaxation_sweeps'], 200)

    def test_sphere_refuses_open_meshes_and_handles(self):
        for mesh, status, fragment in (('alligator.obj', 'open mesh', '1 boundary loop'),
                                       ('rocker-arm.obj', 'genus greater than zero', 'genus 1')):
            rc, out, err = run('--sphere', self.mesh(mesh), '-o', self.out)
            self.assertEqual(rc, 1, mesh)
            d = json.loads(out)
            self.assertTrue(d['error']['status_name'].startswith(status), d)
            self.assertIn(fragment, d['error']['message'])
            self.assertFalse(os.path.exists(self.out))

    def test_sphere_usage_errors_exit_2(self):
        for args in (['--sphere-method', 'bogus'], ['--sphere-uv', 'cube'], ['--damping', '2'],
                     ['--threads', '-1'], ['--max-sweeps', '1.5']):
            rc, out, err = run('--sphere', self.mesh('spot.obj'), '-o', self.out, *args)
            self.assertEqual(rc, 2, args)
            self.assertIn('error', json.loads(out))
            self.assertFalse(os.path.exists(self.out))
        # Two domains asked for: the last flag won in silence.
        for flags in (['--sphere', '--atlas'], ['--atlas', '--sphere'], ['--sphere', '--lightmap'],
                      ['--repack', '--sphere']):
            rc, out, err = run(*flags, self.mesh('spot.obj'), '-o', self.out)
            self.assertEqual(rc, 2, flags)
            self.assertIn('choose different domains', err, flags)
            self.assertFalse(os.path.exists(self.out))

    def objects(self, path):
        """The OBJ's objects in order: (name, v, vt, f) with v and vt indices made 0-based and
        local to the object."""
        objects = []
        v_seen = vt_seen = 0
        with open(path) as fh:
            for line in fh:
                parts = line.split()
                if not parts:
                    continue
                if parts[0] == 'o':
                    if objects:
                        v_seen += len(objects[-1][1])
                        vt_seen += len(objects[-1][2])
                    objects.append((parts[1], [], [], []))
                elif parts[0] == 'v':
                    objects[-1][1].append(tuple(map(float, parts[1:4])))
                elif parts[0] == 'vt':
                    objects[-1][2].append(tuple(map(float, parts[1:3])))
                elif parts[0] == 'f':
                    corners = [tuple(int(x) for x in c.split('/')) for c in parts[1:]]
                    objects[-1][3].append([(a - 1 - v_seen, b - 1 - vt_seen) for a, b in corners])
        return objects

    def test_atlas_of_several_inputs_writes_one_object_per_input_in_order(self):
        names = ['teapot.obj', 'spot.obj', 'teapot.obj']
        rc, out, err = run('--atlas', *[self.mesh(n) for n in names], '-o', self.out,
                           '--threads', '2', '--padding', '2')
        self.assertEqual(rc, 0, err)
        d = json.loads(out)
        objects = self.objects(self.out)
        self.assertEqual([o[0] for o in objects], ['teapot', 'spot', 'teapot'])
        for name, (obj_name, v, vt, f) in zip(names, objects):
            v_in, _, f_in = obj_records(self.mesh(name))
            self.assertEqual(v, v_in)  # every input's vertices, in order
            self.assertEqual([[c[0] for c in face] for face in f],
                             [[c[0] - 1 for c in face] for face in f_in])
            for face in f:
                for _, t in face:
                    self.assertTrue(0 <= t < len(vt))  # an object's faces use its own vt
            for u, w in vt:
                self.assertTrue(0.0 <= u <= 1.0 and 0.0 <= w <= 1.0)
        self.assertEqual([i['input'] for i in d['inputs']], [self.mesh(n) for n in names])
        self.assertEqual([i['triangles'] for i in d['inputs']], [len(o[3]) for o in objects])
        self.assertEqual([i['output_vertices'] for i in d['inputs']], [len(o[2]) for o in objects])
        st = d['stats']
        self.assertEqual(len(d['charts']), st['charts'])
        self.assertEqual(sum(i['charts'] for i in d['inputs']), st['charts'])
        self.assertEqual(len(d['pages']), st['pages'])
        self.assertEqual(max(st['atlas_width'], st['atlas_height']), 1024)
        # One density: the two teapots get the same texels.
        self.assertAlmostEqual(d['inputs'][0]['area_texels'] / d['inputs'][2]['area_texels'], 1.0,
                               delta=0.02)
        ref = json.loads(subprocess.run(['/usr/bin/python3', os.path.join(DATA, '..', 'tools', 'uvmetrics.py'),
                                         '--raster', '2048', self.out], capture_output=True, text=True).stdout)
        self.assertEqual(ref['n_flipped'], 0)
        self.assertLess(ref['uv_overlap_fraction'], 0.002)  # raster noise only

    def test_lightmap_packs_at_a_density_on_pages_within_the_maximum(self):
        rc, out, err = run('--atlas', self.mesh('teapot.obj'), self.mesh('spot.obj'), '-o', self.out,
                           '--lightmap', '--texels-per-unit', '40', '--max-size', '256')
        self.assertEqual(rc, 0, err)
        d = json.loads(out)
        s, st = d['settings'], d['stats']
        self.assertEqual((s['texels_per_unit'], s['max_width'], s['max_height'], s['rotate'],
                          s['padding'], s['mesh_per_page']), (40, 256, 256, 'quarter', 2, True))
        self.assertEqual(st['texels_per_unit'], 40)
        self.assertGreaterEqual(st['pages'], 2)
        self.assertLessEqual(max(st['atlas_width'], st['atlas_height']), 256)
        page_of_input = {}
        for chart in d['charts']:
            self.assertEqual(chart['rotation_deg'] % 90, 0)
            self.assertEqual(page_of_input.setdefault(chart['input'], chart['page']), chart['page'])
            self.assertLessEqual(chart['x'] + chart['width'], st['atlas_width'])
            self.assertLessEqual(chart['y'] + chart['height'], st['atlas_height'])
            if not chart['scaled_down']:
                self.assertAlmostEqual(chart['area_texels'] / chart['area_3d'], 1600, delta=32)
        for page in d['pages']:
            self.assertTrue(0 < page['utilization'] <= 1)

    def test_lightmap_at_a_resolution_packs_whole_texels_on_one_page(self):
        rc, out, err = run('--atlas', self.mesh('teapot.obj'), self.mesh('spot.obj'), '-o', self.out,
                           '--lightmap', '--resolution', '256')
        self.assertEqual(rc, 0, err)
        d = json.loads(out)
        s, st = d['settings'], d['stats']
        self.assertEqual((s['whole_texels'], s['texels_per_unit'], s['rotate'], s['padding']),
                         (True, 0, 'quarter', 2))
        self.assertEqual((st['pages'], st['scaled_down_charts']), (1, 0))
        self.assertLessEqual(max(st['atlas_width'], st['atlas_height']), 256)
        self.assertGreater(st['texels_per_unit'], 0)
        for chart in d['charts']:
            self.assertEqual(chart['rotation_deg'] % 90, 0)
            self.assertAlmostEqual(chart['area_texels'] / chart['area_3d'], st['texels_per_unit'] ** 2,
                                   delta=0.02 * st['texels_per_unit'] ** 2)

    def test_block_alignment_margin_and_no_rotation_are_echoed_and_kept(self):
        rc, out, err = run('--atlas', self.mesh('spot.obj'), '-o', self.out, '--texels-per-unit', '200',
                           '--max-size', '512', '--block-align', '--margin', '3', '--rotate', 'none')
        self.assertEqual(rc, 0, err)
        d = json.loads(out)
        s, st = d['settings'], d['stats']
        self.assertEqual((s['block_align'], s['margin'], s['rotate']), (True, 3, 'none'))
        self.assertEqual((st['atlas_width'] % 4, st['atlas_height'] % 4), (0, 0))
        for chart in d['charts']:
            self.assertEqual(chart['rotation_deg'], 0)
            self.assertGreaterEqual(min(chart['x'], chart['y']), 4)  # 3 rounded up to a block
            self.assertLessEqual(chart['x'] + chart['width'] + 4, st['atlas_width'])

    def write_grid(self, name, n, face_prefix):
        """An n x n grid of quads in the plane; face_prefix(i, j) gives the lines before quad
        (i, j) and its corners' vt indices (or None for `f v`). One vt per grid vertex and side:
        vt k on the left half, k + (n + 1)^2 on the right."""
        path = os.path.join(self.dir.name, name)
        lines = [f'v {i / n} {j / n} 0' for j in range(n + 1) for i in range(n + 1)]
        lines += [f'vt {i / n} {j / n}' for _ in range(2) for j in range(n + 1) for i in range(n + 1)]
        for j in range(n):
            for i in range(n):
                prefix, vt_offset = face_prefix(i, j)
                lines += prefix
                corners = [j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1,
                           (j + 1) * (n + 1) + i]
                lines.append('f ' + ' '.join(f'{c + 1}' if vt_offset is None else
                                             f'{c + 1}/{c + 1 + vt_offset}' for c in corners))
        with open(path, 'w') as fh:
            fh.write('\n'.join(lines) + '\n')
        return path

    def faces_joined_across(self, obj, label):
        """Pairs of faces with different labels (per face, in order) that share a `v` edge and
        both its `vt`: one chart holds both."""
        _, _, faces = obj_records(obj)
        edges = {}
        for f, face in enumerate(faces):
            for k in range(len(face)):
                a, b = face[k], face[(k + 1) % len(face)]
                edges.setdefault(frozenset((a[0], b[0])), []).append((f, {a[0]: a[1], b[0]: b[1]}))
        joined = 0
        for sides in edges.values():
            for (f, vt_f), (g, vt_g) in zip(sides, sides[1:]):
                joined += label[f] != label[g] and vt_f == vt_g
        return joined

    def test_keep_uv_seams_keeps_the_files_vt_splits_as_chart_boundaries(self):
        n = 8
        grid = self.write_grid('split.obj', n, lambda i, j: ([], 0 if i < n // 2 else (n + 1) ** 2))
        # The output is written face by face (triangles where a seam crosses a quad), so the
        # side of each output face is read from its first vertex's position and its others.
        def sides(obj):
            v, _, faces = obj_records(obj)
            return [int(sum(v[c[0] - 1][0] for c in face) / len(face) > 0.5) for face in faces]
        rc, out, err = run(grid, '-o', self.out, '--atlas')
        self.assertEqual(rc, 0, err)
        self.assertGreater(self.faces_joined_across(self.out, sides(self.out)), 0)
        self.assertFalse(json.loads(out)['settings']['keep_uv_seams'])
        rc, out, err = run(grid, '-o', self.out, '--atlas', '--keep-uv-seams')
        self.assertEqual(rc, 0, err)
        self.assertTrue(json.loads(out)['settings']['keep_uv_seams'])
        self.assertEqual(self.faces_joined_across(self.out, sides(self.out)), 0)
        v_in, _, _ = obj_records(grid)
        v_out, _, _ = obj_records(self.out)
        self.assertEqual(v_out, v_in)  # the file's own `v`, not the split vertices
        # Without vt on every corner, there are no seams to keep: refused, no output.
        os.remove(self.out)
        rc, out, err = run(self.mesh('suzanne.obj'), '-o', self.out, '--atlas', '--keep-uv-seams')
        self.assertEqual(rc, 1)
        self.assertIn('needs an OBJ whose every face corner names a vt', json.loads(out)['error']['message'])
        self.assertFalse(os.path.exists(self.out))

    def test_obj_groups_keep_charts_within_a_group_and_usemtl(self):
        n = 8
        def prefix(i, j):
            lines = []
            if i == 0:
                lines.append('g bottom' if j < n // 2 else 'g top')
            if i == 0 or i == n // 2:
                lines.append('usemtl left' if i < n // 2 else 'usemtl right')
            return lines, None
        grid = self.write_grid('groups.obj', n, prefix)
        quads = [(i, j) for j in range(n) for i in range(n)]
        label = [(2 * (j < n // 2) + (i < n // 2)) for i, j in quads]
        rc, _, err = run(grid, '-o', self.out, '--atlas')
        self.assertEqual(rc, 0, err)
        _, _, faces = obj_records(self.out)
        self.assertEqual(len(faces), len(quads))  # one chart: quads come back whole
        self.assertGreater(self.faces_joined_across(self.out, label), 0)
        rc, _, err = run(grid, '-o', self.out, '--atlas', '--obj-groups')
        self.assertEqual(rc, 0, err)
        _, _, faces = obj_records(self.out)
        self.assertEqual(len(faces), len(quads))  # groups follow the quads: none is cut
        self.assertEqual(self.faces_joined_across(self.out, label), 0)

    @staticmethod
    def face_sizes(path):
        """Corners per face of an OBJ or OFF file, in order."""
        if path.endswith('.obj'):  # corners may be `v//vn`: only counted
            with open(path) as fh:
                return [len(line.split()) - 1 for line in fh if line.split()[:1] == ['f']]
        with open(path) as fh:
            words = [line.split() for line in fh if line.strip() and not line.startswith('#')]
        vertices, faces = int(words[1][0]), int(words[1][1])
        return [int(w[0]) for w in words[2 + vertices:2 + vertices + faces]]

    @staticmethod
    def split_polygons(sizes, faces):
        """Input polygons (corners per face, in order) whose corners get more than one vt at a
        vertex in the output: raps-param writes each polygon whole or as its fan triangles, in
        order, so the triangles are gathered back into their polygon."""
        split, at = 0, 0
        for n in sizes:
            parts = [faces[at]] if len(faces[at]) == n else faces[at:at + n - 2]
            at += len(parts)
            vt_of = {}
            for face in parts:
                for v, vt in ((c[0], c[1]) for c in face):
                    vt_of.setdefault(v, set()).add(vt)
            split += any(len(vts) > 1 for vts in vt_of.values())
        assert at == len(faces), (at, len(faces))
        return split

    def test_atlas_keeps_each_polygon_whole_unless_asked_to_split(self):
        # halftunnel.off is all quads, suzanne.obj mostly quads: by default a face's triangles
        # are one unit to the atlas, so every corner of it gets one vt and it is written whole.
        for name in ('halftunnel.off', 'suzanne.obj'):
            sizes = self.face_sizes(self.mesh(name))
            rc, out, err = run('--atlas', self.mesh(name), '-o', self.out)
            self.assertEqual(rc, 0, err)
            self.assertTrue(json.loads(out)['whole_polygons'])
            _, _, faces = obj_records(self.out)
            self.assertEqual([len(face) for face in faces], sizes, name)
            self.assertEqual(self.split_polygons(sizes, faces), 0, name)
            # --split-polygons: the triangles apart, as in a triangle mesh; charts cut quads.
            rc, out, err = run('--atlas', self.mesh(name), '-o', self.out, '--split-polygons')
            self.assertEqual(rc, 0, err)
            self.assertFalse(json.loads(out)['whole_polygons'])
            _, _, faces = obj_records(self.out)
            self.assertGreater(self.split_polygons(sizes, faces), 0, name)
        # Several inputs, stacked, keep theirs whole too; --repack reads its vt islands as they
        # are (no polygons passed); the flag is in the help.
        names = ('halftunnel.off', 'suzanne.obj', 'halftunnel.off')
        rc, out, err = run('--atlas', *[self.mesh(n) for n in names], '-o', self.out, '--stack')
        self.assertEqual(rc, 0, err)
        self.assertTrue(json.loads(out)['whole_polygons'])
        _, _, faces = obj_records(self.out)
        sizes = sum((self.face_sizes(self.mesh(n)) for n in names), [])
        self.assertEqual([len(face) for face in faces], sizes)
        self.assertEqual(self.split_polygons(sizes, faces), 0)
        first = os.path.join(self.dir.name, 'first.obj')
        os.replace(self.out, first)
        rc, out, err = run('--atlas', first, '-o', self.out, '--repack')
        self.assertEqual(rc, 0, err)
        self.assertFalse(json.loads(out)['whole_polygons'])
        rc, out, _ = run('--help')
        self.assertIn('--split-polygons', out)

    @staticmethod
    def vt_islands(faces):
        """Faces joined by a shared corner (position, uv) pair, each corner given as such a
        pair: in a raps atlas no two charts share a uv (padding keeps them apart), and a chart's
        faces are joined through its corners, also where the file splits a vertex. Island label
        per face."""
        parent = list(range(len(faces)))
        def root(x):
            while parent[x] != x:
                parent[x] = parent[parent[x]]
                x = parent[x]
            return x
        first_face = {}
        for i, face in enumerate(faces):
            for _, t in face:
                j = first_face.setdefault(t, i)
                parent[root(i)] = root(j)
        return [root(i) for i in range(len(faces))]

    def test_repack_keeps_each_inputs_vt_islands_and_packs_them_at_one_density(self):
        firsts = []
        for name in ('teapot.obj', 'spot.obj'):
            first = os.path.join(self.dir.name, 'first_' + name)
            rc, out, err = run('--atlas', self.mesh(name), '-o', first)
            self.assertEqual(rc, 0, err)
            firsts.append((first, json.loads(out)['stats']['charts']))
        rc, out, err = run('--atlas', *[f for f, _ in firsts], '-o', self.out, '--repack',
                           '--texels-per-unit', '200', '--rotate', 'quarter', '--padding', '2')
        self.assertEqual(rc, 0, err)
        d = json.loads(out)
        s, st = d['settings'], d['stats']
        self.assertEqual((s['repack'], s['rotate'], s['texels_per_unit']), (True, 'quarter', 200))
        self.assertEqual(st['adaptive_solves'], 0)
        self.assertEqual([i['charts'] for i in d['inputs']], [c for _, c in firsts])
        width, height = st['atlas_width'], st['atlas_height']
        for (first, _), (name, v, vt, faces) in zip(firsts, self.objects(self.out)):
            v_in, vt_in, f_in = obj_records(first)
            self.assertEqual(v, v_in)
            self.assertEqual([[c[0] for c in face] for face in faces],
                             [[c[0] - 1 for c in face] for face in f_in])
            label = self.vt_islands([[(v_in[c[0] - 1], vt_in[c[1] - 1]) for c in face]
                                     for face in f_in])
            # Per island, one similarity out = z * in + t (complex numbers) takes the input's
            # vt to the output's texels: moved, turned by quarter turns, uniformly scaled.
            corners = {}
            for face_in, face_out, island in zip(f_in, faces, label):
                for c_in, c_out in zip(face_in, face_out):
                    a = complex(*vt_in[c_in[1] - 1])
                    b = complex(vt[c_out[1]][0] * width, vt[c_out[1]][1] * height)
                    corners.setdefault(island, []).append((a, b))
            self.assertEqual(len(corners), dict(firsts)[first])
            for pairs in corners.values():
                a0, b0 = pairs[0]
                a1, b1 = max(pairs, key=lambda p: abs(p[0] - a0))
                z = (b1 - b0) / (a1 - a0)
                for a, b in pairs:
                    self.assertLess(abs(b - (b0 + z * (a - a0))), 1e-4 * abs(b1 - b0) + 1e-6)
                turn = math.degrees(math.atan2(z.imag, z.real)) % 90
                self.assertLess(min(turn, 90 - turn), 1e-4)
        for chart in d['charts']:
            self.assertEqual(chart['rotation_deg'] % 90, 0)
            if not chart['scaled_down']:
                self.assertAlmostEqual(chart['area_texels'] / chart['area_3d'], 40000, delta=40)
        ref = json.loads(subprocess.run(['/usr/bin/python3', os.path.join(DATA, '..', 'tools', 'uvmetrics.py'),
                                         '--raster', '2048', self.out], capture_output=True, text=True).stdout)
        self.assertEqual(ref['n_flipped'], 0)
        self.assertLess(ref['uv_overlap_fraction'], 0.002)  # raster noise only

    def test_repack_needs_a_vt_on_every_corner(self):
        rc, out, err = run(self.mesh('suzanne.obj'), '-o', self.out, '--repack')
        self.assertEqual(rc, 1)
        error = json.loads(out)['error']
        self.assertEqual(error['status'], 26)  # RAPS_ERROR_UV_COUNT
        self.assertIn('--repack needs an OBJ whose every face corner names a vt', error['message'])
        self.assertFalse(os.path.exists(self.out))
        # A vt that is not a number is the library's non-finite uv, naming the corner.
        bad = os.path.join(self.dir.name, 'bad.obj')
        with open(bad, 'w') as fh:
            fh.write('v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt x 0\nvt 0 1\nf 1/1 2/2 3/3\n')
        rc, out, err = run(bad, '-o', self.out, '--repack')
        self.assertEqual(rc, 1)
        self.assertEqual(json.loads(out)['error']['status'], 27)  # RAPS_ERROR_NON_FINITE_UV
        self.assertFalse(os.path.exists(self.out))

    def test_stack_gives_an_input_repeated_its_originals_texels(self):
        names = ['spot.obj', 'teapot.obj', 'spot.obj']
        rc, out, err = run('--atlas', *[self.mesh(n) for n in names], '-o', self.out,
                           '--stack', '--threads', '2')
        self.assertEqual(rc, 0, err)
        d = json.loads(out)
        self.assertEqual((d['settings']['stack'], d['settings']['stack_tolerance']), ('rigid', 1e-4))
        charts = d['charts']
        for index, chart in enumerate(charts):
            place = charts[chart['stacked_on']]
            if chart['input'] == 2:  # the repeated spot: every chart on one of the first's
                self.assertLess(chart['stacked_on'], index)
                self.assertEqual(place['input'], 0)
                self.assertEqual([place[k] for k in ('page', 'x', 'y', 'width', 'height')],
                                 [chart[k] for k in ('page', 'x', 'y', 'width', 'height')])
            else:
                self.assertEqual(chart['stacked_on'], index)
        self.assertEqual(d['inputs'][2]['charts'], d['inputs'][0]['charts'])
        # Corner for corner, the repeated spot's vt are the first's.
        first, _, third = self.objects(self.out)
        self.assertEqual([[first[2][t] for _, t in face] for face in first[3]],
                         [[third[2][t] for _, t in face] for face in third[3]])
        # Each shared place counted once.
        st = d['stats']
        placed = sum(c['area_texels'] for i, c in enumerate(charts) if c['stacked_on'] == i)
        self.assertAlmostEqual(st['utilization'], placed / (st['atlas_width'] * st['atlas_height']),
                               places=6)
        self.assertAlmostEqual(d['pages'][0]['utilization'], st['utilization'], places=6)
        rc, out, err = run('--atlas', self.mesh('spot.obj'), '-o', self.out, '--stack-mirrored',
                           '--stack-tolerance', '0.01')
        self.assertEqual(rc, 0, err)
        s = json.loads(out)['settings']
        self.assertEqual((s['stack'], s['stack_tolerance']), ('mirrored', 0.01))

    def test_scene_usage_errors_exit_2(self):
        spot, teapot = self.mesh('spot.obj'), self.mesh('teapot.obj')
        for args in ([spot, teapot, '-o', self.out],  # several inputs need --atlas
                     ['--atlas', spot, '-o', self.out, '--rotate', 'sideways'],
                     ['--atlas', spot, '-o', self.out, '--max-size', '8'],
                     ['--atlas', spot, '-o', self.out, '--texels-per-unit', '-2'],
                     ['--atlas', spot, '-o', self.out, '--stack', '--lightmap'],
                     ['--atlas', spot, '-o', self.out, '--stack-tolerance', '0.5']):
            rc, out, err = run(*args)
            self.assertEqual(rc, 2, args)
            self.assertIn('error', json.loads(out))
            self.assertFalse(os.path.exists(self.out))


if __name__ == '__main__':
    RAPS_PARAM, DATA = sys.argv[1], os.path.abspath(sys.argv[2])
    unittest.main(argv=sys.argv[:1], verbosity=2)
