#!/usr/bin/env bash
# Whole yarn-relaxation runs for docs/BENCHMARKS.md: steps and wall time to convergence per integrator, the
# guard's cost (on vs off), 1 vs 2 threads; one CSV line per run. Usage: bench/relax_yarn_runs.sh [RUNS]
source "$(dirname "$0")/common.sh"
runs=${1:-3}
for model in swatch mitten sweater; do
  "$skein" -q stitch "models/$model.obj" --labels "models/$model.skein" -o "$tmp/$model.skein"
done
echo "case,threads,converged,stopped_by,steps,wall_seconds,us_per_point_step,residual,control_points,finest_hits,held_points"
run() {  # name threads args...
  local name=$1 threads=$2
  shift 2
  OMP_NUM_THREADS=$threads "$skein" -q relax-yarn "$@" -o "$tmp/out.bcc" --report "$tmp/r.json" --no-audit
  python3 -c "
import json; r = json.load(open('$tmp/r.json'))
print(','.join(str(x) for x in ['$name', $threads, r['converged'], r['stopped_by'], r['steps'], round(r['wall_seconds'], 3),
      round(r['us_per_point_step'], 3), round(r['residual'], 5), r['control_points'], r['guard_events']['finest_hits'], r['guard_events']['held_points']]))"
}
for i in $(seq "$runs"); do
  run swatch-fire 2 "$tmp/swatch.skein"
  run swatch-fire-no-guard 2 "$tmp/swatch.skein" --no-guard
  run swatch-fire-no-safe-bounds 2 "$tmp/swatch.skein" --no-safe-bounds
  run swatch-fire 1 "$tmp/swatch.skein"
  run swatch-euler 2 "$tmp/swatch.skein" --method euler
done
run mitten-fire-300s 2 "$tmp/mitten.skein" --max-seconds 300
run sweater-fire-10-steps 2 "$tmp/sweater.skein" --max-steps 10
