#!/usr/bin/env bash
# Local re-relaxation against a full one (docs/BENCHMARKS.md, issue 10): the mitten's yarn relaxed in full,
# a share of its plain stitches repainted purl, then the edited yarn relaxed locally from the previous result
# and in full from its emission. One CSV line per run (bench/bench_local.cpp says what each column is).
# Usage: bench/local_runs.sh [RUNS=1] [PERCENT:RINGS:HALO[:ACTIVE] ...]   (ACTIVE=1: both edited runs with the active
# set; after scripts/build.sh; about 90 s per run on 2 cores; the default configurations are those of docs/BENCHMARKS.md)
source "$(dirname "$0")/common.sh"
runs=${1:-1}
shift || true
configs=("$@")
[ ${#configs[@]} -gt 0 ] || configs=(1:1:1 1:2:2 0.2:1:1 5:1:1 2:1:1)  # percent repainted, rings, halo
mesh_relaxed mitten "$tmp/mitten-relaxed.skein"
header=1
for i in $(seq "$runs"); do
  for config in "${configs[@]}"; do
    IFS=: read -r percent rings halo active <<<"$config"
    line=$(OMP_NUM_THREADS=2 build/bin/bench_local "$tmp/mitten-relaxed.skein" "$percent" "$rings" "$halo" "${active:-0}" 2>/dev/null | grep -v '^\[')  # not the log
    if [ "$header" = 1 ]; then echo "model,percent,$(head -1 <<<"$line")"; header=0; fi
    echo "mitten,$percent,$(tail -1 <<<"$line")"
  done
done
