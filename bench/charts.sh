#!/usr/bin/env bash
# The evidence charts of docs/evidence.md (issue 9), drawn with gnuplot from runs of build/bin/skein:
#   speed      residual and energy against wall time per integrator, with and without mesh relaxation
#              first, on the mitten (glove class) and the sweater; every step audited, the auditor's count
#              in the legend
#   stability  integrator x step size x contact stiffness on a swatch and on two squeezed linked rings:
#              converged, not converged in the time cap, blew up, or pull-through found by the auditor
#              (with the guard and without it)
#   periodic   every bundled knit's periodic patch against the centre of a relaxed 5 x 5 tiling: cost and RMS
#   local      the mitten with 0.2 to 1 % of its stitches repainted: local re-relaxation against a full one
#              (issue 10; bench/local_runs.sh)
#   active     the mitten relaxed from its emission with and without the active set: residual against time,
#              and the share of points integrated per step (issue 10)
#   sampling   the mitten relaxed from its emission with Leaf's contact samples and adaptive ones: residual
#              against step (issue 10)
# Usage: bench/charts.sh [speed|stability|periodic|local|active|sampling|all|plots]   (plots: redraw all from the CSVs)
# Env: MITTEN_SECONDS, SWEATER_SECONDS: the cap per speed run (300 and 180).
# Writes docs/images/charts/*.png and the measured data beside them as CSV.
source "$(dirname "$0")/common.sh"
what=${1:-all}
out=docs/images/charts
mkdir -p "$out"
command -v gnuplot > /dev/null || { echo "bench/charts.sh needs gnuplot (apt-get install gnuplot-nox)" >&2; exit 2; }

# The first lines of every chart's gnuplot script: a PNG of SIZE (W,H) in font size FONT written to FILE.
png_head() {  # size font file
  printf "set terminal pngcairo size %s font ',%s'\nset output '%s'\n" "$1" "$2" "$3"
}

# One relax-yarn run; prints "stopped_by,steps,wall_seconds,residual,pull_through_events" from its report.
relax() {  # input log args...
  local input=$1 log=$2
  shift 2
  rm -f "$tmp/r.json"  # a run that fails before its report must not be read as the one before it
  "$skein" -q relax-yarn "$input" -o "$tmp/out.bcc" --report "$tmp/r.json" --log "$log" "$@" || true
  python3 -c "
import json; r = json.load(open('$tmp/r.json'))
print(','.join(str(x) for x in [r['stopped_by'], r['steps'], round(r['wall_seconds'], 2), r['residual'], r['pull_through_events']]))"
}

speed() {
  for model in mitten sweater; do
    local cap=${MITTEN_SECONDS:-300}
    [[ $model == sweater ]] && cap=${SWEATER_SECONDS:-180}
    mesh_relaxed "$model" "$tmp/$model-mesh-relaxed.skein"
    local summary=$out/speed-$model.csv
    echo "method,start,stopped_by,steps,wall_seconds,residual,pull_through_events,cap_seconds" > "$summary"
    for method in fire euler; do
      for start in tessellated mesh-relaxed; do
        local result
        result=$(relax "$tmp/$model-$start.skein" "$out/speed-$model-$method-$start.csv" --method "$method" --max-seconds "$cap" --max-steps 1000000)
        echo "$method,$start,$result,$cap" >> "$summary"
      done
    done
  done
  speed_plots
}

# Residual and energy against time from the speed runs' logs (their CSV summaries name the runs).
speed_plots() {
  for model in mitten sweater; do
    local summary=$out/speed-$model.csv residual="" energy="" caption=""
    while IFS=, read -r method start _ _ _ _ events cap; do
      local log=$out/speed-$model-$method-$start.csv title="$method from the $start mesh ($events pull-through)"
      caption=$cap
      residual+="'$log' using 10:3 with lines lw 2 title '$title', "
      energy+="'$log' using 10:2 with lines lw 2 title '$title', "
    done < <(tail -n +2 "$summary")
    gnuplot <<EOF
$(png_head 1200,1100 13 "$out/speed-$model.png")
set datafile separator ','
set multiplot layout 2,1 title "$model: yarn relaxation against wall time (cap ${caption} s; 2 threads, every step audited)"
set logscale y
set format y '10^{%L}'
set grid
set key top right font ',11'
set ylabel 'residual |∇E| / |∇E_0|'
plot ${residual%, }
set xlabel 'wall time [s]'
set ylabel 'energy'
plot ${energy%, }
unset multiplot
EOF
  done
}

