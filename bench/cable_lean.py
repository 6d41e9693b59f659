#!/usr/bin/env python3
"""How far a cable's crossing strands lean (issue 24: "crossing strands lean by at least 30 degrees from the course
direction"). The strands are the yarn pieces of the cable faces (stitches/cable*.stitch: each piece runs from the
cable face's bottom edge to its top edge, moving its loops sideways), found as the runs of control points the stitch
ids side file (docs/FORMATS.md) gives no stitch face, away from the swatch's borders (where the turns, cast-on and
bind-off pieces are faceless too). A strand's lean is the angle of the line from its first to its last point
against the course direction (x).

Usage: cable_lean.py EMITTED.bcc IDS.csv [RELAXED.bcc]   prints "STRANDS,MEDIAN_DEG,MEAN_DEG,MIN_DEG,MAX_DEG" for the
emitted yarn and, given, for the relaxed one: the strands are chosen in the emitted yarn (the borders are where it
was emitted) and measured in each. IDS.csv is the emission's (`skein pattern --tile NxM --ids`; a relaxed yarn keeps
its points' order)."""
import csv
import math
import statistics
import sys

from bcc import read_curves


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    _, curves = read_curves(sys.argv[1])
    points = [p for c in curves for p in c]
    states = [points] + ([[p for c in read_curves(sys.argv[3])[1] for p in c]] if len(sys.argv) == 4 else [])
    if any(len(s) != len(points) for s in states):
        sys.exit(f"{sys.argv[3]}: not the yarn of {sys.argv[1]} (other point counts)")
    ids = list(csv.DictReader(open(sys.argv[2])))
    if len(ids) != len(points):
        sys.exit(f"{sys.argv[2]}: {len(ids)} points, but {sys.argv[1]} has {len(points)}")
    runs, run = [], []
    for k, row in enumerate(ids):
        faceless = row["face"] == "-1"
        if run and (not faceless or ids[run[-1]]["curve"] != row["curve"]):
            runs.append(run)
            run = []
        if faceless:
            run.append(k)
    if run:
        runs.append(run)
    xs, ys = [p[0] for p in points], [p[1] for p in points]
    mx, my = 0.08 * (max(xs) - min(xs)), 0.08 * (max(ys) - min(ys))
    strands = []
    for run in runs:
        a, b = points[run[0]], points[run[-1]]
        cx, cy = (a[0] + b[0]) / 2, (a[1] + b[1]) / 2
        if len(run) >= 3 and min(xs) + mx < cx < max(xs) - mx and min(ys) + my < cy < max(ys) - my:
            strands.append(run)
    if not strands:
        sys.exit(f"{sys.argv[1]}: no cable strands away from the borders")
    for state in states:
        angles = [math.degrees(math.atan2(abs(state[r[-1]][1] - state[r[0]][1]), abs(state[r[-1]][0] - state[r[0]][0]))) for r in strands]
        print(f"{len(angles)},{statistics.median(angles):.1f},{statistics.mean(angles):.1f},{min(angles):.1f},{max(angles):.1f}")


if __name__ == "__main__":
    main()
