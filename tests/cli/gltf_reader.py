"""A small, independent glTF 2.0 reader for the tests: JSON, buffers (GLB BIN chunk, external
files, data uris of both encodings; none for a placeholder buffer), accessors as numpy arrays (strides, sparse, matrices are not needed here),
and image bytes. It trusts its input: the tests only give it the shared assets and raps-gltf's
outputs."""
import base64
import json
import os
import struct
import urllib.parse

import numpy as np

COMPONENT = {5120: np.int8, 5121: np.uint8, 5122: np.int16, 5123: np.uint16, 5125: np.uint32,
             5126: np.float32}
COUNT = {'SCALAR': 1, 'VEC2': 2, 'VEC3': 3, 'VEC4': 4, 'MAT2': 4, 'MAT3': 9, 'MAT4': 16}


class Gltf:
    def __init__(self, path):
        self.path = path
        self.folder = os.path.dirname(os.path.abspath(path))
        with open(path, 'rb') as fh:
            data = fh.read()
        self.bin = None
        if data[:4] == b'glTF':
            length = struct.unpack_from('<I', data, 12)[0]
            self.json = json.loads(data[20:20 + length])
            at = 20 + length
            if at < len(data):
                bin_length = struct.unpack_from('<I', data, at)[0]
                self.bin = data[at + 8:at + 8 + bin_length]
        else:
            self.json = json.loads(data)
        self.buffers = [self._load(b.get('uri'), b) for b in self.json.get('buffers', [])]

    def _load(self, uri, obj):
        if uri is None:  # the GLB's BIN chunk, or None for a placeholder buffer
            return self.bin if obj is self.json.get('buffers', [None])[0] else None
        if uri.startswith('data:'):
            header, payload = uri.split(',', 1)
            if header.endswith(';base64'):
                return base64.b64decode(payload)
            return urllib.parse.unquote_to_bytes(payload)
        with open(os.path.join(self.folder, urllib.parse.unquote(uri)), 'rb') as fh:
            return fh.read()

    def view_bytes(self, index):
        v = self.json['bufferViews'][index]
        start = v.get('byteOffset', 0)
        return self.buffers[v['buffer']][start:start + v['byteLength']]

    def accessor(self, index):
        a = self.json['accessors'][index]
        dtype = np.dtype(COMPONENT[a['componentType']])
        n = COUNT[a['type']]
        count = a['count']
        out = np.zeros((count, n), dtype=dtype)
        if 'bufferView' in a:
            view = self.json['bufferViews'][a['bufferView']]
            raw = self.view_bytes(a['bufferView'])
            stride = view.get('byteStride', dtype.itemsize * n)
            offset = a.get('byteOffset', 0)
            for i in range(count):
                start = offset + i * stride
                out[i] = np.frombuffer(raw[start:start + dtype.itemsize * n], dtype=dtype)
        sparse = a.get('sparse')
        if sparse:
            idx_dtype = np.dtype(COMPONENT[sparse['indices']['componentType']])
            raw = self.view_bytes(sparse['indices']['bufferView'])
            o = sparse['indices'].get('byteOffset', 0)
            idx = np.frombuffer(raw[o:o + idx_dtype.itemsize * sparse['count']], dtype=idx_dtype)
            raw = self.view_bytes(sparse['values']['bufferView'])
            o = sparse['values'].get('byteOffset', 0)
            values = np.frombuffer(raw[o:o + dtype.itemsize * n * sparse['count']], dtype=dtype)
            out[idx.astype(np.int64)] = values.reshape(-1, n)
        return out

    def triangles(self, prim):
        """The primitive's triangles as an (n, 3) array, strips and fans expanded (spec 3.7.2.1)."""
        mode = prim.get('mode', 4)
        if 'indices' in prim:
            v = self.accessor(prim['indices'])[:, 0].astype(np.int64)
        else:
            v = np.arange(self.json['accessors'][prim['attributes']['POSITION']]['count'])
        if mode == 4:
            return v[:len(v) // 3 * 3].reshape(-1, 3)
        if mode == 5:
            return np.array([[v[i], v[i + 1 + i % 2], v[i + 2 - i % 2]] for i in range(len(v) - 2)])
        if mode == 6:
            return np.array([[v[i + 1], v[i + 2], v[0]] for i in range(len(v) - 2)])
        return np.zeros((0, 3), dtype=np.int64)

    def image_bytes(self, index):
        image = self.json['images'][index]
        if 'bufferView' in image:
            return bytes(self.view_bytes(image['bufferView']))
        return self._load(image['uri'], image)
