#!/usr/bin/env bash
# Remakes the user guide's pictures (docs/images/gui/): the GUI tour of a beanie, from mesh to relaxed yarn, with
# time for the yarn to converge, and the yarn settings dialog. Needs a build with the GUI (scripts/build.sh) and xvfb-run.
set -euo pipefail
cd "$(dirname "$0")/.."
out=docs/images/gui
shots=$(mktemp -d)
trap 'rm -rf "$shots"' EXIT
SKEIN_GUI_SHOTS="$shots" SKEIN_GUI_TOUR_SECONDS=${SKEIN_GUI_TOUR_SECONDS:-1500} QTEST_FUNCTION_TIMEOUT=1800000 \
  xvfb-run -a -s "-screen 0 1600x1200x24" build/bin/test_gui tour_of_a_beanie yarn_settings_reach_the_relaxation
mkdir -p "$out"
rm -f "$out"/gui-*.png
cp "$shots"/gui-*.png "$out"/
ls -l "$out"
