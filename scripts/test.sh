#!/usr/bin/env bash
# Sets up and builds skein, then runs every test. Tests labelled `cuda` skip themselves when no GPU answers.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
ctest --test-dir build --output-on-failure -j"$(nproc)"