stability() {
  # Two cases: a swatch of knitting (400 stitches at 10 x 8 mm), and two linked rings given 30 % of their
  # yarn's length, which pull tight against each other.
  "$skein" -q stitch models/swatch.obj --auto-label --stitch-size 10 --stitch-height 8 -o "$tmp/swatch.skein"
  python3 - "$tmp/rings.bcc" <<'EOF'
import math, struct, sys
def ring(c, u, v):
    return [[c[i] + 3 * (math.cos(2 * math.pi * k / 24) * u[i] + math.sin(2 * math.pi * k / 24) * v[i]) for i in range(3)] for k in range(24)]
rings = [ring([0, 0, 0], [1, 0, 0], [0, 1, 0]), ring([3, 0, 0], [1, 0, 0], [0, 0, 1])]
out = b'BCC' + bytes([0x44]) + b'C0' + bytes([3, 1]) + struct.pack('<QQ', 2, 48) + b'skein yarn, radius 0.5 mm'.ljust(40, b'\0')
for r in rings:
    out += struct.pack('<i', -len(r)) + b''.join(struct.pack('<fff', *p) for p in r)
open(sys.argv[1], 'wb').write(out)
EOF
  local data=$out/stability.csv
  echo "case,method,guard,step_factor,contact_factor,stopped_by,steps,wall_seconds,residual,pull_through_events,outcome" > "$data"
  for case in swatch rings; do
    local input=$tmp/swatch.skein contacts="0.25 4" extra=()
    [[ $case == rings ]] && input=$tmp/rings.bcc contacts=1 extra=(--take-up 0.3)
    for method in fire euler; do
      local base=0.02
      [[ $method == euler ]] && base=0.002
      # The guard with the default movement limit (0.25 r per step), the guard with 1 r, and no guard with 1 r.
      for guard in "on" "on, moves 1 r" "off, moves 1 r"; do
        local flags=("${extra[@]}")
        [[ $guard == *"1 r" ]] && flags+=(--max-move 1 --contact-margin 2)
        [[ $guard == off* ]] && flags+=(--no-guard)
        for step in 1 4 16 64 256; do
          for contact in $contacts; do
            local h k result outcome
            h=$(python3 -c "print($base * $step)")
            k=$(python3 -c "print(50 * $contact)")
            result=$(relax "$input" "$tmp/log.csv" --method "$method" "${flags[@]}" --time-step "$h" --k-contact "$k" --max-seconds 10 --max-steps 1000000)
            IFS=, read -r stopped _ _ _ events <<< "$result"
            if [[ $events != 0 ]]; then outcome=pull-through
            elif [[ $stopped == diverged ]]; then outcome=blew-up
            elif [[ $stopped == converged ]]; then outcome=converged
            else outcome=not-converged; fi
            echo "$case,$method,\"$guard\",$step,$contact,$result,$outcome" | tee -a "$data"
          done
        done
      done
    done
  done
  stability_plot
}

