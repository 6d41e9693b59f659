#!/usr/bin/env python3
"""Bend a relaxed swatch onto a cylinder, or measure how curved one is (issue 24: does the model's fabric have a
curling moment and a bending stiffness?). The fabric lies in the xy plane, courses along x, wales along y, +z its
front (the knit side).

Usage:
  bend_swatch.py bend IN.bcc OUT.bcc AXIS RADIUS SIDE   map IN onto a cylinder of RADIUS mm whose axis runs along
        the wales (AXIS course: the courses bend, as when the side edges curl) or along the courses (AXIS wale:
        the wales bend, as when the top and bottom curl); SIDE front puts the centre of curvature in front (the
        knit side concave), back behind it. Lengths along the mid-surface are kept; yarn in front of it is
        shortened or lengthened by its height over the radius.
  bend_swatch.py curvature IN.bcc AXIS                 print the mean curvature along AXIS [1/mm] of the middle
        half across the other direction: the least-squares parabola z = a u^2 + b u + c, curvature 2a (> 0: the
        front concave)."""
import math
import sys

from bcc import read_curves, rewrite_points


def points(path):
    return [p for curve in read_curves(path)[1] for p in curve]


def along(axis):
    """(index of the bent direction, index of the other in-plane direction)."""
    if axis not in ("course", "wale"):
        sys.exit(f"axis must be course or wale, not {axis}")
    return (0, 1) if axis == "course" else (1, 0)


def bend(src, dst, axis, radius, side):
    if side not in ("front", "back") or not radius > 0:
        sys.exit("bend needs a positive radius and the side front or back")
    u, _ = along(axis)
    pts = points(src)
    centre_u = (min(p[u] for p in pts) + max(p[u] for p in pts)) / 2
    mid_z = sum(p[2] for p in pts) / len(pts)
    sign = 1.0 if side == "front" else -1.0

    def move(p):
        t = (p[u] - centre_u) / radius
        r = radius - sign * (p[2] - mid_z)  # distance from the cylinder's axis
        q = list(p)
        q[u] = centre_u + r * math.sin(t)
        q[2] = mid_z + sign * (radius - r * math.cos(t))
        return q

    rewrite_points(src, dst, move)


def parabola(us, vs):
    """Least-squares a, b, c of v = a u^2 + b u + c."""
    rows = [[u * u, u, 1.0, v] for u, v in zip(us, vs)]
    m = [[sum(r[i] * r[j] for r in rows) for j in range(4)] for i in range(3)]
    for i in range(3):
        pivot = max(range(i, 3), key=lambda k: abs(m[k][i]))
        m[i], m[pivot] = m[pivot], m[i]
        for k in range(3):
            if k != i:
                f = m[k][i] / m[i][i]
                m[k] = [x - f * y for x, y in zip(m[k], m[i])]
    return [m[i][3] / m[i][i] for i in range(3)]


def curvature(src, axis):
    u, w = along(axis)
    pts = points(src)
    across = sorted(p[w] for p in pts)
    lo, hi = across[len(across) // 4], across[3 * len(across) // 4]
    mid = [p for p in pts if lo < p[w] < hi]
    mean_u = sum(p[u] for p in mid) / len(mid)
    return 2 * parabola([p[u] - mean_u for p in mid], [p[2] for p in mid])[0]


if __name__ == "__main__":
    if len(sys.argv) == 7 and sys.argv[1] == "bend":
        bend(sys.argv[2], sys.argv[3], sys.argv[4], float(sys.argv[5]), sys.argv[6])
    elif len(sys.argv) == 4 and sys.argv[1] == "curvature":
        print(f"{curvature(sys.argv[2], sys.argv[3]):.5f}")
    else:
        sys.exit(__doc__)
