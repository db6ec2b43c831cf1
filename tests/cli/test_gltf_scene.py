"""raps-gltf --group scene end to end on the shared glTF assets: one atlas for every mesh the
default scene draws, each at its world scale. Measured here from the written files alone (world
matrices from the nodes, areas from the positions and the new uvs): every mesh gets the density
asked within 2 %; no page exceeds --max-size and each mesh's page is in its extras; charts too
large for a page are shrunk, flagged and noted; --lightmap keeps TEXCOORD_0 and writes
TEXCOORD_1; with --keep-uv-seams every seam of TEXCOORD_0 is a seam of the new set; unorm16
texcoords decode into the texels of the float uvs; a mesh drawn at several scales (by nodes or
by EXT_mesh_gpu_instancing) is packed at its largest and the report says so, and meshes defined
alike share one place at the larger scale of either; with --stack a congruent copy's charts
share their original's texels; bad flag combinations are refused with
exit status 2 and nothing written, a node's malformed transform with status 1, a scene that
draws nothing is nothing to bake; the Khronos validator finds no error in any output.

usage: test_gltf_scene.py RAPS_GLTF SHARED_DATA_DIR VALIDATOR_PREFIX NODE
"""
import base64
import json
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gltf_reader import Gltf  # noqa: E402
from gltf_tools import RUNNER, run_tool  # noqa: E402

RAPS_GLTF = DATA = VALIDATOR = NODE = None

# Shared assets whose scenes place meshes at other scales than 1: nine meshes side by side, a
# mesh drawn twice, a non-uniform scale, a scale of 0.01.
SCENES = ['AlphaBlendModeTest.glb', 'CesiumMilkTruck/CesiumMilkTruck.gltf',
          'VertexColorTest/VertexColorTest.gltf', 'Duck/Duck.gltf']
DENSITY = 48.0
MAX_SIZE = 512


