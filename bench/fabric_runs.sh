#!/usr/bin/env bash
# Relaxed fabric against real fabric (issue 24; docs/BENCHMARKS.md "Relaxed fabric"): periodic patches relaxed
# with a free width (variable cell, --free-period x: the rows held at the height they are emitted at) to their
# stress-free repeat, by L-BFGS under the force stop rule (skein pattern's defaults).
#  1. Plain knit (stockinette) at four loop lengths (stitch sizes) and two yarn radii: Munden's constant Kw =
#     wales per length x loop length against relaxed plain knit (dry relaxed ~ 3.8-4.0, fully relaxed ~ 4.2), and
#     Doyle's independence of the yarn diameter (Kc = courses per length x loop length is set by the held rows).
#  2. Stockinette, garter, 1x1 and 2x2 rib and seed at one yarn and loop length: width per wale and height per
#     course, against stockinette's.
# Usage: bench/fabric_runs.sh   (prints markdown tables; a run at a time, 2 threads)
source "$(dirname "$0")/common.sh"
run() {  # run NAME PATTERN ARGS...: a free-period relaxation, its report in $tmp/NAME.json
  local name=$1 pattern=$2
  shift 2
  "$skein" -q pattern "patterns/$pattern.knit" --relax --free-period x --no-audit -o "$tmp/$name.bcc" --report "$tmp/$name.json" "$@"
}
echo "| stitch emitted [mm] | yarn radius [mm] | loop length l [mm] | relaxed repeat [mm] | Kc | Kw | Kc/Kw | steps | s |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"
for r in 0.6 0.45; do
  for w in 5 6 7 8; do
    h=$(python3 -c "print(round($w * 5 / 6, 3))")
    run "plain-$w-$r" stockinette --stitch-size "$w" --stitch-height "$h" --yarn-radius "$r"
    field "$tmp/plain-$w-$r.json" "'| $w x $h | $r | %.2f | %.2f x %.2f | %.2f | %.2f | %.2f | %d | %.1f |' % (r['free_period']['loop_length_mm'], \
      *r['free_period']['repeat_mm'], r['free_period']['Kc'], r['free_period']['Kw'], r['free_period']['Kc'] / r['free_period']['Kw'], r['steps'], r['wall_seconds'])"
  done
done
echo
echo "| pattern | repeat (wales x courses) | relaxed repeat [mm] | width per wale [mm] | against stockinette | height per course [mm] | against stockinette | steps | s |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"
for p in stockinette garter rib-1x1 rib-2x2 seed; do
  run "$p" "$p"
  python3 - "$tmp/$p.json" "$tmp/stockinette.json" "$p" <<'PY'
import json, sys
r, s, name = json.load(open(sys.argv[1])), json.load(open(sys.argv[2])), sys.argv[3]
f, g = r["free_period"], s["free_period"]
wales = round(f["gauge_per_10cm"]["stitches"] * f["repeat_mm"][0] / 100)
courses = round(f["gauge_per_10cm"]["rows"] * f["repeat_mm"][1] / 100)
w, h = f["repeat_mm"][0] / wales, f["repeat_mm"][1] / courses
print(f"| {name} | {wales} x {courses} | {f['repeat_mm'][0]:.2f} x {f['repeat_mm'][1]:.2f} | {w:.2f} | {w / g['repeat_mm'][0]:.3f} | {h:.2f} | "
      f"{h / g['repeat_mm'][1]:.3f} | {r['steps']} | {r['wall_seconds']:.1f} |")
PY
done
