#!/usr/bin/env python3
"""The field corpus (issue 25): surfaces nobody labeled, written as OBJ into a folder. Generated, so the corpus
needs no download: triangle meshes (a tube, a jittered sheet, a sphere, a torus, a U-shaped sheet that branches),
quads with a pole of valence 8, and the bundled garments fanned into triangles.
Usage: bench/field_meshes.py FOLDER"""
import math
import os
import random
import sys


def write(folder, name, points, faces):
    with open(os.path.join(folder, name + ".obj"), "w") as out:
        out.write("# skein field corpus: %s (bench/field_meshes.py)\n" % name)
        for p in points:
            out.write("v %.6f %.6f %.6f\n" % p)
        for f in faces:
            out.write("f " + " ".join(str(i + 1) for i in f) + "\n")


def grid(nx, ny, wrap, at, keep=lambda i, j: True):
    """Quads of an (nx x ny) grid over [0,1]^2 mapped by `at`, each cut in two along alternating diagonals."""
    cols = nx if wrap else nx + 1
    points = [at(i / nx, j / ny) for j in range(ny + 1) for i in range(cols)]
    vid = lambda i, j: j * cols + (i % nx if wrap else i)
    faces = []
    for j in range(ny):
        for i in range(nx):
            if not keep(i, j):
                continue
            a, b, c, d = vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)
            faces += [(a, b, c), (a, c, d)] if (i + j) % 2 else [(a, b, d), (b, c, d)]
    used = sorted({v for f in faces for v in f})
    remap = {v: k for k, v in enumerate(used)}
    return [points[v] for v in used], [tuple(remap[v] for v in f) for f in faces]


