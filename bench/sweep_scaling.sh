#!/usr/bin/env bash
# Sweeps on MPI ranks (issue 31; docs/sweeps.md): bench/sweep-scaling.json (12 cases of equal work, each capped
# at 1,500 L-BFGS steps, one thread) run by `skein sweep` in one process and by `skein-mpi sweep` on 2 and 4
# ranks (4 oversubscribe a 2-core machine), REPEATS times each; prints the median wall time of each and its
# speed-up against one process, and checks that every run wrote the same relaxed yarn.
# Usage: bench/sweep_scaling.sh [REPEATS]   (default 3; about 6 minutes on 2 cores)
source "$(dirname "$0")/common.sh"
repeats=${1:-3}
mpirun_cmd=(mpirun --oversubscribe)
[ "$(id -u)" -eq 0 ] && mpirun_cmd+=(--allow-run-as-root)
median() { sort -g | awk '{ a[NR] = $1 } END { print (NR % 2 ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2) }'; }
declare -A seconds
for ranks in 1 2 4; do
  for ((i = 0; i < repeats; ++i)); do
    out="$tmp/r$ranks-$i"
    if [ "$ranks" = 1 ]; then "$skein" -q sweep bench/sweep-scaling.json -o "$out" || true
    else "${mpirun_cmd[@]}" -np "$ranks" build/bin/skein-mpi sweep bench/sweep-scaling.json -o "$out" 2>/dev/null || true; fi
    seconds[$ranks]+="$(field "$out/sweep.json" "r['wall_seconds']") "
    for bcc in "$out"/cases/*/relaxed.bcc; do
      cmp -s "$bcc" "$tmp/r1-0/cases/$(basename "$(dirname "$bcc")")/relaxed.bcc" || echo "warning: $bcc differs from one process's" >&2
    done
  done
done
one=$(echo "${seconds[1]}" | tr ' ' '\n' | grep . | median)
echo "| processes | runs [s] | median [s] | speed-up |"
echo "| --- | --- | --- | --- |"
for ranks in 1 2 4; do
  m=$(echo "${seconds[$ranks]}" | tr ' ' '\n' | grep . | median)
  printf "| %s | %s | %.1f | %s |\n" "$ranks" "$(echo ${seconds[$ranks]} | xargs printf '%.1f ')" "$m" "$(awk -v a="$one" -v b="$m" 'BEGIN { printf "%.2f", a / b }')"
done
