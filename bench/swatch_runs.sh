#!/usr/bin/env bash
# Swatches with free borders against real fabric (issue 24; docs/BENCHMARKS.md "What holds the shape"): each
# pattern tiled to 8 wales x 8 courses and relaxed as bare yarn (`skein pattern --relax --tiled`, L-BFGS), once to
# the force stop rule's defaults and once continued to 40,000 steps at a force tolerance 100 times smaller.
# bench/swatch_shape.py measures each: width and height, the side and end edges' rise (curl) and the wales' fold
# depth in yarn diameters. Real stockinette curls (sides to the back: side rise < 0), garter and seed lie flat,
# and ribs pull in (narrower than stockinette) by folding (knit wales in front of purl ones).
# Usage: bench/swatch_runs.sh   (prints a markdown table; about 15 minutes on 2 cores)
source "$(dirname "$0")/common.sh"
echo "| pattern | run | steps | stopped | energy | width [mm] | against stockinette | height [mm] | side rise [d] | end rise [d] | fold depth [d] |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
for run in default continued; do
  extra=()
  [ "$run" = continued ] && extra=(--max-steps 40000 --force-tolerance 0.005 --energy-stall 1e-8)
  for entry in stockinette:8x8 garter:8x4 seed:4x4 rib-1x1:4x8 rib-2x2:2x8; do
    p=${entry%%:*}
    "$skein" -q pattern "patterns/$p.knit" --relax --tiled --tile "${entry##*:}" --no-audit "${extra[@]}" \
      -o "$tmp/$p-$run.bcc" --report "$tmp/$p-$run.json"
    python3 bench/swatch_shape.py "$tmp/$p-$run.bcc" 8 > "$tmp/$p-$run.shape"
    python3 - "$tmp/$p-$run.json" "$tmp/$p-$run.shape" "$tmp/stockinette-$run.shape" "$p" "$run" <<'PY'
import json, sys
r, s, plain = json.load(open(sys.argv[1])), json.load(open(sys.argv[2])), json.load(open(sys.argv[3]))
print(f"| {sys.argv[4]} | {sys.argv[5]} | {r['steps']} | {r['stopped_by']} | {r['energy']:.1f} | {s['width_mm']:.2f} | "
      f"{s['width_mm'] / plain['width_mm']:.3f} | {s['height_mm']:.2f} | {s['side_rise_d']:+.2f} | {s['end_rise_d']:+.2f} | {s['fold_depth_d']:.2f} |")
PY
  done
done
