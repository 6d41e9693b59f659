#!/usr/bin/env bash
# Periodic stand-ins against a full relaxation (docs/BENCHMARKS.md, issue 10): a garment's emitted yarn relaxed to
# convergence, and its stand-in preview (`skein relax-yarn --stand-in`); the two compared (bench/yarn_distance.py:
# RMS and largest control-point distance) and with the emission. One CSV line per run; with FULL=0 the full
# relaxation is skipped (the sweater's takes half an hour on 2 cores) and only the preview is measured. With FILL
# (a `skein edit --fill` pattern: rib2x2, seed, ...) the whole garment is knitted in it first; with a pattern file
# instead (patterns/cable-4.knit, ...) it is tiled over the garment (`skein pattern --onto`) and named to the stand-in.
# FULL_ARGS (environment) goes to the full relaxation, e.g. FULL_ARGS="--max-steps 300" for a garment whose relaxation
# jams short of Leaf's rule.
# Usage: bench/standin_runs.sh [RUNS=3] [MODEL=mitten] [FULL=1] [FILL]   (after scripts/build.sh)
source "$(dirname "$0")/common.sh"
runs=${1:-3}
model=${2:-mitten}
full=${3:-1}
fill=${4:-}
mesh_relaxed "$model" "$tmp/relaxed.skein"
standin_args=()
if [ -f "$fill" ]; then
  "$skein" -q pattern "$fill" --onto "$tmp/relaxed.skein" -o "$tmp/relaxed.skein"
  standin_args=(--stand-in-pattern "$fill")
  fill=$(basename "$fill")
elif [ -n "$fill" ]; then
  "$skein" -q edit "$tmp/relaxed.skein" --fill "$fill" -o "$tmp/relaxed.skein"
fi
"$skein" -q yarn "$tmp/relaxed.skein" -o "$tmp/emitted.bcc"
OMP_NUM_THREADS=2 "$skein" -q relax-yarn "$tmp/relaxed.skein" -o "$tmp/probe.bcc" --report "$tmp/emitted.json" --max-steps 0 --no-audit
distance() { bench/yarn_distance.py "$1" "$2"; }  # A B: "rms_r,largest_r"
echo "model,fill,control_points,full_seconds,full_steps,standin_seconds,speedup,placed_points,following_points,taken_back_points,patch_steps,\
rms_standin_full_r,largest_standin_full_r,rms_emitted_full_r,largest_emitted_full_r,energy_emitted,energy_standin,energy_full,pull_through_events"
for i in $(seq "$runs"); do
  OMP_NUM_THREADS=2 "$skein" -q relax-yarn "$tmp/relaxed.skein" --stand-in "${standin_args[@]}" -o "$tmp/standin.bcc" --report "$tmp/standin.json"
  s=$tmp/standin.json
  if [ "$full" = 1 ]; then
    OMP_NUM_THREADS=2 "$skein" -q relax-yarn "$tmp/relaxed.skein" -o "$tmp/full.bcc" --report "$tmp/full.json" --no-audit ${FULL_ARGS:-}
    f=$tmp/full.json
    cols="$(field "$f" "round(r['wall_seconds'], 2)"),$(field "$f" "r['steps']")"
    speedup=$(python3 -c "import json; print(round(json.load(open('$f'))['wall_seconds'] / json.load(open('$s'))['wall_seconds'], 1))")
    against="$(distance "$tmp/full.bcc" "$tmp/standin.bcc"),$(distance "$tmp/full.bcc" "$tmp/emitted.bcc")"
    energy_full=$(field "$f" "round(r['energy'], 1)")
  else
    cols=",";speedup="";against=",,,";energy_full=""
  fi
  echo "$model,${fill:-as modelled},$(field "$s" "r['control_points']"),$cols,$(field "$s" "round(r['wall_seconds'], 2)"),$speedup,\
$(field "$s" "r['stand_in']['placed_points']"),$(field "$s" "r['stand_in']['following_points']"),$(field "$s" "r['stand_in']['taken_back_points']"),\
$(field "$s" "'+'.join(str(t['patch_steps']) for t in r['stand_in']['repeats'])"),$against,$(field "$tmp/emitted.json" "round(r['energy'], 1)"),\
$(field "$s" "round(r['energy'], 1)"),$energy_full,$(field "$s" "r['pull_through_events']")"
done