def icosphere(radius, levels):
    g = (1 + 5 ** 0.5) / 2
    p = [(-1, g, 0), (1, g, 0), (-1, -g, 0), (1, -g, 0), (0, -1, g), (0, 1, g), (0, -1, -g), (0, 1, -g), (g, 0, -1), (g, 0, 1), (-g, 0, -1), (-g, 0, 1)]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2),
         (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    scale = lambda v: tuple(radius * x / math.sqrt(sum(y * y for y in v)) for x in v)
    p = [scale(v) for v in p]
    for _ in range(levels):
        mid, nf = {}, []
        def m(a, b):
            k = (min(a, b), max(a, b))
            if k not in mid:
                p.append(scale(tuple((p[a][i] + p[b][i]) / 2 for i in range(3))))
                mid[k] = len(p) - 1
            return mid[k]
        for a, b, c in f:
            ab, bc, ca = m(a, b), m(b, c), m(c, a)
            nf += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = nf
    return p, f


def pole_dome():
    """Quads: 8 meet at a pole of valence 8, then 3 rings of 16; a border at the rim."""
    around, rings = 16, 4
    p = [(0.0, 40.0, 0.0)]
    for r in range(1, rings + 1):
        for s in range(around):
            a, rho = 2 * math.pi * s / around, 90.0 * r / rings
            p.append((rho * math.cos(a), 40 - rho * rho / 200, rho * math.sin(a)))
    at = lambda r, s: 1 + (r - 1) * around + s % around
    f = [(0, at(1, s), at(1, s + 1), at(1, s + 2)) for s in range(0, around, 2)]
    f += [(at(r, s + 1), at(r, s), at(r + 1, s), at(r + 1, s + 1)) for r in range(1, rings) for s in range(around)]
    return p, f


def sock():
    """A sock: a leg tube (open cuff at the top) bending through a heel into a foot that ends in a round toe.
    Circles of radius 35 swept along leg, heel arc and foot (parallel-transported frames), triangulated."""
    centres = []
    for k in range(16):  # the leg, down from the cuff at y = 250 to y = 100
        centres.append((0.0, 250.0 - 10 * k, 0.0))
    for k in range(1, 13):  # the heel: a quarter circle of radius 60 turning from -y to +x
        a = math.pi / 2 * k / 12
        centres.append((60 - 60 * math.cos(a), 100 - 60 * math.sin(a), 0.0))
    for k in range(1, 13):  # the foot, along +x
        centres.append((60 + 10 * k, 40.0, 0.0))
    radius, around = 35.0, 24
    points, rings = [], []
    for i, c in enumerate(centres):
        t = [centres[min(i + 1, len(centres) - 1)][k] - centres[max(i - 1, 0)][k] for k in range(3)]
        n = math.sqrt(sum(x * x for x in t))
        t = [x / n for x in t]
        u = (0.0, 0.0, 1.0)  # every tangent lies in the xy plane: z is a normal all along
        v = (t[1] * u[2] - t[2] * u[1], t[2] * u[0] - t[0] * u[2], t[0] * u[1] - t[1] * u[0])
        ring = []
        for j in range(around):
            a = 2 * math.pi * j / around
            ring.append(len(points))
            points.append(tuple(c[k] + radius * (math.cos(a) * u[k] + math.sin(a) * v[k]) for k in range(3)))
        rings.append(ring)
    end = centres[-1]
    for k in range(1, 6):  # the toe: rings closing over a hemisphere
        a = math.pi / 2 * k / 6
        ring = []
        for j in range(around):
            b = 2 * math.pi * j / around
            ring.append(len(points))
            points.append((end[0] + radius * math.sin(a), end[1] - radius * math.cos(a) * math.sin(b), end[2] + radius * math.cos(a) * math.cos(b)))
        rings.append(ring)
    tip = len(points)
    points.append((end[0] + radius, end[1], end[2]))
    faces = []
    for r in range(len(rings) - 1):
        for j in range(around):
            a, b, c, d = rings[r][j], rings[r][(j + 1) % around], rings[r + 1][(j + 1) % around], rings[r + 1][j]
            faces += [(a, b, c), (a, c, d)]
    for j in range(around):
        faces.append((rings[-1][j], rings[-1][(j + 1) % around], tip))
    return points, faces


def fanned(path):
    """An OBJ's polygons fanned into triangles."""
    points, faces = [], []
    for line in open(path):
        w = line.split()
        if not w:
            continue
        if w[0] == "v":
            points.append(tuple(float(x) for x in w[1:4]))
        elif w[0] == "f":
            idx = [int(x.split("/")[0]) - 1 for x in w[1:]]
            faces += [(idx[0], idx[k], idx[k + 1]) for k in range(1, len(idx) - 1)]
    return points, faces


def main():
    folder = sys.argv[1]
    os.makedirs(folder, exist_ok=True)
    rng = random.Random(3)
    write(folder, "tube-triangles", *grid(20, 6, True, lambda u, v: (40 * math.cos(2 * math.pi * u), 120 * v, 40 * math.sin(2 * math.pi * u))))
    def jittered(u, v):
        inner = 0 < u < 1 and 0 < v < 1
        return (120 * (u + (rng.uniform(-0.3, 0.3) / 12 if inner else 0)), 100 * (v + (rng.uniform(-0.3, 0.3) / 10 if inner else 0)), 0.0)
    write(folder, "sheet-triangles", *grid(12, 10, False, jittered))
    write(folder, "cone-triangles", *grid(24, 8, True, lambda u, v: ((60 - 45 * v) * math.cos(2 * math.pi * u), 100 * v, (60 - 45 * v) * math.sin(2 * math.pi * u))))
    write(folder, "sphere", *icosphere(50, 4))
    write(folder, "torus", *grid(32, 16, True, lambda u, v: ((60 + 20 * math.cos(2 * math.pi * v)) * math.cos(2 * math.pi * u), 20 * math.sin(2 * math.pi * v),
                                                              (60 + 20 * math.cos(2 * math.pi * v)) * math.sin(2 * math.pi * u))))
    write(folder, "pole-valence-8", *pole_dome())
    write(folder, "sock", *sock())
    write(folder, "u-sheet", *grid(12, 12, False, lambda u, v: (120 * u, 120 * v, 0.0), lambda i, j: not (j >= 6 and 4 <= i < 8)))
    models = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "models")
    for name in ("swatch", "tube", "beanie", "mitten", "tea_cozy", "sweater"):
        write(folder, name + "-fanned", *fanned(os.path.join(models, name + ".obj")))


if __name__ == "__main__":
    main()
