#!/usr/bin/env bash
# The main job, jobs/sweater.json: set-up and build, then the bundled sweater loaded, labeled and tessellated
# into a stitch mesh, ribbing at the hem, cuffs and neck, mesh relaxation on the limit surface, yarn emitted
# from the stitch library and relaxed at yarn level for five minutes (its checkpoint lets it go on), with the
# projects, the yarn, pictures, a log and a report written under out/sweater/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
build/bin/skein run jobs/sweater.json
out=out/sweater
echo "wrote $out/stitch.skein (stitch mesh), $out/relaxed.skein (relaxed), $out/yarn.bcc (yarn),"
echo "      $out/yarn-relaxed.bcc (yarn after five minutes of relaxation; go on overnight with"
echo "      build/bin/skein run jobs/sweater.json --resume --yarn-seconds 0),"
echo "      pictures $out/stitch-types.png, stretch-before.png, stretch-after.png, yarn.png, yarn-relaxed.png,"
echo "      $out/report.json (stages, times, residual history, guard events, auditor), $out/job.log, $out/yarn-relax-log.csv"
