"""raps-gltf reads what the glTF 2.0 specification allows, as it says, and copies values without
inventing any; it refuses the structural defects an output would inherit. Each test builds a
small asset (a curved grid) that holds one such case, bakes it, and checks the output with the
Khronos validator (no error code its input did not have) and with an independent reader.

usage: test_gltf_spec_cases.py RAPS_GLTF VALIDATOR_PREFIX NODE
"""
import json
import os
import struct
import sys
import tempfile
import unittest
import urllib.parse

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gltf_reader import Gltf  # noqa: E402
from gltf_tools import grid as shared_grid, run_tool, validator_report  # noqa: E402

RAPS_GLTF = VALIDATOR = NODE = None
FLOAT, UINT8, UINT16, UINT32 = 5126, 5121, 5123, 5125


def run(*args):
    return run_tool(RAPS_GLTF, *args, timeout=300)


def error_codes(path):
    report = validator_report(NODE, VALIDATOR, path, timeout=300)
    return {m['code'] for m in report['messages'] if m['severity'] == 0}


class Builder:
    """A glTF document and one binary buffer, written as .gltf (data uri) or .glb."""

    def __init__(self):
        self.raw = bytearray()
        self.doc = {'asset': {'version': '2.0'}, 'scene': 0, 'scenes': [{'nodes': [0]}],
                    'nodes': [{'mesh': 0}], 'meshes': [], 'bufferViews': [], 'accessors': [],
                    'buffers': []}

    def view(self, data, target=None):
        while len(self.raw) % 4:
            self.raw.append(0)
        view = {'buffer': 0, 'byteOffset': len(self.raw), 'byteLength': len(data)}
        if target:
            view['target'] = target
        self.raw += data
        self.doc['bufferViews'].append(view)
        return len(self.doc['bufferViews']) - 1

    def accessor(self, array, type_, component=FLOAT, view=True, bounds=False, target=34962):
        array = np.ascontiguousarray(array)
        a = {'componentType': component, 'count': len(array), 'type': type_}
        if view:
            a['bufferView'] = self.view(array.tobytes(), target)
        if bounds:
            a['min'] = array.min(axis=0).tolist()
            a['max'] = array.max(axis=0).tolist()
        self.doc['accessors'].append(a)
        return len(self.doc['accessors']) - 1

    def sparse(self, accessor, indices, values):
        """A sparse substitution on an accessor already added."""
        a = self.doc['accessors'][accessor]
        a['sparse'] = {'count': len(indices),
                       'indices': {'bufferView': self.view(np.asarray(indices, np.uint32).tobytes()),
                                   'componentType': UINT32},
                       'values': {'bufferView': self.view(np.ascontiguousarray(values).tobytes())}}

    def grid_primitive(self, n=6, indices_type=np.uint16, extra_attributes=None):
        pos, tris = grid(n, n)
        prim = {'attributes': {'POSITION': self.accessor(pos, 'VEC3', bounds=True)},
                'indices': self.accessor(np.asarray(tris, indices_type), 'SCALAR',
                                         UINT16 if indices_type == np.uint16 else UINT32,
                                         target=34963)}
        for name, accessor in (extra_attributes or {}).items():
            prim['attributes'][name] = accessor
        return prim, pos, tris

    def write_gltf(self, path, uri=None):
        doc = json.loads(json.dumps(self.doc))
        if self.raw:
            buffer = {'byteLength': len(self.raw)}
            buffer['uri'] = uri if uri is not None else (
                'data:application/octet-stream;base64,' + __import__('base64').b64encode(
                    bytes(self.raw)).decode())
            doc['buffers'].insert(0, buffer)
        with open(path, 'w') as fh:
            json.dump(doc, fh)

    def write_glb(self, path, bin_padding=0, trailing=b''):
        doc = json.loads(json.dumps(self.doc))
        doc['buffers'].insert(0, {'byteLength': len(self.raw)})
        text = json.dumps(doc).encode()
        text += b' ' * (-len(text) % 4)
        data = bytes(self.raw) + b'\0' * (-len(self.raw) % 4 + bin_padding)
        body = struct.pack('<II', len(text), 0x4E4F534A) + text + \
            struct.pack('<II', len(data), 0x004E4942) + data
        with open(path, 'wb') as fh:
            fh.write(struct.pack('<III', 0x46546C67, 2, 12 + len(body)) + body + trailing)


