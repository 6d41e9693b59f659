#!/usr/bin/env bash
# Periodic patches relaxed by `skein pattern FILE --relax` (the defaults: L-BFGS, the force rule, audited) with
# two skein binaries, to compare them in one run on one machine: the median wall time of RUNS runs each, the
# steps, and one repeat's energy. docs/BENCHMARKS.md, "One repeat's energy".
# Usage: bench/periodic_speed.sh OLD_SKEIN NEW_SKEIN [RUNS] [PATTERN...]
set -euo pipefail
cd "$(dirname "$0")/.."
old=$1 new=$2 runs=${3:-3}
shift $(($# < 3 ? $# : 3))
patterns=("$@")
[ ${#patterns[@]} -gt 0 ] || patterns=(patterns/stockinette.knit patterns/rib-2x2.knit patterns/cable-4.knit patterns/eyelet-lace.knit
  patterns/honeycomb.knit patterns/written/braid-ws-crossings.txt)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "pattern,binary,median_s,steps,stopped_by,repeat_energy,control_points"
for f in "${patterns[@]}"; do
  for which in old new; do
    bin=$old; [ $which = new ] && bin=$new
    times=()
    for ((k = 0; k < runs; k++)); do
      "$bin" -q pattern "$f" -o "$tmp/o.bcc" --relax --report "$tmp/r.json"
      times+=("$(python3 -c "import json; print(json.load(open('$tmp/r.json'))['wall_seconds'])")")
    done
    python3 - "$f" "$which" "$tmp/r.json" "${times[@]}" <<'PY'
import json, statistics, sys
f, which, report, *times = sys.argv[1:]
r = json.load(open(report))
period = r.get("fixed_period", r.get("free_period", {}))
print(f"{f},{which},{statistics.median(map(float, times)):.2f},{r['steps']},{r['stopped_by']},{period.get('repeat_energy', float('nan')):.4f},{r['control_points']}")
PY
  done
done
