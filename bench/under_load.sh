#!/usr/bin/env bash
# Steady under load (issue 28, part 3): one relaxation alone, then two of the same at once, REPEATS times each,
# with skein's threads as they are now (waiting threads sleep; the thread count follows the free cores) and as
# they were before (libgomp's default spin of 300,000 rounds, as many threads as cores). One CSV line per run,
# then each mode's median slowdown: a run beside another / the median run alone.
# Usage: bench/under_load.sh [PATTERN] [REPEATS]   (default patterns/seed.knit, 3)
source "$(dirname "$0")/common.sh"
pattern=${1:-patterns/seed.knit}
repeats=${2:-3}
relax() { "$skein" -q pattern "$pattern" -o "$1.bcc" --relax --backend cpu --report "$1.json"; }
# now: skein's own choice. before: the spinning default, kept by an explicit spin count and thread count.
run_mode() {
  if [ "$1" = before ]; then GOMP_SPINCOUNT=300000 OMP_NUM_THREADS=$(nproc) relax "$2"; else relax "$2"; fi
}
seconds() { field "$1" "r['wall_seconds']"; }
{
echo "mode,case,repeat,wall_seconds,steps"
for mode in before now; do
  for i in $(seq "$repeats"); do
    run_mode "$mode" "$tmp/alone"
    echo "$mode,alone,$i,$(seconds "$tmp/alone.json"),$(field "$tmp/alone.json" "r['steps']")"
  done
  for i in $(seq "$repeats"); do
    run_mode "$mode" "$tmp/a" & first=$!
    run_mode "$mode" "$tmp/b"
    wait "$first"
    for x in a b; do echo "$mode,pair-$x,$i,$(seconds "$tmp/$x.json"),$(field "$tmp/$x.json" "r['steps']")"; done
  done
done
} | tee "$tmp/runs.csv"
python3 - "$tmp/runs.csv" <<'PY'
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
for mode in ("before", "now"):
    alone = statistics.median(float(r["wall_seconds"]) for r in rows if r["mode"] == mode and r["case"] == "alone")
    pair = [float(r["wall_seconds"]) for r in rows if r["mode"] == mode and r["case"] != "alone"]
    print(f"# {mode}: alone {alone:.2f} s (median); beside another {statistics.median(pair):.2f} s median, "
          f"{max(pair):.2f} s worst: slowdown {statistics.median(pair) / alone:.2f} median, {max(pair) / alone:.2f} worst")
PY
