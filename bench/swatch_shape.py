#!/usr/bin/env python3
"""The shape of a relaxed swatch with free borders (`skein pattern --relax --tiled`), as issue 24 asks for it:
its width and height, how far its edges rise out of the plane (curl), and how deep its wales fold (the
corrugation that makes a rib pull in). Lengths in mm; rises and depths also in yarn diameters (the radius from
the .bcc header). The fabric lies in the xy plane with +z its front (the knit side of a stitch model, h > 0).

Usage: swatch_shape.py YARN.bcc WALES   prints one JSON object:
  width_mm, height_mm   the 5th to 95th percentile of x over the middle half of the rows, of y over the middle
                        half of the wales (the border loops and the yarn's ends left out)
  side_rise_d           the mean z of the outermost eighth of the width on both sides, less that of the middle
                        half, in yarn diameters: < 0 when the side edges curl to the back (stockinette)
  end_rise_d            the same for the bottom and top eighths of the height: > 0 when they curl to the front
  fold_depth_d          the peak-to-peak mean z across a repeat of the wales' mean z (the middle half of the
                        rows, each wale's half-width bin), averaged over the wales: how far knit and purl
                        columns stand apart front to back, in yarn diameters
The yarn is the Catmull-Rom spline through the control points, 8 samples a segment."""
import json
import sys

from bcc import read_curves
from open_area import catmull_rom


def samples(curve, per_segment=8):
    pts = [curve[0]] + list(curve) + [curve[-1]]
    out = []
    for i in range(1, len(pts) - 2):
        for k in range(per_segment):
            out.append(catmull_rom(pts[i - 1], pts[i], pts[i + 1], pts[i + 2], k / per_segment))
    out.append(tuple(curve[-1]))
    return out


def percentile(values, q):
    values = sorted(values)
    return values[min(len(values) - 1, max(0, int(q * (len(values) - 1) + 0.5)))]


def mean(values):
    return sum(values) / len(values) if values else 0.0


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    radius, curves = read_curves(sys.argv[1])
    wales = int(sys.argv[2])
    if radius <= 0 or wales < 2:
        sys.exit(f"{sys.argv[1]}: the header names no yarn radius, or fewer than 2 wales asked")
    points = [p for c in curves for p in samples(c)]
    x_lo, x_hi = percentile([p[0] for p in points], 0.05), percentile([p[0] for p in points], 0.95)
    y_lo, y_hi = percentile([p[1] for p in points], 0.05), percentile([p[1] for p in points], 0.95)
    middle_rows = [p for p in points if y_lo + 0.25 * (y_hi - y_lo) <= p[1] <= y_hi - 0.25 * (y_hi - y_lo)]
    middle_wales = [p for p in points if x_lo + 0.25 * (x_hi - x_lo) <= p[0] <= x_hi - 0.25 * (x_hi - x_lo)]
    width = percentile([p[0] for p in middle_rows], 0.95) - percentile([p[0] for p in middle_rows], 0.05)
    height = percentile([p[1] for p in middle_wales], 0.95) - percentile([p[1] for p in middle_wales], 0.05)
    d = 2 * radius

    def rise(axis, lo, hi):
        span = hi - lo
        edge = [p[2] for p in points if p[axis] < lo + span / 8 or p[axis] > hi - span / 8]
        centre = [p[2] for p in points if lo + span / 4 <= p[axis] <= hi - span / 4]
        return (mean(edge) - mean(centre)) / d

    # Half-wale bins across the middle rows; the fold is the peak-to-peak of their mean z over each pair of
    # neighbouring wales (a 1x1 rib's repeat), averaged.
    bins = 2 * wales
    step = (x_hi - x_lo) / bins
    zs = [[] for _ in range(bins)]
    for p in middle_rows:
        i = int((p[0] - x_lo) / step)
        if 0 <= i < bins:
            zs[i].append(p[2])
    profile = [mean(z) for z in zs]
    folds = [max(profile[i:i + 4]) - min(profile[i:i + 4]) for i in range(0, bins - 3, 2)]
    print(json.dumps({
        "width_mm": round(width, 3), "height_mm": round(height, 3),
        "side_rise_d": round(rise(0, x_lo, x_hi), 3), "end_rise_d": round(rise(1, y_lo, y_hi), 3),
        "fold_depth_d": round(mean(folds) / d, 3),
        "z_profile_mm": [round(z, 2) for z in profile]}))


if __name__ == "__main__":
    main()