def local_matrix(node):
    if 'matrix' in node:
        return np.array(node['matrix'], dtype=float).reshape(4, 4).T
    x, y, z, w = node.get('rotation', [0, 0, 0, 1])
    rotation = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                         [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                         [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    m = np.eye(4)
    m[:3, :3] = rotation @ np.diag(node.get('scale', [1, 1, 1]))
    m[:3, 3] = node.get('translation', [0, 0, 0])
    return m


def mesh_instances(doc):
    """Per mesh the 3x3 linear parts the default scene draws it with (no skins here)."""
    out = {}
    nodes = doc.get('nodes', [])
    stack = [(n, np.eye(4)) for n in doc['scenes'][doc.get('scene', 0)].get('nodes', [])]
    while stack:
        n, parent = stack.pop()
        world = parent @ local_matrix(nodes[n])
        if 'mesh' in nodes[n]:
            out.setdefault(nodes[n]['mesh'], []).append(world[:3, :3])
        stack += [(c, world) for c in nodes[n].get('children', [])]
    return out


def triangle_areas(points, triangles):
    a, b, c = (points[triangles[:, k]] for k in range(3))
    if points.shape[1] == 2:
        e, f = b - a, c - a
        return 0.5 * np.abs(e[:, 0] * f[:, 1] - e[:, 1] * f[:, 0])
    return 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)


def texcoords(g, prim, set_index):
    accessor = prim['attributes']['TEXCOORD_%d' % set_index]
    uv = g.accessor(accessor).astype(float)
    if g.json['accessors'][accessor]['componentType'] == 5123:
        uv /= 65535.0
    return uv


def world_area(g, mesh, linear):
    return sum(triangle_areas(g.accessor(p['attributes']['POSITION']).astype(float) @ linear.T,
                              g.triangles(p)).sum() for p in g.json['meshes'][mesh]['primitives'])


def texel_area(g, mesh, page, set_index):
    return sum(triangle_areas(texcoords(g, p, set_index) * page, g.triangles(p)).sum()
               for p in g.json['meshes'][mesh]['primitives'])


def validate_all(paths):
    p = subprocess.run([NODE, RUNNER, VALIDATOR, *paths], capture_output=True, text=True,
                       timeout=300)
    if p.returncode != 0:
        raise AssertionError('validator did not run: ' + p.stderr)
    return [json.loads(line) for line in p.stdout.splitlines() if line.strip()]


class SceneAtlas(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.outputs = []  # every file written, validated at the end

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def bake(self, source, name, *flags):
        out = os.path.join(self.tmp.name, name)
        status, stdout, stderr = run_tool(RAPS_GLTF, source, out, '--group', 'scene', *flags)
        self.assertEqual(status, 0, stderr)
        self.outputs.append(out)
        return Gltf(out), json.loads(stdout)

    def check_density(self, g, report, set_index, density):
        page = np.array(report['scene']['atlas'], dtype=float)
        scaled = {c['mesh'] for c in report['scene']['chart_list'] if c['scaled_down']}
        checked = []
        for mesh, linears in mesh_instances(g.json).items():
            if mesh in scaled or 'extras' not in g.json['meshes'][mesh]:
                continue
            # A mesh drawn several times gets the density on the instance that is largest.
            world = max(world_area(g, mesh, linear) for linear in linears)
            measured = np.sqrt(texel_area(g, mesh, page, set_index) / world)
            checked.append(measured)
            self.assertAlmostEqual(measured / density, 1.0, delta=0.02,
                                   msg='%s mesh %d: %.3f texels per unit' % (g.path, mesh,
                                                                             measured))
        self.assertTrue(checked, g.path)

    def check_pages(self, g, report, max_size):
        scene = report['scene']
        self.assertLessEqual(max(scene['atlas']), max_size)
        self.assertEqual(len(scene['pages']), scene['page_count'])
        for page in scene['pages']:
            self.assertLessEqual(max(page['size']), max_size)
            self.assertTrue(0 < page['utilization'] <= 1)
        for group in report['groups']:
            extras = g.json['meshes'][group['mesh']]['extras']['raps_atlas']
            self.assertEqual(extras['page'], group['page'])
            self.assertLess(group['page'], scene['page_count'])
        for chart in scene['chart_list']:
            x, y, w, h = chart['rect']
            self.assertLessEqual(x + w, scene['atlas'][0])
            self.assertLessEqual(y + h, scene['atlas'][1])

    def test_density_uniform_and_pages_bounded(self):
        for asset in SCENES:
            name = os.path.splitext(os.path.basename(asset))[0] + '.glb'
            g, report = self.bake(os.path.join(DATA, 'gltf', asset), name, '--overwrite',
                                  '--texels-per-unit', str(DENSITY), '--max-size',
                                  str(MAX_SIZE))
            self.assertEqual(report['scene']['scaled_down_charts'], 0, asset)
            self.check_density(g, report, 0, DENSITY)
            self.check_pages(g, report, MAX_SIZE)

    def test_pages_never_exceed_max_size(self):
        g, report = self.bake(os.path.join(DATA, 'gltf', 'CesiumMilkTruck', 'CesiumMilkTruck.gltf'),
                              'truck_pages.glb', '--overwrite', '--texels-per-unit', '60',
                              '--max-size', '128')
        self.assertGreater(report['scene']['page_count'], 1)
        self.check_pages(g, report, 128)

    def test_charts_too_large_for_a_page_are_shrunk_and_reported(self):
        g, report = self.bake(os.path.join(DATA, 'gltf', 'Fox', 'Fox.gltf'), 'fox.glb',
                              '--overwrite', '--texels-per-unit', '64', '--max-size', '256')
        scene = report['scene']
        shrunk = [c for c in scene['chart_list'] if c['scaled_down']]
        self.assertEqual(len(shrunk), scene['scaled_down_charts'])
        self.assertGreater(len(shrunk), 0)
        self.assertTrue(any('shrunk to fit a page' in note for note in report['notes']))
        for c in shrunk:
            self.assertLess(c['area_texels'], 0.99 * c['area_3d'] * 64 ** 2)
        self.check_pages(g, report, 256)

    def test_lightmap_keeps_texcoord0(self):
        source = os.path.join(DATA, 'gltf', 'Duck', 'Duck.gltf')
        g, report = self.bake(source, 'duck_lightmap.gltf', '--lightmap', '--texels-per-unit',
                              str(DENSITY), '--max-size', str(MAX_SIZE))
        self.assertEqual(report['settings']['texcoord'], 1)
        self.assertEqual(report['settings']['atlas_padding'], 2)
        original = Gltf(source)
        before = original.json['meshes'][0]['primitives'][0]['attributes']
        rows = {tuple(p) + tuple(t) for p, t in zip(original.accessor(before['POSITION']),
                                                    original.accessor(before['TEXCOORD_0']))}
        prim = g.json['meshes'][0]['primitives'][0]
        after = zip(g.accessor(prim['attributes']['POSITION']),
                    g.accessor(prim['attributes']['TEXCOORD_0']))
        self.assertTrue(all(tuple(p) + tuple(t) in rows for p, t in after))
        self.check_density(g, report, 1, DENSITY)

    def test_unorm16_decodes_into_the_float_texels(self):
        source = os.path.join(DATA, 'gltf', 'CesiumMilkTruck', 'CesiumMilkTruck.gltf')
        flags = ['--overwrite', '--lightmap', '--texcoord', '0', '--resolution', '256']
        g_float, report = self.bake(source, 'truck_float.glb', *flags)
        g_short, _ = self.bake(source, 'truck_unorm16.glb', *flags, '--uv-format', 'unorm16')
        page = np.array(report['scene']['atlas'])
        for mesh in range(len(g_float.json['meshes'])):
            for a, b in zip(g_float.json['meshes'][mesh]['primitives'],
                            g_short.json['meshes'][mesh]['primitives']):
                accessor = g_short.json['accessors'][b['attributes']['TEXCOORD_0']]
                self.assertEqual((accessor['componentType'], accessor['normalized']),
                                 (5123, True))
                exact, decoded = texcoords(g_float, a, 0), texcoords(g_short, b, 0)
                self.assertLessEqual(np.abs(decoded - exact).max(), 1.0001 / 65535)
                texel = lambda uv: np.minimum(np.floor(uv * page), page - 1)  # noqa: E731
                np.testing.assert_array_equal(texel(decoded), texel(exact))

    def test_several_scales_take_the_largest(self):
        with open(os.path.join(DATA, 'gltf', 'BoxTextured.gltf')) as fh:
            doc = json.load(fh)
        doc['nodes'] += [{'mesh': 0, 'scale': [2, 2, 2], 'translation': [5, 0, 0]},
                         {'mesh': 0, 'scale': [0.5, 0.5, 0.5]}]
        doc['scenes'][0]['nodes'] += [len(doc['nodes']) - 2, len(doc['nodes']) - 1]
        source = os.path.join(self.tmp.name, 'three_boxes.gltf')
        with open(source, 'w') as fh:
            json.dump(doc, fh)
        g, report = self.bake(source, 'three_boxes_uv.glb', '--overwrite', '--texels-per-unit',
                              '20')
        mesh = report['scene']['meshes'][0]
        self.assertTrue(mesh['several_scales'])
        self.assertEqual(mesh['instances'], 3)
        np.testing.assert_allclose(mesh['scales'], [0.5, 1, 2], rtol=1e-6)
        self.assertAlmostEqual(mesh['scale'], 2, places=6)
        self.assertTrue(any('packed at the largest' in note for note in report['notes']))
        self.check_density(g, report, 0, 20)

    def test_gpu_instances_take_the_largest(self):
        with open(os.path.join(DATA, 'gltf', 'BoxTextured.gltf')) as fh:
            doc = json.load(fh)
        scales = np.array([[1, 1, 1], [4, 4, 4], [0.5, 0.5, 0.5]], dtype=np.float32)
        doc['buffers'].append({'byteLength': scales.nbytes, 'uri': 'data:application/octet-stream;'
                               'base64,' + base64.b64encode(scales.tobytes()).decode()})
        doc['bufferViews'].append({'buffer': len(doc['buffers']) - 1, 'byteLength': scales.nbytes})
        doc['accessors'].append({'bufferView': len(doc['bufferViews']) - 1, 'componentType': 5126,
                                 'count': 3, 'type': 'VEC3'})
        doc['nodes'][1]['extensions'] = {'EXT_mesh_gpu_instancing': {
            'attributes': {'SCALE': len(doc['accessors']) - 1}}}
        doc['extensionsUsed'] = ['EXT_mesh_gpu_instancing']
        source = os.path.join(self.tmp.name, 'instanced.gltf')
        with open(source, 'w') as fh:
            json.dump(doc, fh)
        g, report = self.bake(source, 'instanced_uv.glb', '--overwrite', '--texels-per-unit', '10')
        mesh = report['scene']['meshes'][0]
        self.assertEqual(mesh['instances'], 3)
        np.testing.assert_allclose(mesh['scales'], [0.5, 1, 4], rtol=1e-6)
        page = np.array(report['scene']['atlas'], dtype=float)
        density = np.sqrt(texel_area(g, 0, page, 0) / world_area(g, 0, 4 * np.eye(3)))
        self.assertAlmostEqual(density / 10.0, 1.0, delta=0.02)

    def test_meshes_defined_alike_share_one_place(self):
        with open(os.path.join(DATA, 'gltf', 'BoxTextured.gltf')) as fh:
            doc = json.load(fh)
        doc['meshes'].append(dict(doc['meshes'][0], name='copy'))
        doc['nodes'].append({'mesh': 1, 'scale': [3, 3, 3]})
        doc['scenes'][0]['nodes'].append(len(doc['nodes']) - 1)
        source = os.path.join(self.tmp.name, 'alike.gltf')
        with open(source, 'w') as fh:
            json.dump(doc, fh)
        g, report = self.bake(source, 'alike_uv.glb', '--overwrite', '--texels-per-unit', '20')
        meshes = report['scene']['meshes']
        self.assertEqual(meshes[1]['shares_atlas_of'], 0)
        self.assertEqual(report['groups'][1]['reused_from_mesh'], 0)
        np.testing.assert_allclose([m['scales'] for m in meshes], [[1], [3]], rtol=1e-9)
        np.testing.assert_allclose([m['scale'] for m in meshes], [3, 3], rtol=1e-9)
        page = np.array(report['scene']['atlas'], dtype=float)
        density = np.sqrt(texel_area(g, 0, page, 0) / world_area(g, 0, np.eye(3)))
        # Packed once at the larger instance: 20 texels per unit there, 3 x 20 at scale 1.
        self.assertAlmostEqual(density / 60.0, 1.0, delta=0.02)

    def test_stack_shares_the_texels_of_congruent_meshes(self):
        # A second mesh whose positions are the first's moved 5 units: congruent charts, but
        # not the same data, so only --stack gives them one place.
        with open(os.path.join(DATA, 'gltf', 'BoxTextured.gltf')) as fh:
            doc = json.load(fh)
        box = Gltf(os.path.join(DATA, 'gltf', 'BoxTextured.gltf'))
        prim = doc['meshes'][0]['primitives'][0]
        moved = (box.accessor(prim['attributes']['POSITION']) + [5, 0, 0]).astype(np.float32)
        doc['buffers'].append({'byteLength': moved.nbytes, 'uri': 'data:application/octet-stream;'
                               'base64,' + base64.b64encode(moved.tobytes()).decode()})
        doc['bufferViews'].append({'buffer': len(doc['buffers']) - 1, 'byteLength': moved.nbytes})
        doc['accessors'].append({'bufferView': len(doc['bufferViews']) - 1, 'componentType': 5126,
                                 'count': len(moved), 'type': 'VEC3',
                                 'min': moved.min(axis=0).tolist(),
                                 'max': moved.max(axis=0).tolist()})
        doc['meshes'].append({'primitives': [dict(prim, attributes=dict(
            prim['attributes'], POSITION=len(doc['accessors']) - 1))]})
        doc['nodes'].append({'mesh': 1})
        doc['scenes'][0]['nodes'].append(len(doc['nodes']) - 1)
        source = os.path.join(self.tmp.name, 'two_boxes.gltf')
        with open(source, 'w') as fh:
            json.dump(doc, fh)
        flags = ('--overwrite',)
        plain_g, plain = self.bake(source, 'two_boxes_uv.glb', *flags)
        g, stacked = self.bake(source, 'two_boxes_stacked.glb', *flags, '--stack')
        self.assertFalse(any('stacked_on' in c for c in plain['scene']['chart_list']))
        copies = [c for c in stacked['scene']['chart_list'] if c['mesh'] == 1]
        self.assertTrue(copies)
        originals = stacked['scene']['chart_list']
        for c in copies:
            self.assertEqual(originals[c['stacked_on']]['mesh'], 0)
            self.assertEqual(originals[c['stacked_on']]['rect'], c['rect'])
        self.assertEqual(stacked['settings']['atlas_stack'], 1)
        # The copy's uvs are the original's: the same texels. Without --stack they are not.
        for baked, same in ((g, True), (plain_g, False)):
            uv = [texcoords(baked, baked.json['meshes'][m]['primitives'][0], 0) for m in (0, 1)]
            self.assertEqual(np.allclose(uv[0], uv[1], atol=1e-6), same)

    def test_keep_uv_seams(self):
        source = os.path.join(DATA, 'gltf', 'Duck', 'Duck.gltf')
        g, _ = self.bake(source, 'duck_seams.glb', '--lightmap', '--keep-uv-seams',
                         '--resolution', '512')
        prim = g.json['meshes'][0]['primitives'][0]
        xyz = g.accessor(prim['attributes']['POSITION'])
        old, new = texcoords(g, prim, 0), texcoords(g, prim, 1)
        sides = {}  # an edge by its end positions: per side, its ends' (old uv, new uv)
        for tri in g.triangles(prim):
            for k in range(3):
                a, b = tri[k], tri[(k + 1) % 3]
                key = tuple(sorted((tuple(xyz[a]), tuple(xyz[b]))))
                ends = sorted([(tuple(xyz[v]), tuple(old[v]), tuple(new[v])) for v in (a, b)])
                sides.setdefault(key, []).append(ends)
        kept = 0
        for pair in (s for s in sides.values() if len(s) == 2):
            if [e[1] for e in pair[0]] != [e[1] for e in pair[1]]:  # a seam of TEXCOORD_0
                self.assertNotEqual([e[2] for e in pair[0]], [e[2] for e in pair[1]])
                kept += 1
        self.assertGreater(kept, 0)

    def test_bad_flags_refused_before_writing(self):
        source = os.path.join(DATA, 'gltf', 'Duck', 'Duck.gltf')
        out = os.path.join(self.tmp.name, 'refused.glb')
        for flags, message in [
                (['--max-size', '512'], '--texels-per-unit too'),
                (['--texels-per-unit', '10', '--resolution', '512'], 'exclude each other'),
                (['--margin', '4'], 'whole texels'),
                (['--block-align'], 'whole texels'),
                (['--uv-format', 'half'], 'float or unorm16'),
                (['--group', 'world'], 'mesh, primitive or scene'),
                (['--texels-per-unit', 'nan'], 'atlas_texels_per_unit'),
                (['--texels-per-unit', '1', '--max-size', '8'], 'atlas_max_width'),
                (['--lightmap', '--stack'], 'exclude each other'),
                (['--texels-per-unit', '10', '--stack'], 'its own page'),
                (['--stack-tolerance', '0.5'], 'atlas_stack_tolerance')]:
            status, stdout, stderr = run_tool(RAPS_GLTF, source, out, '--overwrite', *flags)
            self.assertEqual(status, 2, flags)
            self.assertIn(message, stderr)
            self.assertEqual(json.loads(stdout)['error']['kind'], 'usage')
            self.assertFalse(os.path.exists(out))

    def test_help_documents_the_scene_flags(self):
        status, stdout, _ = run_tool(RAPS_GLTF, '--help')
        self.assertEqual(status, 0)
        for flag in ('--group mesh|primitive|scene', '--texels-per-unit', '--max-size',
                     '--lightmap', '--keep-uv-seams', '--uv-format float|unorm16',
                     '--rotate any|quarter|none', '--margin', '--block-align'):
            self.assertIn(flag, stdout)

    def test_scene_defects(self):
        with open(os.path.join(DATA, 'gltf', 'TriangleWithoutIndices.gltf')) as fh:
            original = json.load(fh)
        cases = [('no_scene', lambda d: [d.pop('scene'), d.pop('scenes')], 3, 'does not draw'),
                 ('zero_scale', lambda d: d['nodes'][0].update(scale=[0, 0, 0]), 3,
                  'does not draw'),
                 ('bad_scale', lambda d: d['nodes'][0].update(scale=[1, 'x', 1]), 1,
                  "node 0: 'scale' must be 3 finite numbers"),
                 ('bad_matrix', lambda d: d['nodes'][0].update(matrix=[1] * 15), 1,
                  "node 0: 'matrix' must be 16 finite numbers")]
        for name, edit, status, message in cases:
            doc = json.loads(json.dumps(original))
            edit(doc)
            source = os.path.join(self.tmp.name, name + '.gltf')
            with open(source, 'w') as fh:
                json.dump(doc, fh)
            out = os.path.join(self.tmp.name, name + '_uv.glb')
            code, _, stderr = run_tool(RAPS_GLTF, source, out, '--group', 'scene')
            self.assertEqual(code, status, name)
            self.assertIn(message, stderr)
            self.assertFalse(os.path.exists(out))

    def test_zz_validator_finds_no_error(self):
        self.assertTrue(self.outputs)
        for summary in validate_all(self.outputs):
            errors = [m for m in summary['messages'] if m['severity'] == 0]
            self.assertEqual(summary['errors'], 0, (summary['asset'], errors[:3]))


if __name__ == '__main__':
    RAPS_GLTF, DATA, VALIDATOR, NODE = sys.argv[1:5]
    unittest.main(argv=sys.argv[:1], verbosity=2)
