"""side_by_side.py LEFT.pfm RIGHT.pfm OUT.png [--scale N]: two linear PFM renders (Cycles |
memograph) as one sRGB PNG, clamped, a white gap between, each pixel N x N. Pure Python."""

import re
import struct
import sys
import zlib


def read_pfm(path):
    data = open(path, 'rb').read()
    m = re.match(rb'(P[Ff])\s+(\d+)\s+(\d+)\s+(\S+)\s', data)
    w, h, scale = int(m.group(2)), int(m.group(3)), float(m.group(4))
    ch = 3 if m.group(1) == b'PF' else 1
    v = struct.unpack_from(('<' if scale < 0 else '>') + '%df' % (w * h * ch), data, m.end())
    # PFM rows start at the bottom: return top row first.
    return w, h, [[tuple(v[(j * w + i) * ch:(j * w + i) * ch + 3]) if ch == 3 else (v[j * w + i],) * 3
                   for i in range(w)] for j in reversed(range(h))]


def srgb(x):
    x = min(max(x, 0.0), 1.0)
    return int(255 * (12.92 * x if x < 0.0031308 else 1.055 * x ** (1 / 2.4) - 0.055) + 0.5)


def main(argv):
    scale = int(argv[argv.index('--scale') + 1]) if '--scale' in argv else 1
    w, h, a = read_pfm(argv[0])
    w2, h2, b = read_pfm(argv[1])
    assert (w, h) == (w2, h2), 'sizes differ'
    gap = max(2, scale)
    W, H = 2 * w * scale + gap, h * scale
    raw = bytearray()
    for y in range(H):
        raw.append(0)
        for x in range(W):
            if x < w * scale:
                p = a[y // scale][x // scale]
            elif x < w * scale + gap:
                p = (1.0, 1.0, 1.0)
            else:
                p = b[y // scale][(x - w * scale - gap) // scale]
            raw += bytes(srgb(c) for c in p)

    def chunk(t, d):
        return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d))
    with open(argv[2], 'wb') as f:
        f.write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', W, H, 8, 2, 0, 0, 0))
                + chunk(b'IDAT', zlib.compress(bytes(raw))) + chunk(b'IEND', b''))


if __name__ == '__main__':
    main(sys.argv[1:])
