"""Fixtures of the Python package's tests: where the CLI and the shared data are (CTest passes
them as OCTRACE_EXE and OCTRACE_SHARED_DATA), and a PNG decoder to read the CLI's images."""

import os
import pathlib
import struct
import subprocess
import zlib

import numpy as np
import pytest


@pytest.fixture(scope="session")
def octrace_exe():
    exe = os.environ.get("OCTRACE_EXE")
    if not exe or not os.path.exists(exe):
        pytest.skip("OCTRACE_EXE (the CLI) is not set: run through CTest")
    return exe


def shared(relative):
    """A file of ../shared/data, or a skip when the shared data are absent."""
    root = os.environ.get("OCTRACE_SHARED_DATA", str(pathlib.Path(__file__).parents[2] / ".." / "shared" / "data"))
    path = pathlib.Path(root) / relative
    if not path.exists():
        pytest.skip(f"needs the shared data: {path}")
    return str(path)


@pytest.fixture(scope="session")
def levitus():
    return shared("ocean/levitus_climatology.cdf")


def run_cli(exe, *args):
    r = subprocess.run([exe, *map(str, args)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return r


def read_png(path):
    """The pixels of an 8-bit RGB or RGBA PNG (no interlace) as (H, W, 4) uint8."""
    data = pathlib.Path(path).read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat, header = 8, b"", None
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    width, height, bits, colour, _, _, interlace = header
    assert bits == 8 and colour in (2, 6) and interlace == 0, header
    channels = 4 if colour == 6 else 3
    raw = zlib.decompress(idat)
    stride = width * channels
    out = np.zeros((height, stride), dtype=np.int32)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = np.frombuffer(raw, dtype=np.uint8, count=stride, offset=y * (stride + 1) + 1).astype(np.int32)
        prior = out[y - 1] if y else np.zeros(stride, dtype=np.int32)
        if kind == 0:
            out[y] = line
        elif kind == 2:
            out[y] = (line + prior) & 255
        else:  # sub, average, Paeth: byte by byte
            row = np.zeros(stride, dtype=np.int32)
            for x in range(stride):
                a = row[x - channels] if x >= channels else 0
                b = prior[x]
                c = prior[x - channels] if x >= channels else 0
                if kind == 1:
                    predictor = a
                elif kind == 3:
                    predictor = (a + b) // 2
                else:
                    p = a + b - c
                    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                    predictor = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                row[x] = (line[x] + predictor) & 255
            out[y] = row
    pixels = out.astype(np.uint8).reshape(height, width, channels)
    if channels == 3:
        pixels = np.concatenate([pixels, np.full((height, width, 1), 255, np.uint8)], axis=2)
    return pixels
