#!/usr/bin/env bash
# Adaptive contact samples against Leaf's counts (docs/BENCHMARKS.md, issue 10): a garment's emitted yarn relaxed to
# convergence with Leaf's rule (an odd count over L / 2r per segment) and with adaptive samples at SPACING r
# (`--contact-spacing`); the two compared (bench/yarn_distance.py: RMS and largest control-point distance). The adaptive
# run is audited (pull-through events); the timed runs are not. One CSV line per run.
# Usage: bench/sampling_runs.sh [RUNS=3] [MODEL=mitten] [SPACING=2.5]   (after scripts/build.sh; about 70 s per run on 2 cores)
source "$(dirname "$0")/common.sh"
runs=${1:-3}
model=${2:-mitten}
spacing=${3:-2.5}
mesh_relaxed "$model" "$tmp/relaxed.skein"
"$skein" -q relax-yarn "$tmp/relaxed.skein" -o "$tmp/audited.bcc" --report "$tmp/audited.json" --contact-spacing "$spacing"
events=$(field "$tmp/audited.json" "r['pull_through_events']")
echo "model,control_points,spacing_r,leaf_samples,adaptive_samples,leaf_steps,leaf_seconds,adaptive_steps,adaptive_seconds,speedup,\
leaf_ms_per_step,adaptive_ms_per_step,rms_r,largest_r,energy_leaf,energy_adaptive,pull_through_events"
for i in $(seq "$runs"); do
  OMP_NUM_THREADS=2 "$skein" -q relax-yarn "$tmp/relaxed.skein" -o "$tmp/leaf.bcc" --report "$tmp/leaf.json" --no-audit
  OMP_NUM_THREADS=2 "$skein" -q relax-yarn "$tmp/relaxed.skein" -o "$tmp/adaptive.bcc" --report "$tmp/adaptive.json" --no-audit --contact-spacing "$spacing"
  l=$tmp/leaf.json a=$tmp/adaptive.json
  echo "$model,$(field "$l" "r['control_points']"),$spacing,$(field "$l" "r['contact_samples']"),$(field "$a" "r['contact_samples']"),\
$(field "$l" "r['steps']"),$(field "$l" "round(r['wall_seconds'], 2)"),$(field "$a" "r['steps']"),$(field "$a" "round(r['wall_seconds'], 2)"),\
$(python3 -c "import json; print(round(json.load(open('$l'))['wall_seconds'] / json.load(open('$a'))['wall_seconds'], 2))"),\
$(field "$l" "round(1000 * r['wall_seconds'] / r['steps'], 1)"),$(field "$a" "round(1000 * r['wall_seconds'] / r['steps'], 1)"),\
$(bench/yarn_distance.py "$tmp/leaf.bcc" "$tmp/adaptive.bcc"),$(field "$l" "round(r['energy'], 1)"),$(field "$a" "round(r['energy'], 1)"),$events"
done
