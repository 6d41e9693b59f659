#!/bin/sh
# CTest's `blender` test: the swatch's yarn emitted by skein, imported into Blender by tools/blender/skein_bcc.py,
# checked and rendered (check_bcc_import.py). Skipped (exit 77) where Blender is not installed.
# Usage: run.sh SKEIN MODELS_DIR SCRATCH_DIR
set -eu
command -v blender >/dev/null 2>&1 || { echo "blender is not installed: skipped"; exit 77; }
skein=$1 models=$2 scratch=$3
mkdir -p "$scratch"
"$skein" -q stitch "$models/swatch.obj" --labels "$models/swatch.skein" -o "$scratch/swatch.skein"
"$skein" -q yarn "$scratch/swatch.skein" -o "$scratch/swatch.bcc"
out=$(blender -b --python-exit-code 1 --python "$(dirname "$0")/check_bcc_import.py" -- "$scratch/swatch.bcc" "$scratch/swatch.png" 2>&1) || { echo "$out"; exit 1; }
echo "$out" | grep -E "^(OK|FAIL)"
echo "$out" | grep -q "^OK"
