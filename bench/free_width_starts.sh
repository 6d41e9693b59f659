#!/usr/bin/env bash
# Is the stress-free width a property of the fabric or of where the run starts? (issue 24; docs/BENCHMARKS.md
# "The free width stays where it starts".) Each pattern's periodic patch is relaxed with a free width (skein
# pattern's defaults: L-BFGS, the force rule, the rows held at the emitted height) from three starts, 0.85, 1 and
# 1.15 times its emitted width (--period), and the widths it ends at are compared; then stockinette at fixed widths
# from 0.85 to 1.15, for one repeat's energy and the width's stress there. Usage: bench/free_width_starts.sh
# (prints markdown tables; a run at a time, 2 threads; about 6 minutes on the 2-core machine).
source "$(dirname "$0")/common.sh"
starts() {  # starts LABEL PATTERN ARGS...: one table row, the three starts
  local label=$1 pattern=$2
  shift 2
  for p in 0.85 1 1.15; do
    "$skein" -q pattern "patterns/$pattern.knit" --relax --free-period --no-audit --period "${p}x1" -o "$tmp/s.bcc" --report "$tmp/$pattern-$p.json" "$@"
  done
  python3 - "$label" "$tmp/$pattern" <<'PY'
import json, sys
label, stem = sys.argv[1], sys.argv[2]
runs = [json.load(open(f"{stem}-{p}.json")) for p in ("0.85", "1", "1.15")]
width = [r["free_period"]["repeat_mm"][0] for r in runs]
energy = [r["free_period"]["repeat_energy"] for r in runs]
kw = [r["free_period"]["Kw"] for r in runs]
cells = [f"{w:.2f} ({r['steps']}{'' if r['converged'] else ', ' + r['stopped_by']})" for w, r in zip(width, runs)]
print(f"| {label} | " + " | ".join(cells) + f" | {100 * (max(width) - min(width)) / width[1]:.1f} % | "
      f"{100 * (max(energy) - min(energy)) / min(energy):.2f} % | {kw[0]:.2f} to {kw[2]:.2f} |")
PY
}
echo "| pattern, yarn | from 0.85 of the emitted width [mm] (steps) | from 1 | from 1.15 | width spread | energy spread | Kw |"
echo "| --- | --- | --- | --- | --- | --- | --- |"
starts "stockinette, r 0.6 mm (default)" stockinette
starts "garter, r 0.6 mm" garter
starts "1x1 rib, r 0.6 mm" rib-1x1
starts "2x2 rib, r 0.6 mm" rib-2x2
starts "stockinette, r 0.9 mm" stockinette --yarn-radius 0.9
starts "stockinette, r 1.1 mm" stockinette --yarn-radius 1.1
starts "stockinette, --yarn worsted" stockinette --yarn worsted
starts "stockinette, r 0.6 mm, take-up 0.8" stockinette --take-up 0.8
starts "stockinette, r 1.1 mm, take-up 0.85" stockinette --yarn-radius 1.1 --take-up 0.85
starts "stockinette, r 1.3 mm" stockinette --yarn-radius 1.3
echo
echo "| stockinette at a fixed width [mm] | steps | one repeat's energy | the width's stress [B/r³] |"
echo "| --- | --- | --- | --- |"
for p in 0.85 0.9 0.95 1 1.05 1.1 1.15; do
  "$skein" -q pattern patterns/stockinette.knit --relax --no-audit --period "${p}x1" -o "$tmp/s.bcc" --report "$tmp/fixed-$p.json"
  field "$tmp/fixed-$p.json" "'| %.2f | %d | %.3f | %+.3f |' % (r['fixed_period']['period_x_mm'][0], r['steps'], r['fixed_period']['repeat_energy'], r['fixed_period']['stress_over_bending'][0])"
done