def grid(n, m):
    pos, tris = shared_grid(n, m)
    return pos.astype(np.float32), tris


class SpecCases(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.tmp = self.dir.name

    def tearDown(self):
        self.dir.cleanup()

    def path(self, name):
        return os.path.join(self.tmp, name)

    def bake_clean(self, src, out='out.glb', *flags):
        """Bakes src; the output may have no validator error code src did not have."""
        out = self.path(out)
        rc, stdout, stderr = run(src, out, '--overwrite', *flags)
        self.assertEqual(rc, 0, stderr)
        new = error_codes(out) - error_codes(src)
        self.assertEqual(new, set(), f'new validator errors in the output of {src}')
        return Gltf(out), json.loads(stdout)

    def assert_refused(self, src, words):
        out = self.path('refused.glb')
        rc, stdout, stderr = run(src, out)
        self.assertEqual(rc, 1, stdout)
        self.assertIn(words, stderr)
        self.assertFalse(os.path.exists(out))
        self.assertTrue(error_codes(src), f'{src} was meant to be invalid')

    def corner_positions(self, g, prim):
        return g.accessor(prim['attributes']['POSITION'])[g.triangles(prim)]

    def test_attributes_without_bufferview_stay_zeros_without_bufferview(self):
        b = Builder()
        pos, _ = grid(6, 6)
        normal = b.accessor(np.zeros((len(pos), 3), np.float32), 'VEC3', view=False)
        color = b.accessor(np.zeros((len(pos), 4), np.float32), 'VEC4', view=False)
        prim, _, _ = b.grid_primitive(extra_attributes={'NORMAL': normal, 'COLOR_0': color})
        b.doc['meshes'].append({'primitives': [prim]})
        src = self.path('zeros.gltf')
        b.write_gltf(src)
        self.assertEqual(error_codes(src), set())
        g, _ = self.bake_clean(src)
        out = g.json['meshes'][0]['primitives'][0]['attributes']
        for name in ('NORMAL', 'COLOR_0'):
            accessor = g.json['accessors'][out[name]]
            self.assertNotIn('bufferView', accessor, name)
            self.assertNotIn('sparse', accessor, name)
            self.assertEqual(accessor['count'], g.json['accessors'][out['POSITION']]['count'])

    def test_sparse_positions_are_read_and_copied_as_sparse(self):
        b = Builder()
        pos, tris = grid(6, 6)
        base = b.accessor(np.zeros_like(pos), 'VEC3', view=False)
        b.sparse(base, np.arange(len(pos)), pos)
        b.doc['accessors'][base].update(min=pos.min(axis=0).tolist(), max=pos.max(axis=0).tolist())
        # A second attribute: zeros except a few substituted vertices.
        few = [0, 7, 20, len(pos) - 1]
        colors = np.zeros((len(pos), 4), np.float32)
        colors[few] = [1, 0.5, 0.25, 1]
        color = b.accessor(np.zeros((len(pos), 4), np.float32), 'VEC4', view=False)
        b.sparse(color, few, colors[few])
        indices = b.accessor(np.asarray(tris, np.uint16), 'SCALAR', UINT16, target=34963)
        b.doc['meshes'].append({'primitives': [{'attributes': {'POSITION': base, 'COLOR_0': color},
                                                'indices': indices}]})
        src = self.path('sparse.gltf')
        b.write_gltf(src)
        self.assertEqual(error_codes(src), set())
        g, _ = self.bake_clean(src)
        gi = Gltf(src)
        pi, po = gi.json['meshes'][0]['primitives'][0], g.json['meshes'][0]['primitives'][0]
        np.testing.assert_array_equal(self.corner_positions(gi, pi), self.corner_positions(g, po))
        out_color = g.json['accessors'][po['attributes']['COLOR_0']]
        self.assertNotIn('bufferView', out_color)
        # Exactly the output copies of the substituted vertices are substituted.
        remap = {}
        for ci, co in zip(gi.triangles(pi).ravel(), g.triangles(po).ravel()):
            remap[int(co)] = int(ci)
        substituted = sorted(k for k, v in remap.items() if v in few)
        self.assertEqual(out_color['sparse']['count'], len(substituted))
        np.testing.assert_array_equal(g.accessor(po['attributes']['COLOR_0'])[substituted],
                                      colors[[remap[k] for k in substituted]])

    def test_sparse_over_a_bufferview_moves_vertices(self):
        b = Builder()
        prim, pos, _ = b.grid_primitive()
        moved = pos.copy()
        moved[[3, 10]] += [0, 0, 0.5]
        b.sparse(prim['attributes']['POSITION'], [3, 10], moved[[3, 10]])
        b.doc['accessors'][prim['attributes']['POSITION']].update(
            min=moved.min(axis=0).tolist(), max=moved.max(axis=0).tolist())
        b.doc['meshes'].append({'primitives': [prim]})
        src = self.path('moved.gltf')
        b.write_gltf(src)
        g, _ = self.bake_clean(src)
        gi = Gltf(src)
        pi, po = gi.json['meshes'][0]['primitives'][0], g.json['meshes'][0]['primitives'][0]
        np.testing.assert_array_equal(self.corner_positions(g, po), moved[gi.triangles(pi)])

    def test_placeholder_buffer_is_kept_and_its_primitive_left_as_it_is(self):
        b = Builder()
        prim, _, _ = b.grid_primitive()
        # A second buffer without uri: a placeholder, as an extension's fallback buffer is.
        b.doc['buffers'].append({'byteLength': 96})
        b.doc['bufferViews'].append({'buffer': 1, 'byteLength': 96})
        ghost = len(b.doc['accessors'])
        b.doc['accessors'].append({'bufferView': len(b.doc['bufferViews']) - 1,
                                   'componentType': FLOAT, 'count': 8, 'type': 'VEC3',
                                   'min': [0, 0, 0], 'max': [1, 1, 1]})
        placeholder_prim = {'attributes': {'POSITION': ghost}}
        b.doc['meshes'].append({'primitives': [prim, placeholder_prim]})
        src = self.path('placeholder.gltf')
        b.write_gltf(src)
        self.assertEqual(error_codes(src), set())
        for out in ('placeholder_out.gltf', 'placeholder_out.glb'):
            g, report = self.bake_clean(src, out)
            self.assertEqual(len(report['skipped']), 1)
            self.assertIn('placeholder', report['skipped'][0]['reason'])
            kept = g.json['meshes'][0]['primitives'][1]['attributes']['POSITION']
            view = g.json['bufferViews'][g.json['accessors'][kept]['bufferView']]
            buffer = g.json['buffers'][view['buffer']]
            self.assertEqual(buffer, {'byteLength': 96})

    def test_data_uri_without_base64_is_percent_decoded(self):
        b = Builder()
        prim, pos, tris = b.grid_primitive()
        b.doc['meshes'].append({'primitives': [prim]})
        src = self.path('percent.gltf')
        b.write_gltf(src, uri='data:application/gltf-buffer,' +
                     urllib.parse.quote(bytes(b.raw), safe=''))
        self.assertEqual(error_codes(src), set())
        g, _ = self.bake_clean(src)
        po = g.json['meshes'][0]['primitives'][0]
        np.testing.assert_array_equal(self.corner_positions(g, po),
                                      pos[np.asarray(tris).reshape(-1, 3)])

    def test_glb_chunk_padding_and_trailing_bytes(self):
        b = Builder()
        prim, _, _ = b.grid_primitive()
        b.doc['meshes'].append({'primitives': [prim]})
        src = self.path('padded.glb')
        b.write_glb(src, bin_padding=8, trailing=b'\0\0\0\0\0')
        self.assertEqual(error_codes(src), set())
        _, report = self.bake_clean(src)
        self.assertTrue(any('trailing' in w or 'after' in w for w in report.get('loader_warnings', [])),
                        report.get('loader_warnings'))

    def test_integers_written_as_floats(self):
        b = Builder()
        prim, _, _ = b.grid_primitive()
        b.doc['meshes'].append({'primitives': [prim]})
        src = self.path('floats.gltf')
        b.write_gltf(src)
        with open(src) as fh:
            doc = json.load(fh)
        for v in doc['bufferViews']:
            v['buffer'] = float(v['buffer'])
            v['byteLength'] = float(v['byteLength'])
        doc['meshes'][0]['primitives'][0]['attributes']['POSITION'] = 0.0
        doc['meshes'][0]['primitives'][0]['indices'] = 1.0
        doc['nodes'][0]['mesh'] = 0.0
        with open(src, 'w') as fh:
            json.dump(doc, fh)
        self.assertEqual(error_codes(src), set())
        self.bake_clean(src)

    def test_unused_accessor_of_unknown_type_is_kept(self):
        b = Builder()
        prim, _, _ = b.grid_primitive()
        b.doc['meshes'].append({'primitives': [prim]})
        b.doc['accessors'].append({'componentType': FLOAT, 'count': 4, 'type': 'NotaVEC3'})
        src = self.path('unknown_type.gltf')
        b.write_gltf(src)
        self.assertEqual(error_codes(src), set())
        g, _ = self.bake_clean(src)
        self.assertIn({'componentType': FLOAT, 'count': 4, 'type': 'NotaVEC3'}, g.json['accessors'])

    def test_primitive_restart_index_is_refused(self):
        for dtype, component, restart in ((np.uint8, UINT8, 0xFF), (np.uint16, UINT16, 0xFFFF)):
            b = Builder()
            pos = np.random.default_rng(1).random((300, 3)).astype(np.float32)
            position = b.accessor(pos, 'VEC3', bounds=True)
            indices = b.accessor(np.asarray([0, 1, 2, 3, 4, restart], dtype), 'SCALAR', component,
                                 target=34963)
            b.doc['meshes'].append({'primitives': [{'attributes': {'POSITION': position},
                                                    'indices': indices}]})
            src = self.path('restart.gltf')
            b.write_gltf(src)
            self.assert_refused(src, 'primitive-restart value')

    def test_node_cycles_and_second_parents_are_refused(self):
        for children, words in (([[1], [0]], 'cycle'), ([[2], [2], []], 'two parents')):
            b = Builder()
            prim, _, _ = b.grid_primitive()
            b.doc['meshes'].append({'primitives': [prim]})
            b.doc['nodes'] = [{'mesh': 0, 'children': c} if c else {'mesh': 0} for c in children]
            src = self.path('graph.gltf')
            b.write_gltf(src)
            self.assert_refused(src, words)

    def test_anisotropic_material_without_normal_texture_gets_new_tangents(self):
        b = Builder()
        pos, _ = grid(6, 6)
        normals = np.tile(np.float32([0, 0, 1]), (len(pos), 1))
        tangents = np.tile(np.float32([1, 0, 0, 1]), (len(pos), 1))
        uv = pos[:, :2].copy()
        prim, _, _ = b.grid_primitive(extra_attributes={
            'NORMAL': b.accessor(normals, 'VEC3'), 'TANGENT': b.accessor(tangents, 'VEC4'),
            'TEXCOORD_0': b.accessor(uv, 'VEC2')})
        prim['material'] = 0
        b.doc['meshes'].append({'primitives': [prim]})
        b.doc['extensionsUsed'] = ['KHR_materials_anisotropy']
        b.doc['materials'] = [{'extensions': {'KHR_materials_anisotropy': {
            'anisotropyStrength': 0.5, 'anisotropyTexture': {'index': 0}}}}]
        b.doc['textures'] = [{'source': 0}]
        png = bytes.fromhex('89504e470d0a1a0a0000000d4948445200000001000000010806000000'
                            '1f15c4890000000d49444154789c6360f8ffff3f0005fe02fea7a3a1e6'
                            '0000000049454e44ae426082')
        b.doc['images'] = [{'uri': 'data:image/png;base64,' +
                            __import__('base64').b64encode(png).decode()}]
        src = self.path('anisotropy.gltf')
        b.write_gltf(src)
        self.assertNotIn('MESH_PRIMITIVE_NO_TANGENT_SPACE', error_codes(src))
        g, report = self.bake_clean(src)
        self.assertEqual(report['primitives'][0]['tangents'], 'generated')
        po = g.json['meshes'][0]['primitives'][0]
        t = g.accessor(po['attributes']['TANGENT']).astype(np.float64)
        n = g.accessor(po['attributes']['NORMAL']).astype(np.float64)
        np.testing.assert_allclose(np.linalg.norm(t[:, :3], axis=1), 1, atol=1e-5)
        np.testing.assert_allclose(np.sum(t[:, :3] * n, axis=1), 0, atol=1e-5)
        self.assertTrue(np.all(np.abs(t[:, 3]) == 1))
        # The tangent follows the new u direction: along each triangle's edges, u grows with it.
        uv_out = g.accessor(po['attributes']['TEXCOORD_0']).astype(np.float64)
        p = g.accessor(po['attributes']['POSITION']).astype(np.float64)
        tris = g.triangles(po)
        e = p[tris[:, 1]] - p[tris[:, 0]]
        du = uv_out[tris[:, 1], 0] - uv_out[tris[:, 0], 0]
        along = np.sum(e * t[tris[:, 0], :3], axis=1)
        big = np.abs(du) > 1e-3
        self.assertGreater(np.mean(np.sign(along[big]) == np.sign(du[big])), 0.9)

    def test_unnormalized_input_weights_are_copied_and_reported(self):
        b = Builder()
        pos, _ = grid(6, 6)
        weights = np.tile(np.float32([1, 0, 0, 0]), (len(pos), 1))
        weights[::5] = [0.5, 0, 0, 0]
        prim, _, _ = b.grid_primitive(extra_attributes={
            'JOINTS_0': b.accessor(np.zeros((len(pos), 4), np.uint8), 'VEC4', UINT8),
            'WEIGHTS_0': b.accessor(weights, 'VEC4')})
        b.doc['meshes'].append({'primitives': [prim]})
        # The validator checks weights of meshes a skinned node uses.
        b.doc['nodes'] = [{'mesh': 0, 'skin': 0}, {}]
        b.doc['scenes'] = [{'nodes': [0, 1]}]
        b.doc['skins'] = [{'joints': [1]}]
        src = self.path('weights.gltf')
        b.write_gltf(src)
        self.assertIn('ACCESSOR_WEIGHTS_NON_NORMALIZED', error_codes(src))
        g, report = self.bake_clean(src)
        po = g.json['meshes'][0]['primitives'][0]
        out = g.accessor(po['attributes']['WEIGHTS_0'])
        bad = int(np.sum(np.abs(out.sum(axis=1) - 1) > 1e-3))
        self.assertGreater(bad, 0)
        self.assertEqual(report['primitives'][0]['unnormalized_weights'], bad)
        self.assertTrue(any('do not sum to 1' in n for n in report['notes']), report['notes'])

    def test_normal_texture_material_drops_tangents_of_the_rewritten_set(self):
        b = Builder()
        pos, _ = grid(6, 6)
        prim, _, _ = b.grid_primitive(extra_attributes={
            'NORMAL': b.accessor(np.tile(np.float32([0, 0, 1]), (len(pos), 1)), 'VEC3'),
            'TANGENT': b.accessor(np.tile(np.float32([1, 0, 0, 1]), (len(pos), 1)), 'VEC4'),
            'TEXCOORD_0': b.accessor(pos[:, :2].copy(), 'VEC2')})
        prim['material'] = 0
        b.doc['meshes'].append({'primitives': [prim]})
        b.doc['materials'] = [{'normalTexture': {'index': 0}}]
        b.doc['textures'] = [{}]
        src = self.path('normal_map.gltf')
        b.write_gltf(src)
        g, report = self.bake_clean(src)
        self.assertEqual(report['primitives'][0]['tangents'], 'dropped')
        self.assertNotIn('TANGENT', g.json['meshes'][0]['primitives'][0]['attributes'])


if __name__ == '__main__':
    RAPS_GLTF, VALIDATOR, NODE = sys.argv[1], sys.argv[2], sys.argv[3]
    unittest.main(argv=sys.argv[:1], verbosity=2)
