# Sourced by the bench scripts: strict mode, the repository root as the working folder, the skein binary, and
# a scratch folder ($tmp) removed on exit.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[1]}")/.."
skein=build/bin/skein
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
