#!/usr/bin/env bash
# The 3-D smocked fabric of every bundled pattern at the default subdivisions, and the zigzag at finer meshes
# (docs/BENCHMARKS.md "The 3-D fabric"). One run each (deterministic), nothing else running. Prints one table row
# per run: pattern, points, seconds, Newton steps (cut short), frames, RMS from places, stretch, closest (reach),
# final barrier stiffness, intersections.
# Usage: bench/smock_cloth_runs.sh [BUILD_DIR] [SUBDIVISIONS_OF_THE_ZIGZAG...]   (default: build, 4 6)
set -euo pipefail
build=${1:-build}
shift || true
fine=("${@:-4 6}")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
run() {  # name, pattern file, extra options
  local name=$1 file=$2
  shift 2
  if ! "$build/bin/skein" smock "$file" --cloth "$out/c.obj" --report "$out/r.json" "$@" > "$out/log" 2>&1; then
    echo "$name failed:" >&2
    cat "$out/log" >&2
    exit 1
  fi
  python3 - "$name" "$out/r.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[2]))["cloth"]
print(f"| {sys.argv[1]} | {c['points']:,} | {c['seconds']:.1f} s | {c['newton_iterations']:,} ({c['collision_limited_steps']:,}) | {c['frames']} | "
      f"{c['target_rms_mm']:.2f} mm | {100 * c['largest_stretch']:.0f} % | {c['smallest_distance_mm']:.2f} mm ({c['barrier_reach_mm']:.1f} mm) | "
      f"{c['barrier_stiffness']:g} | {c['intersections']} |")
PY
}
for f in patterns/smocking/*.smock; do
  name=$(basename "$f" .smock)
  if [ "$name" = spiral ]; then run "spiral (--pull along)" "$f" --pull along; else run "$name" "$f"; fi
done
for s in ${fine[@]}; do run "zigzag, --subdivisions $s" patterns/smocking/zigzag.smock --subdivisions "$s"; done
