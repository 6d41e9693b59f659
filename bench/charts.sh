#!/usr/bin/env bash
# The evidence charts of docs/evidence.md (issue 9), drawn with gnuplot from runs of build/bin/skein:
#   speed      residual against wall time per integrator, with and without mesh relaxation first, on the
#              mitten (glove class) and the sweater; every step audited, the auditor's count in the legend
#   stability  integrator x step size x contact stiffness on a swatch: converged, not converged in the
#              time cap, blew up, or pull-through found by the auditor (with the guard and without it)
#   periodic   every bundled knit's periodic patch against the centre of a relaxed 5 x 5 tiling: cost and RMS
# Usage: bench/charts.sh [speed|stability|periodic|all]   (env: MITTEN_SECONDS, SWEATER_SECONDS: the cap per
# speed run, 300 and 180)
# Writes docs/images/charts/*.png and the measured data beside them as CSV.
set -euo pipefail
cd "$(dirname "$0")/.."
what=${1:-all}
skein=build/bin/skein
out=docs/images/charts
mkdir -p "$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
command -v gnuplot > /dev/null || { echo "bench/charts.sh needs gnuplot (apt-get install gnuplot-nox)" >&2; exit 2; }

# One relax-yarn run; prints "stopped_by,steps,wall_seconds,residual,pull_through_events" from its report.
relax() {  # input log args...
  local input=$1 log=$2
  shift 2
  "$skein" -q relax-yarn "$input" -o "$tmp/out.bcc" --report "$tmp/r.json" --log "$log" "$@" || true
  python3 -c "
import json; r = json.load(open('$tmp/r.json'))
print(','.join(str(x) for x in [r['stopped_by'], r['steps'], round(r['wall_seconds'], 2), r['residual'], r['pull_through_events']]))"
}

speed() {
  for model in mitten sweater; do
    local cap=${MITTEN_SECONDS:-300}
    [[ $model == sweater ]] && cap=${SWEATER_SECONDS:-180}
    "$skein" -q stitch "models/$model.obj" --labels "models/$model.skein" -o "$tmp/$model-tessellated.skein"
    "$skein" -q relax-mesh "$tmp/$model-tessellated.skein" -o "$tmp/$model-mesh-relaxed.skein"
    local summary=$out/speed-$model.csv plot=""
    echo "method,start,stopped_by,steps,wall_seconds,residual,pull_through_events" > "$summary"
    for method in fire euler; do
      for start in tessellated mesh-relaxed; do
        local log=$out/speed-$model-$method-$start.csv
        local result
        result=$(relax "$tmp/$model-$start.skein" "$log" --method "$method" --max-seconds "$cap" --max-steps 1000000)
        echo "$method,$start,$result" >> "$summary"
        local events=${result##*,}
        plot+="'$log' using 10:3 with lines lw 2 title '$method from the $start mesh ($events pull-through)', "
      done
    done
    gnuplot <<EOF
set terminal pngcairo size 1200,700 font ',13'
set output '$out/speed-$model.png'
set datafile separator ','
set key outside below
set logscale y
set format y '10^{%L}'
set xlabel 'wall time [s] (2 threads, every step audited)'
set ylabel 'residual |∇E| / |∇E_0|'
set title "$model: yarn relaxation, residual against time (cap ${cap} s)"
set grid
plot ${plot%, }
EOF
  done
}

stability() {
  "$skein" -q stitch models/swatch.obj --auto-label --stitch-size 10 --stitch-height 8 -o "$tmp/swatch.skein"
  local data=$out/stability.csv
  echo "method,guard,step_factor,contact_factor,stopped_by,steps,wall_seconds,residual,pull_through_events,outcome" > "$data"
  for method in fire euler; do
    local base=0.02
    [[ $method == euler ]] && base=0.002
    for guard in on off; do
      local flag=""
      [[ $guard == off ]] && flag=--no-guard
      for step in 0.5 1 2 4 8; do
        for contact in 0.25 1 4; do
          local h k result outcome
          h=$(python3 -c "print($base * $step)")
          k=$(python3 -c "print(50 * $contact)")
          result=$(relax "$tmp/swatch.skein" "$tmp/log.csv" --method "$method" $flag --time-step "$h" --k-contact "$k" --max-seconds 20 --max-steps 1000000)
          IFS=, read -r stopped _ _ _ events <<< "$result"
          if [[ $events != 0 ]]; then outcome=pull-through
          elif [[ $stopped == diverged ]]; then outcome=blew-up
          elif [[ $stopped == converged ]]; then outcome=converged
          else outcome=not-converged; fi
          echo "$method,$guard,$step,$contact,$result,$outcome" | tee -a "$data"
        done
      done
    done
  done
  # Rows: method and guard with the contact stiffness inside; columns: the step size.
  python3 - "$data" > "$tmp/map.dat" <<'EOF'
import csv, sys
colour = {'converged': '0x4caf50', 'not-converged': '0xffc107', 'blew-up': '0x9e9e9e', 'pull-through': '0xe53935'}
rows = list(csv.DictReader(open(sys.argv[1])))
keys = []
for r in rows:
    key = (r['method'], r['guard'], r['contact_factor'])
    if key not in keys: keys.append(key)
steps = sorted({float(r['step_factor']) for r in rows})
for r in rows:
    y = keys.index((r['method'], r['guard'], r['contact_factor']))
    x = steps.index(float(r['step_factor']))
    label = r['steps'] if r['outcome'] != 'pull-through' else r['pull_through_events'] + ' pt'
    print(x, y, colour[r['outcome']], '"%s"' % label)
print('# ytics', ', '.join('"%s, guard %s, k_c x%s" %d' % (m, g, c, i) for i, (m, g, c) in enumerate(keys)))
print('# xtics', ', '.join('"%g" %d' % (s, i) for i, s in enumerate(steps)))
EOF
  local ytics xtics
  ytics=$(grep '^# ytics' "$tmp/map.dat" | cut -c9-)
  xtics=$(grep '^# xtics' "$tmp/map.dat" | cut -c9-)
  gnuplot <<EOF
set terminal pngcairo size 1100,1000 font ',12'
set output '$out/stability.png'
set title "Stability map: swatch yarn (20 s cap); cell text: steps taken, or pull-through events (pt)"
set xlabel 'time step x the default (Euler 0.002 s, FIRE 0.02 s)'
set ytics ($ytics)
set xtics ($xtics)
set xrange [-0.5:4.5]
set yrange [-0.5:11.5] reverse
set key outside bottom center horizontal
set style fill solid 1.0 border lc rgb 'white'
plot '$tmp/map.dat' using 1:2:(0.5):(0.5):3 with boxxy lc rgb variable notitle, \
     '' using 1:2:4 with labels font ',11' notitle, \
     NaN with boxes lc rgb '0x4caf50' title 'converged', NaN with boxes lc rgb '0xffc107' title 'not converged in 20 s', \
     NaN with boxes lc rgb '0x9e9e9e' title 'blew up', NaN with boxes lc rgb '0xe53935' title 'pull-through'
EOF
}

periodic() {
  local data=$out/periodic-vs-tiled.csv
  build/bin/bench_periodic --tiles 5 patterns/*.knit | tee "$data"
  gnuplot <<EOF
set terminal pngcairo size 1300,1000 font ',12'
set output '$out/periodic-vs-tiled.png'
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

case $what in
  speed) speed ;;
  stability) stability ;;
  periodic) periodic ;;
  all) periodic; stability; speed ;;
  *) echo "usage: bench/charts.sh [speed|stability|periodic|all]" >&2; exit 2 ;;
esac
echo "wrote $out/"