# The map from stability.csv.
stability_plot() {
  local data=$out/stability.csv
  # Rows: case, method and guard with the contact stiffness inside; columns: the step size.
  python3 - "$data" > "$tmp/map.dat" <<'EOF'
import csv, sys
colour = {'converged': '0x4caf50', 'not-converged': '0xffc107', 'blew-up': '0x9e9e9e', 'pull-through': '0xe53935'}
rows = list(csv.DictReader(open(sys.argv[1])))
keys = []
for r in rows:
    key = (r['case'], r['method'], r['guard'], r['contact_factor'])
    if key not in keys: keys.append(key)
steps = sorted({float(r['step_factor']) for r in rows})
for r in rows:
    y = keys.index((r['case'], r['method'], r['guard'], r['contact_factor']))
    x = steps.index(float(r['step_factor']))
    label = r['steps'] if r['outcome'] != 'pull-through' else r['pull_through_events'] + ' pt'
    print(x, y, colour[r['outcome']], '"%s"' % label)
print('# ytics', ', '.join('"%s: %s, guard %s, k_c x%s" %d' % (c, m, g, k, i) for i, (c, m, g, k) in enumerate(keys)))
print('# xtics', ', '.join('"%g" %d' % (s, i) for i, s in enumerate(steps)))
print('# rows', len(keys) - 0.5)
EOF
  local ytics xtics rows
  ytics=$(grep '^# ytics' "$tmp/map.dat" | cut -c9-)
  xtics=$(grep '^# xtics' "$tmp/map.dat" | cut -c9-)
  rows=$(grep '^# rows' "$tmp/map.dat" | cut -c8-)
  gnuplot <<EOF
$(png_head 1200,1300 12 "$out/stability.png")
set title "Stability map, 10 s per run. swatch: 400 stitches; rings: two linked rings\nwith 30 % of their length. Cells: steps taken, or pull-through events (pt)"
set xlabel 'time step x the default (Euler 0.002 s, FIRE 0.02 s)'
set ytics ($ytics)
set xtics ($xtics)
set xrange [-0.5:4.5]
set yrange [-0.5:$rows] reverse
set key at screen 0.5, 0.025 center center horizontal maxrows 1 samplen 2
set bmargin 6
set style fill solid 1.0 border lc rgb 'white'
plot '$tmp/map.dat' using 1:2:(0.5):(0.5):3 with boxxy lc rgb variable notitle, \
     '' using 1:2:4 with labels font ',11' notitle, \
     NaN with boxes lc rgb '0x4caf50' title 'converged', NaN with boxes lc rgb '0xffc107' title 'not converged in 10 s', \
     NaN with boxes lc rgb '0x9e9e9e' title 'blew up', NaN with boxes lc rgb '0xe53935' title 'pull-through'
EOF
}

