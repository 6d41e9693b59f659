#!/usr/bin/env bash
# The main job on the bundled sweater: set-up and build, then load → label → tessellate into a stitch mesh,
# ribbing at the hem, cuffs and neck, mesh relaxation on the limit surface, yarn emitted from the stitch
# library, yarn-level relaxation for five minutes (a checkpoint lets it go on: see below), and the projects,
# the yarn, pictures and reports written under out/sweater/.
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
"$skein" relax-yarn "$out/sweater-relaxed.skein" -o "$out/yarn-relaxed.bcc" --max-seconds 300 --checkpoint "$out/yarn.ckp" \
    --checkpoint-minutes 1 --report "$out/yarn-relax-report.json" --log "$out/yarn-relax-log.csv" --png "$out/yarn-relaxed.png"
echo "wrote $out/sweater.skein (stitch mesh), $out/sweater-relaxed.skein (relaxed), $out/yarn.bcc (yarn),"
echo "      $out/yarn-relaxed.bcc (yarn after five minutes of relaxation; go on overnight with"
echo "      build/bin/skein relax-yarn $out/sweater-relaxed.skein -o $out/yarn-relaxed.bcc --resume $out/yarn.ckp --checkpoint $out/yarn.ckp),"
echo "      pictures $out/rows.png, stitch-types.png, stretch-before.png, stretch-after.png, yarn.png, yarn-relaxed.png,"
echo "      reports $out/report.json, relax-report.json, yarn-report.json, yarn-relax-report.json, yarn-relax-log.csv and $out/stretch.ply"
