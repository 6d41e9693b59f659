#!/usr/bin/env python3
"""RMS and largest control-point distance between two .bcc files of the same yarn, in yarn radii (the radius
from the first file's header): "RMS,LARGEST". For the bench scripts; `skein audit` gives the same figures with
the crossing and linking-number checks, which take minutes on a garment."""
import math
import sys

from bcc import read_curves


def read(path):
    radius, curves = read_curves(path)
    return radius, [p for curve in curves for p in curve]


radius, a = read(sys.argv[1])
_, b = read(sys.argv[2])
if len(a) != len(b) or radius <= 0:
    sys.exit(f"{sys.argv[2]}: not the yarn of {sys.argv[1]} (or no radius in its header)")
d = [math.dist(p, q) / radius for p, q in zip(a, b)]
print(f"{math.sqrt(sum(x * x for x in d) / len(d)):.4f},{max(d):.4f}")
