#!/usr/bin/env python3
"""How many control points of a yarn (.bcc) its shape does not need (docs/BENCHMARKS.md, issue 10): walking each curve,
a point is dropped when the Catmull-Rom segment through its kept neighbours stays within TOL yarn radii of the curve
it replaces (the original segments on both sides, 8 samples each, against the new one at 64). Prints one CSV line
per tolerance: tolerance_r,points,removable,share. Usage: bench/spline_slack.py YARN.bcc [TOL ...] (default 0.05 0.1 0.2)."""
import math
import sys

from bcc import read_curves


def catmull_rom(p0, p1, p2, p3, t):
    t2, t3 = t * t, t * t * t
    w = (-0.5 * t3 + t2 - 0.5 * t, 1.5 * t3 - 2.5 * t2 + 1, -1.5 * t3 + 2 * t2 + 0.5 * t, 0.5 * t3 - 0.5 * t2)
    return [w[0] * p0[k] + w[1] * p1[k] + w[2] * p2[k] + w[3] * p3[k] for k in range(3)]


def removable(points, tolerance):
    """Points dropped greedily along one curve (ends and their neighbours kept)."""
    keep, dropped = [True] * len(points), 0
    for k in range(2, len(points) - 2):
        if not keep[k - 1]:
            continue
        before = points[k - 2] if keep[k - 2] else points[k - 3]
        original = [catmull_rom(points[k - 2], points[k - 1], points[k], points[k + 1], i / 8) for i in range(9)]
        original += [catmull_rom(points[k - 1], points[k], points[k + 1], points[k + 2], i / 8) for i in range(1, 9)]
        merged = [catmull_rom(before, points[k - 1], points[k + 1], points[k + 2], i / 64) for i in range(65)]
        if max(min(math.dist(o, m) for m in merged) for o in original) < tolerance:
            keep[k] = False
            dropped += 1
    return dropped


radius, curves = read_curves(sys.argv[1])
if radius <= 0:
    sys.exit(f"{sys.argv[1]}: no yarn radius in its header")
total = sum(len(c) for c in curves)
print("tolerance_r,points,removable,share")
for tolerance in [float(t) for t in sys.argv[2:]] or [0.05, 0.1, 0.2]:
    dropped = sum(removable(c, tolerance * radius) for c in curves)
    print(f"{tolerance},{total},{dropped},{dropped / total:.4f}")
