#!/usr/bin/env bash
# Installs the Debian packages skein needs, configures and builds it into build/ (Release).
# Safe to run again: it only installs what is missing and rebuilds what changed.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --preset ci ${SKEIN_CMAKE_ARGS:-} >/dev/null
cmake --build build
