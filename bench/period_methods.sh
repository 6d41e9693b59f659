#!/usr/bin/env bash
# The free width under tension by the two methods (issue 24; docs/BENCHMARKS.md "The free width by bracketing"):
# each pattern's periodic patch at take-up 0.8 with its width free (skein pattern's defaults otherwise: L-BFGS,
# the force rule; no audit; a 40,000-step cap), by --period-method frame (the width a variable of the points'
# L-BFGS) and bracket (fixed widths relaxed one after another until the stress-free one is bracketed), from the
# emitted width and from 0.85 of it.
# Usage: bench/period_methods.sh [PATTERN...]   (default: the table's thirteen; one markdown row per pattern and
# start; about 25 minutes on the 2-core machine, a run at a time)
source "$(dirname "$0")/common.sh"
patterns=("$@")
[ $# -eq 0 ] && patterns=(patterns/stockinette.knit patterns/garter.knit patterns/seed.knit patterns/rib-1x1.knit patterns/rib-2x2.knit
  patterns/written/eyelet-rows.txt patterns/charts/eyelet-columns.txt patterns/charts/lace-rib.txt patterns/eyelet-lace.knit
  patterns/written/rope-cable.txt patterns/written/feather-and-fan.txt patterns/honeycomb.knit)
run() {  # run PATTERN METHOD START: "stopped after steps, width, stress, seconds"
  local out=$tmp/r.json
  local t0=$(date +%s.%N)
  "$skein" -q pattern "$1" --relax --free-period x --period-method "$2" --period "$3x1" --no-audit --take-up 0.8 --max-steps 40000 \
    -o "$tmp/r.bcc" --report "$out" || true
  local t1=$(date +%s.%N)
  field "$out" "'%s | %d | %.3f | %+.4f | %.1f' % (r['stopped_by'], r['steps'], r['free_period']['repeat_mm'][0], r['free_period']['stress_over_bending'][0], $t1 - $t0)"
}
echo "| pattern | start | frame: stopped | steps | width [mm] | stress [B/r³] | s | bracket: stopped | steps | width [mm] | stress [B/r³] | s |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
for p in "${patterns[@]}"; do
  for start in 1 0.85; do
    echo "| $(basename "${p%.*}") | $start | $(run "$p" frame $start) | $(run "$p" bracket $start) |"
  done
done
