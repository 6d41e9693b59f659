#!/usr/bin/env python3
"""Lays several .bcc yarn files out side by side in one, so that one picture (skein render OUT.bcc --views flat)
shows them at one scale: each file's curves are moved so that its bounding box's lower left corner lies at
(DX, DY) mm. The header (and so the radius) is the first file's.

Usage: lay_out.py OUT.bcc A.bcc:DX:DY [B.bcc:DX:DY ...]"""
import struct
import sys

from bcc import read_curves


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    header, body, count, points = None, bytearray(), 0, 0
    for spec in sys.argv[2:]:
        path, dx, dy = spec.rsplit(":", 2)
        with open(path, "rb") as f:
            data = f.read()
        if header is None:
            header = bytearray(data[:64])
        _, curves = read_curves(path)
        x0 = min(p[0] for c in curves for p in c)
        y0 = min(p[1] for c in curves for p in c)
        at = 64
        for curve in curves:
            n = struct.unpack_from("<i", data, at)[0]  # negative for a closed curve: kept as it is
            body += struct.pack("<i", n)
            for x, y, z in curve:
                body += struct.pack("<3f", x - x0 + float(dx), y - y0 + float(dy), z)
            at += 4 + 12 * abs(n)
        count += len(curves)
        points += sum(len(c) for c in curves)
    struct.pack_into("<QQ", header, 8, count, points)  # the header's curve and control point totals
    with open(sys.argv[1], "wb") as f:
        f.write(header + body)


if __name__ == "__main__":
    main()
