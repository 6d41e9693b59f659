#!/usr/bin/env python3
"""How far a relaxed fabric's rows bow across its width (issue 24: feather and fan's scallops). The control points
are put in rows by where they were emitted: bands a row high (`--row-height`, default 5 mm, the bundled stitch
height) from y = 0, where emission starts its first row. Each band of the middle half of the rows is cut into
eight columns across the yarn's width; its bow is the spread (largest less smallest) of the columns' mean relaxed
height y over the middle six columns (the outermost on each side left out, so three quarters of the width). A
flat row has a bow near 0; a scallop one as deep as its wave.

Usage: row_bow.py EMITTED.bcc RELAXED.bcc [--row-height H]   prints the median bow over the bands [mm]. RELAXED
must be EMITTED's yarn relaxed (the same points in the same order; a `skein pattern --preview` of the tiling
EMITTED was written from)."""
import math
import statistics
import sys

from bcc import read_curves


def main():
    args = sys.argv[1:]
    height = 5.0
    if "--row-height" in args:
        i = args.index("--row-height")
        height = float(args[i + 1])
        del args[i:i + 2]
    if len(args) != 2:
        sys.exit(__doc__)
    emitted = [p for c in read_curves(args[0])[1] for p in c]
    relaxed = [p for c in read_curves(args[1])[1] for p in c]
    if len(emitted) != len(relaxed):
        sys.exit(f"{args[1]}: not the yarn of {args[0]} (other point counts)")
    y0, y1 = min(p[1] for p in emitted), max(p[1] for p in emitted)
    x0, x1 = min(p[0] for p in emitted), max(p[0] for p in emitted)
    first, last = math.floor(y0 / height), math.floor(y1 / height)
    rows = last - first + 1
    bows = []
    for k in range(first + rows // 4, last + 1 - rows // 4):
        columns = {}
        for e, r in zip(emitted, relaxed):
            if k * height <= e[1] < (k + 1) * height:
                columns.setdefault(int(8 * (e[0] - x0) / (x1 - x0 + 1e-9)), []).append(r[1])
        means = [statistics.mean(v) for c, v in columns.items() if 0 < c < 7]
        if means:
            bows.append(max(means) - min(means))
    if not bows:
        sys.exit(f"{args[0]}: fewer than one row of {height} mm")
    print(f"{statistics.median(bows):.2f}")


if __name__ == "__main__":
    main()
