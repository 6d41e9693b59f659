#!/usr/bin/env bash
# Is the stress-free width a property of the fabric or of where the run starts? (issue 24; docs/BENCHMARKS.md
# "The free width stays where it starts".) Each pattern's periodic patch is relaxed with a free width (skein
# pattern's defaults: L-BFGS, the force rule, the rows held at the emitted height) from three starts, 0.85, 1 and
# 1.15 times its emitted width (--period), and the widths it ends at are compared; then stockinette at fixed widths
# from 0.85 to 1.15, for one repeat's energy and the width's stress there. Usage: bench/free_width_starts.sh [PNG]
# (prints markdown tables; with PNG, also draws stockinette's energy against width with the three free ends; a
# run at a time, 2 threads; 3 to 6 minutes on the 2-core machine).
source "$(dirname "$0")/common.sh"
png=${1:-}
starts() {  # starts KEY LABEL PATTERN ARGS...: one table row, the three starts (reports $tmp/KEY-START.json)
  local key=$1 label=$2 pattern=$3
  shift 3
  for p in 0.85 1 1.15; do
    "$skein" -q pattern "patterns/$pattern.knit" --relax --free-period --no-audit --period "${p}x1" -o "$tmp/s.bcc" --report "$tmp/$key-$p.json" "$@"
  done
  python3 - "$label" "$tmp/$key" <<'PY'
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
starts plain "stockinette, r 0.6 mm (default)" stockinette
starts garter "garter, r 0.6 mm" garter
starts rib1 "1x1 rib, r 0.6 mm" rib-1x1
starts rib2 "2x2 rib, r 0.6 mm" rib-2x2
starts plain09 "stockinette, r 0.9 mm" stockinette --yarn-radius 0.9
starts plain11 "stockinette, r 1.1 mm" stockinette --yarn-radius 1.1
starts worsted "stockinette, --yarn worsted" stockinette --yarn worsted
starts taut06 "stockinette, r 0.6 mm, take-up 0.8" stockinette --take-up 0.8
starts taut11 "stockinette, r 1.1 mm, take-up 0.85" stockinette --yarn-radius 1.1 --take-up 0.85
starts plain13 "stockinette, r 1.3 mm" stockinette --yarn-radius 1.3
echo
echo "| stockinette at a fixed width [mm] | steps | one repeat's energy | the width's stress [B/r³] |"
echo "| --- | --- | --- | --- |"
for p in 0.85 0.9 0.95 1 1.05 1.1 1.15; do
  "$skein" -q pattern patterns/stockinette.knit --relax --no-audit --period "${p}x1" -o "$tmp/s.bcc" --report "$tmp/fixed-$p.json"
  field "$tmp/fixed-$p.json" "'| %.2f | %d | %.3f | %+.3f |' % (r['fixed_period']['period_x_mm'][0], r['steps'], r['fixed_period']['repeat_energy'], r['fixed_period']['stress_over_bending'][0])"
done
if [ -n "$png" ]; then
  command -v gnuplot > /dev/null || { echo "drawing $png needs gnuplot (apt-get install gnuplot-nox)" >&2; exit 2; }
  for p in 0.85 0.9 0.95 1 1.05 1.1 1.15; do field "$tmp/fixed-$p.json" "'%f %f' % (r['fixed_period']['period_x_mm'][0], r['fixed_period']['repeat_energy'])"; done > "$tmp/fixed.dat"
  for p in 0.85 1 1.15; do field "$tmp/plain-$p.json" "'%f %f %f' % (6 * $p, r['free_period']['repeat_mm'][0], r['free_period']['repeat_energy'])"; done > "$tmp/free.dat"
  gnuplot <<EOF
set terminal pngcairo size 1000,620 font ',13'
set output '$png'
set title "Stockinette's periodic repeat (r 0.6 mm, rows held at 5 mm): no width of its own"
set xlabel 'width of one stitch [mm]'
set ylabel "one repeat's energy"
set grid
set key top right
plot '$tmp/fixed.dat' using 1:2 with linespoints lw 2 pt 7 title 'relaxed at a fixed width', \
     '$tmp/free.dat' using 1:3:(\$2 - \$1):(0) with vectors head filled lw 2 lc rgb '#c0392b' title 'free width: from its start to where it stops', \
     '$tmp/free.dat' using 2:3 with points pt 9 ps 2 lc rgb '#c0392b' notitle
EOF
  echo "drew $png"
fi
