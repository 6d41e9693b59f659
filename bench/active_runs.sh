#!/usr/bin/env bash
# The active set against a full relaxation (docs/BENCHMARKS.md, issue 10): the mitten's emitted yarn relaxed to
# convergence with every point integrated on every step, and with the active set (`--active-set`); then the two
# results compared (bench/yarn_distance.py: RMS and largest control-point distance) and the active-set run repeated with
# the per-step audit for its pull-through count. One CSV line per run.
# Usage: bench/active_runs.sh [RUNS=3] [MODEL=mitten]   (after scripts/build.sh; about 70 s per run on 2 cores)
source "$(dirname "$0")/common.sh"
runs=${1:-3}
model=${2:-mitten}
mesh_relaxed "$model" "$tmp/relaxed.skein"
echo "model,control_points,full_steps,full_seconds,active_steps,active_seconds,speedup,integrated_share,sleeps,wakes_by_force,wakes_by_move,rms_r,largest_r,energy_full,energy_active,pull_through_events"
for i in $(seq "$runs"); do
  OMP_NUM_THREADS=2 "$skein" -q relax-yarn "$tmp/relaxed.skein" -o "$tmp/full.bcc" --report "$tmp/full.json" --no-audit
  OMP_NUM_THREADS=2 "$skein" -q relax-yarn "$tmp/relaxed.skein" -o "$tmp/active.bcc" --report "$tmp/active.json" --no-audit --active-set
  if [ "$i" = 1 ]; then
    "$skein" -q relax-yarn "$tmp/relaxed.skein" -o "$tmp/audited.bcc" --report "$tmp/audited.json" --active-set
    events=$(field "$tmp/audited.json" "r['pull_through_events']")
  fi
  IFS=, read -r rms largest <<<"$(bench/yarn_distance.py "$tmp/full.bcc" "$tmp/active.bcc")"
  echo "$model,$(field "$tmp/full.json" "r['control_points']"),$(field "$tmp/full.json" "r['steps']"),$(field "$tmp/full.json" "round(r['wall_seconds'], 2)"),\
$(field "$tmp/active.json" "r['steps']"),$(field "$tmp/active.json" "round(r['wall_seconds'], 2)"),\
$(python3 -c "import json; print(round(json.load(open('$tmp/full.json'))['wall_seconds'] / json.load(open('$tmp/active.json'))['wall_seconds'], 2))"),\
$(field "$tmp/active.json" "round(r['active_set']['integrated_share'], 3)"),$(field "$tmp/active.json" "r['active_set']['sleeps']"),\
$(field "$tmp/active.json" "r['active_set']['wakes_by_force']"),$(field "$tmp/active.json" "r['active_set']['wakes_by_move']"),\
$rms,$largest,$(field "$tmp/full.json" "round(r['energy'], 1)"),$(field "$tmp/active.json" "round(r['energy'], 1)"),$events"
done