periodic() {
  local data=$out/periodic-vs-tiled.csv
  build/bin/bench_periodic --tiles 5 patterns/*.knit | tee "$data"
  periodic_plot
}

periodic_plot() {
  local data=$out/periodic-vs-tiled.csv
  gnuplot <<EOF
$(png_head 1300,1000 12 "$out/periodic-vs-tiled.png")
set datafile separator ','
set multiplot layout 2,1 title "Every bundled knit: its periodic patch against the centre repeat of a relaxed 5 x 5 tiling (FIRE, 2 threads)"
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.8 border -1
set xtics rotate by -40 scale 0 font ',10'
set grid ytics
set logscale y
set ylabel 'seconds to converge'
set key top left
plot '$data' using 5:xtic(1) title 'periodic patch' lc rgb '0x1e88e5', '' using 8 title '5 x 5 tiling' lc rgb '0xfb8c00'
unset logscale y
set ylabel 'difference [yarn radii]'
set yrange [0:*]
plot '$data' using 10:xtic(1) title 'RMS' lc rgb '0x43a047', '' using 11 title 'largest' lc rgb '0x8e24aa'
unset multiplot
EOF
}

local_relaxation() {
  bench/local_runs.sh 1 0.2:1:1 0.5:1:1 1:1:1 | tee "$out/local-relaxation.csv"
  local_plot
}

local_plot() {
  local data=$out/local-relaxation.csv
  gnuplot <<EOF
$(png_head 1300,900 12 "$out/local-relaxation.png")
set datafile separator ','
set multiplot layout 2,1 title "The mitten (46,337 points): stitches repainted purl, the yarn relaxed locally from the last result, against in full (FIRE, 2 threads)"
set logscale x
set xlabel 'stitches repainted [%]'
set grid
set logscale y
set ylabel 'full time / local time'
set yrange [1:100]
plot '$data' every ::1 using 2:19 with linespoints lw 2 pt 7 lc rgb '0x1e88e5' title 'speed-up', 10 with lines dt 2 lc rgb '0x757575' title 'target at 1 %'
unset logscale y
set ylabel 'difference [yarn radii]'
set yrange [0:*]
plot '$data' every ::1 using 2:20 with linespoints lw 2 pt 7 lc rgb '0x43a047' title 'RMS outside the relaxed rings', \\
     '' every ::1 using 2:21 with linespoints lw 2 pt 5 lc rgb '0x8e24aa' title 'largest outside', \\
     '' every ::1 using 2:22 with linespoints lw 2 pt 9 lc rgb '0xfb8c00' title 'RMS over all points', \\
     0.1 with lines dt 2 lc rgb '0x757575' title 'target (RMS outside)'
unset multiplot
EOF
}

active_set() {
  mesh_relaxed mitten "$tmp/mitten-relaxed.skein"
  relax "$tmp/mitten-relaxed.skein" "$out/active-full.csv" --no-audit
  relax "$tmp/mitten-relaxed.skein" "$out/active-set.csv" --no-audit --active-set
  active_plot
}

active_plot() {
  local points=46337
  gnuplot <<EOF
$(png_head 1300,900 12 "$out/active-set.png")
set datafile separator ','
set multiplot layout 2,1 title "The mitten (46,337 points) relaxed from its emission, every point integrated or with the active set (FIRE, 2 threads)"
set grid
set xlabel 'wall time [s]'
set logscale y
set ylabel '|∇E| / |∇E_0|'
set yrange [0.005:10]
plot '$out/active-full.csv' every ::1 using 10:3 with lines lw 2 lc rgb '0x1e88e5' title 'every point', \
     '$out/active-set.csv' every ::1 using 10:3 with lines lw 2 lc rgb '0xfb8c00' title 'active set', \
     0.01 with lines dt 2 lc rgb '0x757575' title 'tolerance'
unset logscale y
set xlabel 'step'
set ylabel 'points integrated [%]'
set yrange [0:105]
plot '$out/active-set.csv' every ::1 using 1:(100.0 * \$11 / $points) with lines lw 2 lc rgb '0xfb8c00' title 'active set'
unset multiplot
EOF
}

sampling() {
  mesh_relaxed mitten "$tmp/mitten-relaxed.skein"
  relax "$tmp/mitten-relaxed.skein" "$out/sampling-leaf.csv" --no-audit
  relax "$tmp/mitten-relaxed.skein" "$out/sampling-adaptive.csv" --no-audit --contact-spacing 2.5
  sampling_plot
}

sampling_plot() {
  gnuplot <<EOF
$(png_head 1300,600 12 "$out/contact-sampling.png")
set datafile separator ','
set title "The mitten (46,337 points) relaxed from its emission with Leaf's contact samples and adaptive ones (2.5 r; FIRE)"
set grid
set xlabel 'step'
set logscale y
set ylabel '|∇E| / |∇E_0|'
set yrange [0.005:10]
plot '$out/sampling-leaf.csv' every ::1 using 1:3 with lines lw 2 lc rgb '0x1e88e5' title "Leaf's rule (139,163 samples)", \
     '$out/sampling-adaptive.csv' every ::1 using 1:3 with lines lw 2 lc rgb '0xfb8c00' title 'adaptive (101,513 samples)', \
     0.01 with lines dt 2 lc rgb '0x757575' title 'tolerance'
EOF
}

case $what in
  speed) speed ;;
  plots) speed_plots; stability_plot; periodic_plot; local_plot; active_plot; sampling_plot ;;
  stability) stability ;;
  periodic) periodic ;;
  local) local_relaxation ;;
  active) active_set ;;
  sampling) sampling ;;
  all) periodic; stability; speed; local_relaxation; active_set; sampling ;;
  *) echo "usage: bench/charts.sh [speed|stability|periodic|local|active|sampling|all|plots]" >&2; exit 2 ;;
esac
echo "wrote $out/"
