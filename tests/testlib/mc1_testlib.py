"""What the end-to-end test scripts share (tests/workbench, tests/workbench2,
tests/waveform): failing with the test's name, running a program with its
exit status checked, and reading a PNG screenshot without a library.

    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "testlib"))
    import mc1_testlib as lib
    lib.setup("waveform frame", work=WORK, bin_dir=BIN)
"""
import os
import struct
import subprocess
import sys
import zlib

_name, _work, _bin = "test", None, ""


def setup(name, work=None, bin_dir=""):
    """The test's name for its messages; the directory programs run in (None:
    the current one); where tool() finds the build's programs."""
    global _name, _work, _bin
    _name, _work, _bin = name, work, bin_dir


def fail(msg):
    print(f"{_name}: {msg}", file=sys.stderr)
    sys.exit(1)


def run(args, want=0, timeout=900):
    """Runs args (in the work directory); fails unless it exits `want`."""
    p = subprocess.run(args, capture_output=True, text=True, timeout=timeout, cwd=_work)
    if p.returncode != want:
        fail(f"{' '.join(args)}: exit {p.returncode} (wanted {want})\n{p.stdout}{p.stderr}")
    return p


def tool(name):
    return os.path.join(_bin, name)


def png_pixels(path):
    """(width, height, bytes per pixel, rows of RGB/RGBA bytes) of an 8-bit
    non-interlaced RGB or RGBA PNG (what Chromium's screenshots are)."""
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        fail(f"{path}: not a PNG")
    at, idat, w, h, bpp = 8, b"", 0, 0, 3
    while at < len(data):
        n, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + n]
        if kind == b"IHDR":
            w, h, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or interlace or colour not in (2, 6):
                fail(f"{path}: PNG kind not read here (depth {depth}, colour {colour})")
            bpp = 4 if colour == 6 else 3
        elif kind == b"IDAT":
            idat += body
        at += 12 + n
    raw, rows, prev, stride = zlib.decompress(idat), [], bytearray(w * bpp), w * bpp + 1
    for y in range(h):
        f, line = raw[y * stride], bytearray(raw[y * stride + 1:(y + 1) * stride])
        for i in range(len(line)):  # the PNG filters: none, sub, up, average, Paeth
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return w, h, bpp, rows


def png_pixel(path, x, y):
    """The RGB of pixel (x, y)."""
    _, _, bpp, rows = png_pixels(path)
    return tuple(rows[y][x * bpp:x * bpp + 3])
