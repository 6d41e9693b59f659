#!/usr/bin/env bash
# The main job on the bundled sweater: set-up and build, then load → label → tessellate into a stitch mesh,
# ribbing at the hem, cuffs and neck, mesh relaxation on the limit surface, yarn emitted from the stitch
# library, and the projects, the yarn, pictures and reports written under out/sweater/. (Yarn-level
# relaxation arrives with a later issue.)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
out=out/sweater
mkdir -p "$out"
skein=build/bin/skein
"$skein" stitch models/sweater.obj --labels models/sweater.skein -o "$out/sweater.skein" --png "$out/rows.png"
"$skein" edit "$out/sweater.skein" --fill rib2x2 --near-border 12 -o "$out/sweater.skein" --png-types "$out/stitch-types.png"
"$skein" stats "$out/sweater.skein" --json -o "$out/report.json"
"$skein" relax-mesh "$out/sweater.skein" -o "$out/sweater-relaxed.skein" --png-before "$out/stretch-before.png" \
    --png "$out/stretch-after.png" --ply "$out/stretch.ply" --report "$out/relax-report.json"
"$skein" yarn "$out/sweater-relaxed.skein" -o "$out/yarn.bcc" --png "$out/yarn.png"
"$skein" stats "$out/yarn.bcc" --json -o "$out/yarn-report.json"
echo "wrote $out/sweater.skein (stitch mesh), $out/sweater-relaxed.skein (relaxed), $out/yarn.bcc (yarn),"
echo "      pictures $out/rows.png, stitch-types.png, stretch-before.png, stretch-after.png, yarn.png,"
echo "      reports $out/report.json, relax-report.json, yarn-report.json and $out/stretch.ply"
