# Sourced by the bench scripts: strict mode, the repository root as the working folder, the skein binary, and
# a scratch folder ($tmp) removed on exit.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[1]}")/.."
skein=build/bin/skein
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# mesh_relaxed MODEL OUT: a bundled model tessellated with its shipped labels ($tmp/MODEL-tessellated.skein) and its
# stitch mesh relaxed on the limit surface into OUT.
mesh_relaxed() {
  "$skein" -q stitch "models/$1.obj" --labels "models/$1.skein" -o "$tmp/$1-tessellated.skein"
  "$skein" -q relax-mesh "$tmp/$1-tessellated.skein" -o "$2"
}
# field JSON EXPR: EXPR evaluated with r = the JSON file's contents.
field() { python3 -c "import json, sys; r = json.load(open(sys.argv[1])); print(eval(sys.argv[2]))" "$@"; }
