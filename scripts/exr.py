"""A reader of the OpenEXR files octrace writes (io/src/image/ExrWriter.cpp), numpy only: used by
scripts/smooth_targets.py and bench/peers/normals.py."""
import struct
import zlib

import numpy as np


def read_exr(path, names):
    """The channels `names` of an OpenEXR scanline file (no or ZIP/ZIPS compression; HALF or FLOAT
    channels) as float32 arrays of rows, by name."""
    b = open(path, "rb").read()
    assert b[:4] == b"\x76\x2f\x31\x01", "not an OpenEXR file"
    p, attrs = 8, {}
    while b[p] != 0:
        name_end = b.index(b"\0", p)
        type_end = b.index(b"\0", name_end + 1)
        size = struct.unpack_from("<i", b, type_end + 1)[0]
        attrs[b[p:name_end].decode()] = b[type_end + 5:type_end + 5 + size]
        p = type_end + 5 + size
    p += 1
    chans, q, cl = [], 0, attrs["channels"]
    while cl[q] != 0:
        e = cl.index(b"\0", q)
        chans.append((cl[q:e].decode(), struct.unpack_from("<i", cl, e + 1)[0]))
        q = e + 17
    xmin, ymin, xmax, ymax = struct.unpack("<4i", attrs["dataWindow"])
    w, h = xmax - xmin + 1, ymax - ymin + 1
    comp = attrs["compression"][0]
    lines = {0: 1, 2: 1, 3: 16}[comp]
    nchunks = (h + lines - 1) // lines
    offsets = struct.unpack_from(f"<{nchunks}Q", b, p)
    size_of = {1: 2, 2: 4, 0: 4}
    out = {n: np.zeros((h, w), dtype=np.float32) for n in names}
    for off in offsets:
        y, n = struct.unpack_from("<ii", b, off)
        data = b[off + 8:off + 8 + n]
        rows = min(lines, ymax + 1 - y)
        raw = sum(size_of[t] for _, t in chans) * w * rows
        if comp != 0 and n < raw:
            raw_t = np.frombuffer(zlib.decompress(data), dtype=np.uint8).astype(np.int64)
            # Undo the predictor: t[i] = t[i-1] + t[i] - 128 (mod 256).
            t = ((raw_t[0] + np.cumsum(np.concatenate(([0], raw_t[1:] - 128)))) % 256).astype(np.uint8)
            half = (len(t) + 1) // 2
            data = np.empty(len(t), dtype=np.uint8)
            data[0::2], data[1::2] = t[:half], t[half:]
            data = data.tobytes()
        pos = 0
        for r in range(rows):
            for name, typ in sorted(chans):
                k = size_of[typ] * w
                if name in out:
                    out[name][y - ymin + r] = np.frombuffer(data[pos:pos + k], dtype="<f4" if typ == 2 else "<f2")
                pos += k
    return out
