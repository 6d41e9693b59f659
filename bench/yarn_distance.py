#!/usr/bin/env python3
"""RMS and largest control-point distance between two .bcc files of the same yarn, in yarn radii (the radius
from the first file's header): "RMS,LARGEST". For the bench scripts; `skein audit` gives the same figures with
the crossing and linking-number checks, which take minutes on a garment."""
import math
import struct
import sys


def read(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:3] != b"BCC" or len(data) < 64:
        sys.exit(f"{path}: not a .bcc file")
    info = data[24:64].split(b"\0")[0].decode(errors="replace")
    radius = float(info.split("radius ")[1].split()[0]) if "radius " in info else 0.0
    curves, at, points = struct.unpack_from("<Q", data, 8)[0], 64, []
    for _ in range(curves):
        n = abs(struct.unpack_from("<i", data, at)[0])
        points.extend(struct.iter_unpack("<3f", data[at + 4:at + 4 + 12 * n]))
        at += 4 + 12 * n
    return radius, points


radius, a = read(sys.argv[1])
_, b = read(sys.argv[2])
if len(a) != len(b) or radius <= 0:
    sys.exit(f"{sys.argv[2]}: not the yarn of {sys.argv[1]} (or no radius in its header)")
d = [math.dist(p, q) / radius for p, q in zip(a, b)]
print(f"{math.sqrt(sum(x * x for x in d) / len(d)):.4f},{max(d):.4f}")
