#!/usr/bin/env bash
# The main job on the bundled sweater: set-up and build, then load → label → tessellate into a stitch mesh,
# ribbing at the hem, cuffs and neck, yarn emitted from the stitch library, and the project, the yarn,
# pictures and reports written under out/sweater/. (Relaxation of mesh and yarn arrives with later issues.)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
out=out/sweater
mkdir -p "$out"
skein=build/bin/skein
"$skein" stitch models/sweater.obj --labels models/sweater.skein -o "$out/sweater.skein" --png "$out/rows.png"
"$skein" edit "$out/sweater.skein" --fill rib2x2 --near-border 12 -o "$out/sweater.skein" --png-types "$out/stitch-types.png"
"$skein" stats "$out/sweater.skein" --json -o "$out/report.json"
"$skein" yarn "$out/sweater.skein" -o "$out/yarn.bcc" --png "$out/yarn.png"
"$skein" stats "$out/yarn.bcc" --json -o "$out/yarn-report.json"
echo "wrote $out/sweater.skein (stitch mesh), $out/yarn.bcc (yarn), $out/rows.png, $out/stitch-types.png, $out/yarn.png,"
echo "      $out/report.json, $out/yarn-report.json"
