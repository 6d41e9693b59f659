#!/usr/bin/env python3
"""How much a relaxed patch rises and sinks stitch by stitch (issue 24: honeycomb cells, docs/BENCHMARKS.md).

Usage: bench/stitch_relief.py FILE.bcc... [--stitch WxH]

The middle 60 % of the yarn's x and y range is cut into stitch-sized cells (W x H mm, default 6 x 5, the
bundled stitch size); for each cell the mean depth (z) of its control points. Prints, per file, the spread of
those means (standard deviation and range) and the standard deviation of every point's z. A flat fabric has a
spread near 0; cells, bubbles or ridges a stitch wide raise it."""
import statistics
import sys

from bcc import read_curves


def relief(path, w, h):
    _, curves = read_curves(path)
    pts = [p for c in curves for p in c]
    xs, ys = sorted(p[0] for p in pts), sorted(p[1] for p in pts)
    x0, x1 = xs[len(xs) // 5], xs[4 * len(xs) // 5]
    y0, y1 = ys[len(ys) // 5], ys[4 * len(ys) // 5]
    cells, inside = {}, []
    for x, y, z in pts:
        if x0 <= x <= x1 and y0 <= y <= y1:
            cells.setdefault((int((x - x0) // w), int((y - y0) // h)), []).append(z)
            inside.append(z)
    means = [statistics.mean(v) for v in cells.values() if len(v) > 3]
    if len(means) < 2:
        sys.exit(f"{path}: fewer than two stitch cells with points; is --stitch right?")
    return statistics.pstdev(means), max(means) - min(means), statistics.pstdev(inside)


def main():
    args, w, h = sys.argv[1:], 6.0, 5.0
    if "--stitch" in args:
        i = args.index("--stitch")
        w, h = (float(v) for v in args[i + 1].split("x"))
        del args[i:i + 2]
    if not args:
        sys.exit(__doc__)
    print("file\tcell depth sd [mm]\tcell depth range [mm]\tpoint depth sd [mm]")
    for path in args:
        sd, span, point_sd = relief(path, w, h)
        print(f"{path}\t{sd:.3f}\t{span:.3f}\t{point_sd:.3f}")


if __name__ == "__main__":
    main()
