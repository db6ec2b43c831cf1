"""A PNG decoder for the tests, in the standard library and numpy only (Debian's python3 has no
PIL): 8-bit greyscale, RGB or RGBA, not interlaced, which is what raps-gltf's previews (written
by stb_image_write) are. Anything else raises ValueError, so that a preview in another format is
a test failure and never a silently wrong picture.
"""
import struct
import zlib

import numpy as np

SIGNATURE = b'\x89PNG\r\n\x1a\n'
CHANNELS = {0: 1, 2: 3, 6: 4}  # colour type -> samples per pixel


def _sequential(line, prior, bpp, paeth):
    """One Average or Paeth scanline undone; line and prior are lists of ints."""
    row = [0] * len(line)
    for i, value in enumerate(line):
        left = row[i - bpp] if i >= bpp else 0
        up = prior[i]
        if not paeth:
            row[i] = (value + ((left + up) >> 1)) & 0xFF
            continue
        upper_left = prior[i - bpp] if i >= bpp else 0
        p = left + up - upper_left
        pa, pb, pc = abs(p - left), abs(p - up), abs(p - upper_left)
        predictor = left if pa <= pb and pa <= pc else (up if pb <= pc else upper_left)
        row[i] = (value + predictor) & 0xFF
    return np.array(row, dtype=np.int32)


def _unfilter(raw, height, stride, bpp):
    """The scanlines of the decompressed stream, each filter (PNG spec 9.2) undone."""
    out = np.zeros((height, stride), dtype=np.uint8)
    prior = np.zeros(stride, dtype=np.int32)
    pos = 0
    for y in range(height):
        kind = raw[pos]
        line = np.frombuffer(raw, dtype=np.uint8, count=stride, offset=pos + 1).astype(np.int32)
        pos += 1 + stride
        if kind == 0:
            row = line
        elif kind == 2:  # Up
            row = (line + prior) & 0xFF
        elif kind == 1:  # Sub: each byte adds the one bpp before it, a running sum per channel
            row = line.copy()
            for c in range(bpp):
                row[c::bpp] = np.cumsum(line[c::bpp]) & 0xFF
        elif kind in (3, 4):  # Average, Paeth: sequential along the row (plain lists: fast)
            row = _sequential(line.tolist(), prior.tolist(), bpp, kind == 4)
        else:
            raise ValueError(f'scanline {y}: unknown filter type {kind}')
        out[y] = row
        prior = row
    return out


def read_png(path):
    """The pixels of the PNG at path as a (height, width, channels) uint8 array."""
    with open(path, 'rb') as fh:
        data = fh.read()
    if data[:8] != SIGNATURE:
        raise ValueError('not a PNG signature')
    pos, header, idat = 8, None, []
    while pos < len(data):
        length, kind = struct.unpack('>I4s', data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        crc, = struct.unpack('>I', data[pos + 8 + length:pos + 12 + length])
        if zlib.crc32(kind + body) != crc:
            raise ValueError(f'chunk {kind!r}: bad CRC')
        if kind == b'IHDR':
            header = struct.unpack('>IIBBBBB', body)
        elif kind == b'IDAT':
            idat.append(body)
        elif kind == b'IEND':
            break
        pos += 12 + length
    if header is None:
        raise ValueError('no IHDR chunk')
    width, height, depth, colour, _, _, interlace = header
    if depth != 8 or colour not in CHANNELS or interlace != 0:
        raise ValueError(f'unsupported PNG: depth {depth}, colour type {colour}, interlace {interlace}')
    channels = CHANNELS[colour]
    raw = zlib.decompress(b''.join(idat))
    if len(raw) != height * (1 + width * channels):
        raise ValueError(f'{len(raw)} bytes of image data for {width} x {height}')
    return _unfilter(raw, height, width * channels, channels).reshape(height, width, channels)
