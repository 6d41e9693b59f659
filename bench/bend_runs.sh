#!/usr/bin/env bash
# Does the model's knitted fabric have a curling moment and a bending stiffness? (issue 24; docs/BENCHMARKS.md
# "Bent and let go"). Each swatch is emitted (`skein pattern --tile`) and relaxed flat with free borders
# (`skein relax-yarn`, L-BFGS, the force stop rule), then bent onto a cylinder of radius R (bench/bend_swatch.py)
# along the courses (as when the side edges curl) and along the wales (as when the top and bottom curl), with the
# knit side concave (front) or convex (back), and each bent swatch relaxed again from there. Every run takes its
# rest lengths from the emitted yarn (× the take-up: `--rest-lengths`), so the five are one fabric in five
# shapes; a bent swatch relaxed with its own bent lengths would be given a rest shape that suits the bend. A
# fabric with a bending stiffness springs back (kept < 1); one with a curling moment ends lower in energy bent
# one way than flat. Real stockinette curls its side edges to the back (course, convex lower) and its top and
# bottom to the front (wale, concave lower); garter lies flat.
# Usage: bench/bend_runs.sh [R]   (R = 20 mm by default; prints a markdown table; about 30 minutes on 2 cores)
#        DEPTH=F bench/bend_runs.sh [R]   only the default stockinette, its knit stitch model's depths (h) times F
source "$(dirname "$0")/common.sh"
radius=${1:-20}
relax=(--method lbfgs --stop-rule force --no-audit --max-steps 12000)
entries=("stockinette:12x16:" "stockinette:12x16:--take-up 0.9" "stockinette:12x16:--yarn-radius 0.9 --take-up 0.935" "garter:12x8:")
if [ -n "${DEPTH:-}" ]; then
  cp -r stitches "$tmp/stitches"
  python3 - "$tmp/stitches/k.stitch" "$DEPTH" <<'PY'
import sys
path, factor = sys.argv[1], float(sys.argv[2])
def scaled(line):
    """A point line "  u v h" with h times the factor; any other line as it is."""
    fields = line.split()
    try:
        u, v, h = (float(f) for f in fields)
    except ValueError:  # not three numbers
        return line
    return f"  {u:g} {v:g} {h * factor:g}\n"
lines = [scaled(line) for line in open(path)]
open(path, "w").write("".join(lines))
PY
  entries=("stockinette:12x16:--stitches $tmp/stitches")
fi
echo "| swatch | bent along | knit side | energy against flat | curvature bent [1/mm] | relaxed [1/mm] | kept | steps |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- |"
for entry in "${entries[@]}"; do
  IFS=: read -r p tile options <<<"$entry"
  name="$p${options:+ (${options})}"
  [ -n "${DEPTH:-}" ] && name="$p (knit depths x $DEPTH)"
  # Emission options (the radius, the stitch models) to pattern, the take-up to every relaxation.
  emit=() take_up=()
  # shellcheck disable=SC2086
  set -- $options
  while [ $# -gt 0 ]; do
    case $1 in --take-up) take_up=(--take-up "$2") ;; *) emit+=("$1" "$2") ;; esac
    shift 2
  done
  "$skein" -q pattern "patterns/$p.knit" --tile "$tile" "${emit[@]}" -o "$tmp/emitted.bcc"
  rest=(--rest-lengths "$tmp/emitted.bcc" "${take_up[@]}")
  # Relaxed flat, and relaxed again from there as each bent one is.
  "$skein" -q relax-yarn "$tmp/emitted.bcc" "${rest[@]}" "${relax[@]}" -o "$tmp/flat.bcc"
  "$skein" -q relax-yarn "$tmp/flat.bcc" "${rest[@]}" "${relax[@]}" -o "$tmp/flat-again.bcc" --report "$tmp/flat.json"
  flat_energy=$(field "$tmp/flat.json" "r['energy']")
  for axis in course wale; do
    for side in front back; do
      python3 bench/bend_swatch.py bend "$tmp/flat.bcc" "$tmp/bent.bcc" "$axis" "$radius" "$side"
      "$skein" -q relax-yarn "$tmp/bent.bcc" "${rest[@]}" "${relax[@]}" -o "$tmp/bent-relaxed.bcc" --report "$tmp/bent.json"
      before=$(python3 bench/bend_swatch.py curvature "$tmp/bent.bcc" "$axis")
      after=$(python3 bench/bend_swatch.py curvature "$tmp/bent-relaxed.bcc" "$axis")
      field "$tmp/bent.json" "'| $name | ${axis}s | ${side/front/concave} | %+.2f %% | %.4f | %.4f | %.2f | %d (%s) |' % \
        (100 * (r['energy'] / $flat_energy - 1), abs($before), abs($after), $after / $before, r['steps'], r['stopped_by'])" \
        | sed 's/| back |/| convex |/'
    done
  done
done
