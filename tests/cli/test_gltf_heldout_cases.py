"""raps-gltf on the classes of input a sweep over held-out-like assets found mishandled
(docs/heldout-gltf.md): each test builds the smallest asset of its class, bakes it as a user
would, and checks the output with the Khronos validator and with an independent reader.

usage: test_gltf_heldout_cases.py RAPS_GLTF VALIDATOR_PREFIX NODE
"""
import base64
import json
import os
import sys
import tempfile
import unittest

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import test_gltf_spec_cases as spec  # noqa: E402
from gltf_reader import Gltf  # noqa: E402
from test_gltf_spec_cases import Builder  # noqa: E402


class HeldoutCases(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.tmp = self.dir.name

    def tearDown(self):
        self.dir.cleanup()

    def path(self, name):
        return os.path.join(self.tmp, name)

    def bake_clean(self, src, out='out.glb', *flags):
        out = self.path(out)
        rc, stdout, stderr = spec.run(src, out, '--overwrite', *flags)
        self.assertEqual(rc, 0, stderr)
        self.assertEqual(spec.error_codes(out) - spec.error_codes(src), set(),
                         f'new validator errors in the output of {src}')
        return Gltf(out), json.loads(stdout)

    def test_buffer_data_longer_than_byte_length_is_read(self):
        """A .bin or data uri padded past byteLength is valid (the validator only asks for at
        least byteLength bytes): read, and only byteLength bytes kept."""
        b = Builder()
        prim, _, _ = b.grid_primitive()
        b.doc['meshes'].append({'primitives': [prim]})
        padded = bytes(b.raw) + b'\0\0\0\0\0\0'
        with open(self.path('padded.bin'), 'wb') as fh:
            fh.write(padded)
        external = self.path('external.gltf')
        b.write_gltf(external, uri='padded.bin')
        embedded = self.path('embedded.gltf')
        b.write_gltf(embedded, uri='data:application/octet-stream;base64,' +
                     base64.b64encode(padded).decode())
        for src in (external, embedded):
            self.assertEqual(spec.error_codes(src), set())
            g, report = self.bake_clean(src)
            self.assertTrue(any('past its byteLength' in w
                                for w in report.get('loader_warnings', [])), report)
            self.assertIn('TEXCOORD_0', g.json['meshes'][0]['primitives'][0]['attributes'])
        # Fewer bytes than byteLength stays refused.
        with open(self.path('short.bin'), 'wb') as fh:
            fh.write(bytes(b.raw)[:-4])
        short = self.path('short.gltf')
        b.write_gltf(short, uri='short.bin')
        rc, _, stderr = spec.run(short, self.path('short_out.glb'))
        self.assertEqual(rc, 1)
        self.assertIn('byteLength', stderr)
        self.assertFalse(os.path.exists(self.path('short_out.glb')))


    def test_extensions_are_read_as_the_specification_says(self):
        """Draco beside uncompressed accessors (used, not required) is valid glTF: the
        uncompressed data is baked and the compressed copy, which would not carry the new uvs,
        dropped. A required extension raps-gltf does not know is refused, naming it: it may
        change what the data means."""
        b = Builder()
        prim, _, _ = b.grid_primitive()
        prim['extensions'] = {'KHR_draco_mesh_compression': {
            'bufferView': 0, 'attributes': {'POSITION': 0}}}
        b.doc['meshes'].append({'primitives': [prim]})
        b.doc['extensionsUsed'] = ['KHR_draco_mesh_compression']
        src = self.path('draco_fallback.gltf')
        b.write_gltf(src)
        self.assertEqual(spec.error_codes(src), set())
        g, report = self.bake_clean(src)
        self.assertNotIn('KHR_draco_mesh_compression', g.json.get('extensionsUsed', []))
        out_prim = g.json['meshes'][0]['primitives'][0]
        self.assertNotIn('extensions', out_prim)
        self.assertIn('TEXCOORD_0', out_prim['attributes'])
        self.assertTrue(any('Draco' in w for w in report.get('loader_warnings', [])), report)
        b = Builder()
        prim, _, _ = b.grid_primitive()
        b.doc['meshes'].append({'primitives': [prim]})
        b.doc['extensionsUsed'] = b.doc['extensionsRequired'] = ['EXT_not_known_to_raps']
        src = self.path('unknown_required.gltf')
        b.write_gltf(src)
        rc, _, stderr = spec.run(src, self.path('unknown_out.glb'))
        self.assertEqual(rc, 1, stderr)
        self.assertIn('requires EXT_not_known_to_raps', stderr)
        self.assertFalse(os.path.exists(self.path('unknown_out.glb')))

    def test_text_that_is_not_utf8_is_refused_at_its_first_bad_byte(self):
        """glTF's JSON is UTF-8. A Latin-1 name (one byte 0xE9 for an accented e) is refused
        before anything is read, with the byte's offset and value; it used to be read and then
        fail as an internal error, naming the quote after it, when the output was written."""
        b = Builder()
        prim, _, _ = b.grid_primitive()
        b.doc['meshes'].append({'primitives': [prim], 'name': 'cafX'})
        src = self.path('latin1.gltf')
        b.write_gltf(src)
        with open(src, 'rb') as fh:
            text = fh.read()
        text = text.replace(b'"cafX"', b'"caf\xe9"')
        with open(src, 'wb') as fh:
            fh.write(text)
        rc, _, stderr = spec.run(src, self.path('latin1_out.glb'))
        self.assertEqual(rc, 1, stderr)
        offset = text.index(b'\xe9')
        self.assertIn(f'byte {offset} (0xE9)', stderr)
        self.assertIn('UTF-8', stderr)
        self.assertFalse(os.path.exists(self.path('latin1_out.glb')))

    def test_a_uri_naming_the_folder_is_refused_as_such(self):
        """uri '.' is the asset's own folder: refused as a folder, not as a link leading out."""
        b = Builder()
        prim, _, _ = b.grid_primitive()
        b.doc['meshes'].append({'primitives': [prim]})
        src = self.path('dot.gltf')
        b.write_gltf(src, uri='.')
        rc, _, stderr = spec.run(src, self.path('dot_out.glb'))
        self.assertEqual(rc, 1, stderr)
        self.assertIn("names the asset's folder itself", stderr)

    def test_texture_transform_texcoord_decides_the_tangents(self):
        """KHR_texture_transform's texCoord overrides the normal texture's own: the tangents
        follow the set the normal map really reads."""
        b = Builder()
        prim, pos, _ = b.grid_primitive(extra_attributes={
            'NORMAL': b.accessor(np.tile(np.float32([0, 0, 1]), (49, 1)), 'VEC3'),
            'TANGENT': b.accessor(np.tile(np.float32([1, 0, 0, 1]), (49, 1)), 'VEC4'),
            'TEXCOORD_0': b.accessor(np.zeros((49, 2), np.float32), 'VEC2'),
            'TEXCOORD_1': b.accessor(np.zeros((49, 2), np.float32), 'VEC2')})
        prim['material'] = 0
        b.doc['meshes'].append({'primitives': [prim]})
        b.doc['extensionsUsed'] = ['KHR_texture_transform']
        b.doc['materials'] = [{'normalTexture': {
            'index': 0, 'texCoord': 0,
            'extensions': {'KHR_texture_transform': {'texCoord': 1, 'scale': [2, 2]}}}}]
        b.doc['textures'] = [{}]
        src = self.path('transform.gltf')
        b.write_gltf(src)
        g, report = self.bake_clean(src, 'set1.glb', '--texcoord', '1')
        self.assertEqual(report['primitives'][0]['tangents'], 'dropped')
        self.assertNotIn('TANGENT', g.json['meshes'][0]['primitives'][0]['attributes'])
        g, report = self.bake_clean(src, 'set0.glb')
        self.assertEqual(report['primitives'][0]['tangents'], 'kept')
        self.assertIn('TANGENT', g.json['meshes'][0]['primitives'][0]['attributes'])


    def world_distortion(self, g, report, scale):
        """Per triangle of the output, the ratio of the larger to the smaller singular value of
        the map from world space (positions times the node's scale) to texels, and the sign of
        the triangle's texel area."""
        prim = g.json['meshes'][0]['primitives'][0]
        acc = g.json['accessors'][prim['attributes']['POSITION']]
        xyz = g.accessor(prim['attributes']['POSITION']).astype(np.float64)
        if acc.get('normalized'):
            xyz /= 32767.0
        xyz *= np.asarray(scale, np.float64)
        uv = g.accessor(prim['attributes']['TEXCOORD_0']).astype(np.float64)
        uv *= np.asarray(report['groups'][0]['atlas'], np.float64)
        ratios, signs = [], []
        for a, b, c in g.triangles(prim):
            e = np.column_stack([xyz[b] - xyz[a], xyz[c] - xyz[a]])
            q, r = np.linalg.qr(e)  # the triangle in its own plane
            f = np.column_stack([uv[b] - uv[a], uv[c] - uv[a]])
            sv = np.linalg.svd(f @ np.linalg.inv(r), compute_uv=False)
            ratios.append(sv[0] / sv[1])
            signs.append(np.sign(np.linalg.det(f)))
        return np.asarray(ratios), np.asarray(signs)

    def test_mesh_scaled_unevenly_by_its_node_is_mapped_as_drawn(self):
        """KHR_mesh_quantization stores positions as integers that the node's scale, per axis,
        turns into the model; a mesh's own space is then stretched, and uvs made there are
        stretched in the world. --group mesh maps such a mesh as the scene draws it."""
        pos, tris = spec.grid(8, 8)
        stretch = np.float64([8, 1, 1])
        flat = self.path('flat.gltf')
        b = Builder()
        b.doc['meshes'].append({'primitives': [{
            'attributes': {'POSITION': b.accessor(pos, 'VEC3', bounds=True)},
            'indices': b.accessor(np.asarray(tris, np.uint16), 'SCALAR', spec.UINT16,
                                  target=34963)}]})
        b.write_gltf(flat)
        g, report = self.bake_clean(flat, 'flat.glb')
        _, local_signs = self.world_distortion(g, report, [1, 1, 1])
        # The same surface, 8 times longer: integers scaled per axis, and floats under a
        # mirroring node.
        unit = (pos * stretch).max(axis=0)
        quantized = np.round(pos * stretch / unit * 32767).astype(np.int16)
        b = Builder()
        b.doc['extensionsUsed'] = b.doc['extensionsRequired'] = ['KHR_mesh_quantization']
        position = b.accessor(quantized, 'VEC3', component=5122, bounds=True)
        b.doc['accessors'][position]['normalized'] = True
        b.doc['meshes'].append({'primitives': [{
            'attributes': {'POSITION': position},
            'indices': b.accessor(np.asarray(tris, np.uint16), 'SCALAR', spec.UINT16,
                                  target=34963)}]})
        b.doc['nodes'][0]['scale'] = unit.tolist()
        src = self.path('quantized.gltf')
        b.write_gltf(src)
        mirrored = self.path('mirrored.gltf')
        b = Builder()
        b.doc['meshes'].append({'primitives': [{
            'attributes': {'POSITION': b.accessor(pos, 'VEC3', bounds=True)},
            'indices': b.accessor(np.asarray(tris, np.uint16), 'SCALAR', spec.UINT16,
                                  target=34963)}]})
        b.doc['nodes'][0]['scale'] = [8, 1, -1]
        b.write_gltf(mirrored)
        for path, scale in ((src, unit), (mirrored, [8, 1, -1])):
            for flags in ((), ('--texels-per-unit', '4')):
                g, report = self.bake_clean(path, 'stretched.glb', *flags)
                ratios, signs = self.world_distortion(g, report, scale)
                self.assertLess(np.median(ratios), 1.2, (path, flags))
                self.assertTrue(np.all(signs == local_signs[0]), (path, flags))
        # A node so uneven that no map exists at double precision as drawn: the mesh's own
        # space, as before, and a note.
        b = Builder()
        b.doc['meshes'].append({'primitives': [{
            'attributes': {'POSITION': b.accessor(pos, 'VEC3', bounds=True)},
            'indices': b.accessor(np.asarray(tris, np.uint16), 'SCALAR', spec.UINT16,
                                  target=34963)}]})
        b.doc['nodes'][0]['scale'] = [2.0 ** 63, 3, -1]
        b.write_gltf(mirrored)
        _, report = self.bake_clean(mirrored, 'own_space.glb')
        self.assertTrue(any('own space' in n for n in report['notes']), report['notes'])


    def test_coordinates_past_1e30_are_mapped_as_at_unit_scale(self):
        """Finite positions of any size are valid glTF; the library takes coordinates up to
        1e30, so raps-gltf hands it the mesh scaled by a power of two. The uvs are those of the
        same mesh at unit scale, at a resolution, at a density given per the asset's unit, and in a
        scene's lightmap."""
        pos, tris = spec.grid(6, 6)
        outputs = {}
        for name, factor in (('unit', 1.0), ('huge', 2.0 ** 110)):
            b = Builder()
            b.doc['meshes'].append({'primitives': [{
                'attributes': {'POSITION': b.accessor(pos * np.float32(factor), 'VEC3',
                                                      bounds=True)},
                'indices': b.accessor(np.asarray(tris, np.uint16), 'SCALAR', spec.UINT16,
                                      target=34963)}]})
            src = self.path(name + '.gltf')
            b.write_gltf(src)
            self.assertEqual(spec.error_codes(src), set())
            density = '%r' % (16 / factor)
            for k, flags in enumerate(((), ('--texels-per-unit', density),
                                       ('--group', 'scene', '--lightmap'))):
                g, report = self.bake_clean(src, name + '.glb', *flags)
                prim = g.json['meshes'][0]['primitives'][0]
                atlas = report['scene']['atlas'] if 'scene' in report else \
                    report['groups'][0]['atlas']
                outputs[name, k] = (g.accessor(prim['attributes']['TEXCOORD_%d' % (k // 2)]),
                                    atlas)
        for k in range(3):
            uv_unit, atlas_unit = outputs['unit', k]
            uv_huge, atlas_huge = outputs['huge', k]
            self.assertEqual(atlas_huge, atlas_unit)
            np.testing.assert_allclose(uv_huge, uv_unit, atol=1e-5)


    def test_accessors_of_zeros_are_not_read_to_find_them_degenerate(self):
        """An accessor without a bufferView or a sparse substitution is zeros, and a valid file
        of a few hundred bytes may declare a billion of them: its primitive is left as it is
        (every triangle degenerate) without reading them, and index checks still come first."""
        doc = {'asset': {'version': '2.0'}, 'scene': 0, 'scenes': [{'nodes': [0]}],
               'nodes': [{'mesh': 0}],
               'meshes': [{'primitives': [{'attributes': {'POSITION': 0, 'NORMAL': 1}}]}],
               'accessors': [{'componentType': spec.FLOAT, 'count': 10000002, 'type': 'VEC3',
                              'min': [0, 0, 0], 'max': [0, 0, 0]},
                             {'componentType': spec.FLOAT, 'count': 10000002, 'type': 'VEC3'}]}
        src = self.path('zeros.gltf')
        with open(src, 'w') as fh:
            json.dump(doc, fh)
        rc, _, stderr = spec.run(src, self.path('zeros.glb'))
        self.assertEqual(rc, 3, stderr)
        self.assertIn('all zeros', stderr)
        self.assertFalse(os.path.exists(self.path('zeros.glb')))
        # Indices past the vertex count are still refused when the positions are zeros.
        b = Builder()
        b.doc['accessors'].append({'componentType': spec.FLOAT, 'count': 4, 'type': 'VEC3',
                                   'min': [0, 0, 0], 'max': [0, 0, 0]})
        indices = b.accessor(np.uint16([0, 1, 4]), 'SCALAR', spec.UINT16, target=34963)
        b.doc['meshes'].append({'primitives': [{'attributes': {'POSITION': 0},
                                                'indices': indices}]})
        src = self.path('oob.gltf')
        b.write_gltf(src)
        rc, _, stderr = spec.run(src, self.path('oob.glb'))
        self.assertEqual(rc, 1, stderr)
        self.assertIn('past the vertex count', stderr)


    def test_many_primitives_sharing_one_accessor_keep_their_values(self):
        """Primitives that each use a few vertices of one large interleaved accessor (with a
        sparse substitution) are read at their corners only; every output corner still carries
        its input vertex's position and normal."""
        pos, tris = spec.grid(30, 30)
        tris = np.asarray(tris, np.uint32).reshape(-1, 3)
        normals = np.tile(np.float32([0, 0, 1]), (len(pos), 1))
        normals[::7] = np.float32([0, 1, 0])
        moved = np.arange(5, len(pos), 97, dtype=np.uint32)
        truth = pos.copy()
        truth[moved, 2] += 0.25
        b = Builder()
        rows = np.zeros(len(pos), dtype=[('p', '<f4', 3), ('n', '<f4', 3)])
        rows['p'], rows['n'] = pos, normals
        view = b.view(rows.tobytes(), 34962)
        b.doc['bufferViews'][view]['byteStride'] = 24
        b.doc['accessors'] += [
            {'bufferView': view, 'componentType': spec.FLOAT, 'count': len(pos), 'type': 'VEC3',
             'min': truth.min(axis=0).tolist(), 'max': truth.max(axis=0).tolist()},
            {'bufferView': view, 'byteOffset': 12, 'componentType': spec.FLOAT,
             'count': len(pos), 'type': 'VEC3'}]
        b.sparse(0, moved, truth[moved])
        prims = [{'attributes': {'POSITION': 0, 'NORMAL': 1},
                  'indices': b.accessor(tris[k::45].ravel(), 'SCALAR', spec.UINT32,
                                        target=34963)} for k in range(45)]
        b.doc['meshes'].append({'primitives': prims})
        src = self.path('shared.gltf')
        b.write_gltf(src)
        for flags in ((), ('--group', 'primitive')):
            g, _ = self.bake_clean(src, 'shared.glb', *flags)
            for k, prim in enumerate(g.json['meshes'][0]['primitives']):
                corners = g.triangles(prim)
                np.testing.assert_array_equal(
                    g.accessor(prim['attributes']['POSITION'])[corners], truth[tris[k::45]])
                np.testing.assert_array_equal(
                    g.accessor(prim['attributes']['NORMAL'])[corners], normals[tris[k::45]])


if __name__ == '__main__':
    spec.RAPS_GLTF, spec.VALIDATOR, spec.NODE = sys.argv[1], sys.argv[2], sys.argv[3]
    unittest.main(argv=sys.argv[:1], verbosity=2)
