#!/usr/bin/env bash
# Every bundled pattern's periodic patch relaxed to convergence (Leaf 2018 Table 3's columns), with the
# per-step audit off (AUDIT= turns it on), one CSV line each. Usage: bench/pattern_runs.sh [OMP threads]
source "$(dirname "$0")/common.sh"
threads=${1:-2}
audit=${AUDIT:---no-audit}  # AUDIT= (empty) audits every step
echo "pattern,format,real_points,control_points,steps,wall_seconds,ms_per_step,converged,pull_through_events"
for f in patterns/*.knit patterns/*.weave; do
  OMP_NUM_THREADS=$threads "$skein" -q pattern "$f" -o "$tmp/out.bcc" --relax --report "$tmp/r.json" --backend cpu $audit
  python3 -c "
import json; r = json.load(open('$tmp/r.json'))
print(','.join(str(x) for x in ['$(basename "$f")', '$f'.rsplit('.', 1)[1], r['periodic']['real_points'], r['control_points'], r['steps'],
      round(r['wall_seconds'], 3), round(1e3 * r['wall_seconds'] / max(r['steps'], 1), 3), r['converged'], r['pull_through_events']]))"
done
