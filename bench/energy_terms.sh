#!/usr/bin/env bash
# What the relaxed fabric's energy is made of (issue 24, part 4; docs/BENCHMARKS.md "What the energy is made of"):
# periodic patches relaxed with a free width (skein pattern --relax --free-period x, L-BFGS, force rule) at three
# internal stretch stiffnesses (Leaf eq. 8, which only keeps a spline's parameter speed even), and one repeat's
# energy by term from the report (free_period.repeat_energy_terms): bending (eq. 7), stretch (eq. 8), length
# (eq. 1), contact (eq. 9), with the width per wale against stockinette's at the same stiffness.
# Usage: bench/energy_terms.sh   (prints a markdown table; about 3 minutes on 2 cores)
source "$(dirname "$0")/common.sh"
echo "| k_stretch | pattern | steps | stopped | width per wale [mm] | against stockinette | bending | stretch | length | contact | stretch share |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
for ks in 20 1 0.2; do
  for entry in stockinette:1 garter:1 rib-1x1:2; do
    p=${entry%%:*}
    "$skein" -q pattern "patterns/$p.knit" --relax --free-period x --no-audit --k-stretch "$ks" --max-steps 12000 \
      -o "$tmp/$p-$ks.bcc" --report "$tmp/$p-$ks.json"
    python3 - "$tmp/$p-$ks.json" "$tmp/stockinette-$ks.json" "${entry##*:}" "$ks" "$p" <<'PY'
import json, sys
r, plain, wales = json.load(open(sys.argv[1])), json.load(open(sys.argv[2])), int(sys.argv[3])
f, t = r["free_period"], r["free_period"]["repeat_energy_terms"]
wale = f["repeat_mm"][0] / wales
print(f"| {sys.argv[4]} | {sys.argv[5]} | {r['steps']} | {r['stopped_by']} | {wale:.2f} | {wale / plain['free_period']['repeat_mm'][0]:.3f} | "
      f"{t['bending']:.3f} | {t['stretch']:.3f} | {t['length']:.3f} | {t['contact']:.4f} | {t['stretch'] / f['repeat_energy']:.0%} |")
PY
  done
done
