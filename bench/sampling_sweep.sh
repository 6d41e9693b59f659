#!/usr/bin/env bash
# How deep a relaxation gets with each contact sampling (docs/BENCHMARKS.md, issue 10): the mitten's emitted yarn relaxed
# to Leaf's stop rule with Leaf's counts and with adaptive samples at each SPACING, every result compared with one deep
# reference (Leaf's counts, relaxed 600 steps at a tolerance of 0.002). Positions, not energies, since each sampling
# is its own quadrature of the contact energy. One CSV line per sampling (0: Leaf's rule).
# Usage: bench/sampling_sweep.sh [MODEL=mitten] [SPACING ...=1.0 1.5 2.0 2.5 2.8]   (after scripts/build.sh; about 15 min on one thread)
source "$(dirname "$0")/common.sh"
model=${1:-mitten}
shift || true
spacings=("$@")
[ ${#spacings[@]} -gt 0 ] || spacings=(1.0 1.5 2.0 2.5 2.8)
mesh_relaxed "$model" "$tmp/relaxed.skein"
export OMP_NUM_THREADS=1
"$skein" -q relax-yarn "$tmp/relaxed.skein" -o "$tmp/reference.bcc" --report "$tmp/reference.json" --no-audit --tolerance 0.002 --max-steps 600
echo "model,spacing_r,contact_samples,steps,seconds,energy,rms_from_reference_r,largest_from_reference_r,reference_steps,reference_energy"
for s in 0 "${spacings[@]}"; do
  "$skein" -q relax-yarn "$tmp/relaxed.skein" -o "$tmp/run.bcc" --report "$tmp/run.json" --no-audit --contact-spacing "$s"
  r=$tmp/run.json
  echo "$model,$s,$(field "$r" "r['contact_samples']"),$(field "$r" "r['steps']"),$(field "$r" "round(r['wall_seconds'], 1)"),\
$(field "$r" "round(r['energy'])"),$(bench/yarn_distance.py "$tmp/run.bcc" "$tmp/reference.bcc"),\
$(field "$tmp/reference.json" "r['steps']"),$(field "$tmp/reference.json" "round(r['energy'])")"
done
