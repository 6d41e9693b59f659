#!/usr/bin/env bash
# The picture of docs/BENCHMARKS.md "The free width by bracketing" (docs/images/free-width-by-bracketing.png):
# stockinette, seed and the 1x1 and 2x2 ribs at take-up 0.8, each periodic patch's width found by bracketing from
# its emitted width, tiled to eight wales by six rows (--preview), laid out at one scale (bench/lay_out.py:
# stockinette and seed above, the ribs below) and drawn front, back and three-quarter. Prints each one's width.
# Usage: bench/free_width_picture.sh [OUT.png]   (about 20 s on the 2-core machine)
source "$(dirname "$0")/common.sh"
out=${1:-docs/images/free-width-by-bracketing.png}
specs=(stockinette:8x6 seed:4x3 rib-1x1:4x6 rib-2x2:2x6)
for spec in "${specs[@]}"; do
  name=${spec%:*}
  "$skein" -q pattern "patterns/$name.knit" --relax --free-period x --period-method bracket --take-up 0.8 --max-steps 40000 --no-audit \
    --tile "${spec#*:}" --preview "$tmp/$name.bcc" -o "$tmp/$name-repeat.bcc" --report "$tmp/$name.json" || true
  field "$tmp/$name.json" "'$name: %s after %d steps, a repeat %.3f mm wide' % (r['stopped_by'], r['steps'], r['free_period']['repeat_mm'][0])"
done
python3 bench/lay_out.py "$tmp/all.bcc" "$tmp/stockinette.bcc:0:50" "$tmp/seed.bcc:50:50" "$tmp/rib-1x1.bcc:0:0" "$tmp/rib-2x2.bcc:50:0"
"$skein" -q render "$tmp/all.bcc" --color yarn --views three -o "$out"
echo "wrote $out"
