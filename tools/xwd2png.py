#!/usr/bin/env python3
"""Converts an X window dump (XWD, as Xvfb -fbdir writes its screen) of
depth 24/32 bits per pixel, ZPixmap, to PNG; the standard library only.
   tools/xwd2png.py Xvfb_screen0 out.png"""
import struct
import sys
import zlib


def main(src, dst):
    data = open(src, "rb").read()
    h = struct.unpack(">25I", data[:100])
    header_size, fmt, depth, width, height = h[0], h[2], h[3], h[4], h[5]
    bits_per_pixel, line_bytes, ncolors = h[11], h[12], h[19]
    byte_order = h[7]
    if fmt != 2 or bits_per_pixel != 32:
        sys.exit(f"{src}: format {fmt}, {bits_per_pixel} bits per pixel: only ZPixmap at 32 bpp is read")
    pixels = data[header_size + ncolors * 12:]
    rows = []
    for y in range(height):
        line = pixels[y * line_bytes:y * line_bytes + width * 4]
        out = bytearray(b"\x00")
        for x in range(width):
            p = line[4 * x:4 * x + 4]
            b, g, r = (p[0], p[1], p[2]) if byte_order == 0 else (p[3], p[2], p[1])
            out += bytes((r, g, b))
        rows.append(bytes(out))
    raw = b"".join(rows)

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b"")
    open(dst, "wb").write(png)
    del depth


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: xwd2png.py IN.xwd OUT.png")
    main(sys.argv[1], sys.argv[2])
