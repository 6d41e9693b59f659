#!/usr/bin/env python3
"""RMS and largest control-point distance between two .bcc files of the same yarn, in yarn radii (the radius
from the first file's header): "RMS,LARGEST". For the bench scripts; `skein audit` gives the same figures with
the crossing and linking-number checks, which take minutes on a garment.

With a third file, PREVIOUS, only the points where A lies exactly where PREVIOUS has it count, and the count is
appended ("RMS,LARGEST,POINTS"): for a local re-relaxation A warm-started from PREVIOUS, the points outside the
rings it relaxed."""
import math
import sys

from bcc import read_curves


def read(path):
    radius, curves = read_curves(path)
    return radius, [p for curve in curves for p in curve]


if len(sys.argv) not in (3, 4):
    sys.exit("usage: yarn_distance.py A.bcc B.bcc [PREVIOUS.bcc]")
radius, a = read(sys.argv[1])
_, b = read(sys.argv[2])
if len(a) != len(b) or radius <= 0:
    sys.exit(f"{sys.argv[2]}: not the yarn of {sys.argv[1]} (or no radius in its header)")
pairs = list(zip(a, b))
if len(sys.argv) == 4:
    _, previous = read(sys.argv[3])
    if len(previous) != len(a):
        sys.exit(f"{sys.argv[3]}: not the yarn of {sys.argv[1]}")
    pairs = [(p, q) for p, q, r in zip(a, b, previous) if p == r]
    if not pairs:
        sys.exit(f"{sys.argv[1]}: no point lies where {sys.argv[3]} has it")
d = [math.dist(p, q) / radius for p, q in pairs]
line = f"{math.sqrt(sum(x * x for x in d) / len(d)):.4f},{max(d):.4f}"
print(line + (f",{len(d)}" if len(sys.argv) == 4 else ""))
