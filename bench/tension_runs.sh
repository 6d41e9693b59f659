#!/usr/bin/env bash
# Structures under tension (issue 24, part 5; docs/BENCHMARKS.md "Structures under tension"): lace, a cable,
# feather and fan and honeycomb relaxed at the emitted yarn length (take-up 1) and 20 % shorter (0.8), where
# stockinette finds one width from every start. Periodic patches with a free width (skein pattern's defaults:
# L-BFGS, the force rule; no audit), the cable also as a 2 x 2 tiling with free borders.
#  - lace: the largest hole seen from the front (bench/open_area.py on a 4 x 4 preview) against stockinette's at
#    the same take-up;
#  - the cable: its strands' lean (bench/cable_lean.py) and its panel's width against the same panel uncrossed;
#  - feather and fan: how far its rows bow across a repeat (the scallops), from the emitted rows (row_bow.py);
#  - honeycomb: the width and the cells' depth spread (bench/stitch_relief.py).
# Usage: bench/tension_runs.sh [TAKE_UP...]   (default 1 0.8; prints one markdown row per case; about 25 minutes
# on the 2-core machine, a run at a time)
source "$(dirname "$0")/common.sh"
takes=("$@")
[ $# -eq 0 ] && takes=(1 0.8)
cap=40000
relax() {  # relax NAME PATTERN TAKE_UP ARGS...: a free-width relaxation, its report in $tmp/NAME.json
  local name=$1 pattern=$2 t=$3
  shift 3
  "$skein" -q pattern "$pattern" --relax --free-period x --no-audit --take-up "$t" --max-steps $cap -o "$tmp/$name.bcc" --report "$tmp/$name.json" "$@"
}
outcome() { field "$1" "'%s after %d steps' % (r['stopped_by'], r['steps'])"; }
width() { field "$1" "r['free_period']['repeat_mm'][0]"; }
cat > "$tmp/uncrossed.txt" <<'EOF'
# name: the rope cable's panel, uncrossed
Panel of 8 sts.
Row 1 (RS): P2, k4, p2.
Row 2: K2, p4, k2.
Row 3: P2, k4, p2.
Row 4: K2, p4, k2.
EOF
# The emitted tilings the cable's lean and the fan's bow are measured from (the same at every take-up).
"$skein" -q pattern patterns/written/rope-cable.txt --tile 2x2 -o "$tmp/rope-em.bcc" --ids "$tmp/rope-ids.csv"
"$skein" -q pattern patterns/written/feather-and-fan.txt --tile 1x3 -o "$tmp/fan-em.bcc"
emitted_lean=$(python3 bench/cable_lean.py "$tmp/rope-em.bcc" "$tmp/rope-ids.csv" | cut -d, -f2)
emitted_bow=$(python3 bench/row_bow.py "$tmp/fan-em.bcc" "$tmp/fan-em.bcc")
echo "| pattern | take-up | measure | value | against | ratio | run |"
echo "| --- | --- | --- | --- | --- | --- | --- |"
for t in "${takes[@]}"; do
  relax st-$t patterns/stockinette.knit "$t" --tile 4x4 --preview "$tmp/st-pv-$t.bcc"
  gap=$(python3 bench/open_area.py "$tmp/st-pv-$t.bcc" 0.2 | cut -d, -f1)
  echo "| stockinette | $t | largest gap [mm] | $gap | | | $(outcome "$tmp/st-$t.json") |"
  for p in patterns/written/eyelet-rows.txt patterns/charts/eyelet-columns.txt patterns/charts/lace-rib.txt patterns/eyelet-lace.knit; do
    n=$(basename "${p%.*}")
    relax "$n-$t" "$p" "$t" --tile 4x4 --preview "$tmp/$n-pv-$t.bcc"
    hole=$(python3 bench/open_area.py "$tmp/$n-pv-$t.bcc" 0.2 | cut -d, -f1)
    echo "| $n | $t | largest hole [mm] | $hole | stockinette's $gap | $(python3 -c "print(f'{$hole / $gap:.2f}')") | $(outcome "$tmp/$n-$t.json") |"
  done
  relax rope-$t patterns/written/rope-cable.txt "$t"
  relax flat-$t "$tmp/uncrossed.txt" "$t"
  w=$(width "$tmp/rope-$t.json") u=$(width "$tmp/flat-$t.json")
  echo "| rope cable (C4B) | $t | panel width [mm] | $(printf %.2f "$w") | uncrossed $(printf %.2f "$u") | $(python3 -c "print(f'{$w / $u:.3f}')") | $(outcome "$tmp/rope-$t.json"); uncrossed $(outcome "$tmp/flat-$t.json") |"
  "$skein" -q pattern patterns/written/rope-cable.txt --tile 2x2 --relax --tiled --no-audit --take-up "$t" --max-steps $cap -o "$tmp/rope-tiled-$t.bcc" --report "$tmp/rope-tiled-$t.json"
  lean=$(python3 bench/cable_lean.py "$tmp/rope-em.bcc" "$tmp/rope-ids.csv" "$tmp/rope-tiled-$t.bcc" | tail -1)
  echo "| rope cable (C4B), 2 x 2 free borders | $t | strands' median lean [°] | $(echo "$lean" | cut -d, -f2) | emitted $emitted_lean | | $(outcome "$tmp/rope-tiled-$t.json") |"
  relax fan-$t patterns/written/feather-and-fan.txt "$t" --tile 1x3 --preview "$tmp/fan-pv-$t.bcc"
  echo "| feather and fan | $t | rows' bow [mm] | $(python3 bench/row_bow.py "$tmp/fan-em.bcc" "$tmp/fan-pv-$t.bcc") | as emitted $emitted_bow | | $(outcome "$tmp/fan-$t.json") |"
  relax honeycomb-$t patterns/honeycomb.knit "$t"
  relief=$(python3 bench/stitch_relief.py "$tmp/honeycomb-$t.bcc" | tail -1 | cut -f2)
  echo "| honeycomb | $t | width [mm]; cells' depth sd [mm] | $(printf %.2f "$(width "$tmp/honeycomb-$t.json")"); $relief | | | $(outcome "$tmp/honeycomb-$t.json") |"
done
