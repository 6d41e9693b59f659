#!/usr/bin/env bash
# Sets up and builds skein, runs every test (tests labelled `cuda` skip themselves when no GPU answers), then
# fuzzes every reader for SKEIN_FUZZ_SECONDS each (default 30; 0 skips the fuzzing).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
ctest --test-dir build --output-on-failure -j"$(nproc)"
seconds=${SKEIN_FUZZ_SECONDS:-30}
if [ "$seconds" != 0 ]; then scripts/fuzz.sh "$seconds"; fi
