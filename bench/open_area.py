#!/usr/bin/env python3
"""The largest hole a fabric's yarn leaves, seen from the front: the largest disc in the xy plane that no yarn
tube covers, its centre inside the middle half of the yarn's extent in x and in y (away from the borders).
For issue 24's lace figure ("each hole's largest empty disc at least 3 times stockinette's").

Usage: open_area.py YARN.bcc [STEP]   prints "DIAMETER_MM,DIAMETER_R" (the disc's diameter in mm and in yarn
radii); STEP is the grid spacing of the disc centres in yarn radii (default 0.1). The yarn is the Catmull-Rom
spline through the control points (docs/FORMATS.md), sampled 8 times a segment; a tube covers what lies within
its radius of the centreline's projection."""
import math
import sys

from bcc import read_curves


def catmull_rom(p0, p1, p2, p3, t):
    t2, t3 = t * t, t * t * t
    return tuple(0.5 * (2 * b + (-a + c) * t + (2 * a - 5 * b + 4 * c - d) * t2 + (-a + 3 * b - 3 * c + d) * t3)
                 for a, b, c, d in zip(p0, p1, p2, p3))


def polyline(curve, samples=8):
    """The spline through `curve`'s points as (x, y) points, the end segments with doubled end points."""
    pts = [curve[0]] + list(curve) + [curve[-1]]
    out = []
    for i in range(1, len(pts) - 2):
        for k in range(samples):
            out.append(catmull_rom(pts[i - 1], pts[i], pts[i + 1], pts[i + 2], k / samples)[:2])
    out.append(curve[-1][:2])
    return out


def segment_distance(px, py, ax, ay, bx, by):
    dx, dy = bx - ax, by - ay
    length2 = dx * dx + dy * dy
    t = 0.0 if length2 == 0 else max(0.0, min(1.0, ((px - ax) * dx + (py - ay) * dy) / length2))
    return math.hypot(px - ax - t * dx, py - ay - t * dy)


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    radius, curves = read_curves(sys.argv[1])
    if radius <= 0:
        sys.exit(f"{sys.argv[1]}: the header names no yarn radius")
    step = (float(sys.argv[2]) if len(sys.argv) == 3 else 0.1) * radius
    segments = []
    for curve in curves:
        line = polyline(curve)
        segments += [(a[0], a[1], b[0], b[1]) for a, b in zip(line, line[1:])]
    xs = [s[0] for s in segments] + [s[2] for s in segments]
    ys = [s[1] for s in segments] + [s[3] for s in segments]
    x0, x1, y0, y1 = min(xs), max(xs), min(ys), max(ys)
    # Segments bucketed on a grid of cells 2r wide, searched ring by ring outwards from each centre.
    cell = 2 * radius
    grid = {}
    for s in segments:
        for i in range(int(math.floor(min(s[0], s[2]) / cell)), int(math.floor(max(s[0], s[2]) / cell)) + 1):
            for j in range(int(math.floor(min(s[1], s[3]) / cell)), int(math.floor(max(s[1], s[3]) / cell)) + 1):
                grid.setdefault((i, j), []).append(s)

    def clearance(px, py):
        ci, cj, best, ring = int(math.floor(px / cell)), int(math.floor(py / cell)), math.inf, 0
        while ring * cell - cell < best and ring < 1000:  # a ring's cells are at least (ring - 1) cells away
            for i in range(ci - ring, ci + ring + 1):
                for j in range(cj - ring, cj + ring + 1):
                    if max(abs(i - ci), abs(j - cj)) != ring:
                        continue
                    for s in grid.get((i, j), ()):
                        best = min(best, segment_distance(px, py, *s))
            ring += 1
        return best - radius

    largest = 0.0
    y = y0 + 0.25 * (y1 - y0)
    while y <= y0 + 0.75 * (y1 - y0):
        x = x0 + 0.25 * (x1 - x0)
        while x <= x0 + 0.75 * (x1 - x0):
            largest = max(largest, clearance(x, y))
            x += step
        y += step
    print(f"{2 * largest:.3f},{2 * largest / radius:.2f}")


if __name__ == "__main__":
    main()
