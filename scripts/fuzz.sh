#!/usr/bin/env bash
# Fuzzes every reader: builds the libFuzzer harnesses (fuzz/) with clang, ASan and UBSan into build-fuzz/, then
# for each reader replays the regression inputs (fuzz/regressions/READER/: crashes found before, now fixed) and
# fuzzes for SECONDS (default 30) from the bundled files as seeds. A crash, a sanitizer report or an exception
# other than skein::Error fails the script; the input is left in build-fuzz/crashes/.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-30}
scripts/install-deps.sh
cmake --preset fuzz >/dev/null
readers=(pattern project job sweep bcc ids stitch_model checkpoint mesh smocking)
cmake --build build-fuzz --target "${readers[@]/#/fuzz_}"
declare -A seeds=([pattern]=patterns [project]="models fuzz/seeds/project" [job]=jobs [sweep]=jobs [bcc]=fuzz/seeds/bcc [ids]=fuzz/seeds/ids [stitch_model]=stitches [checkpoint]=fuzz/seeds/checkpoint [mesh]=fuzz/seeds/mesh [smocking]="patterns/smocking fuzz/seeds/smocking")
rm -rf build-fuzz/crashes
mkdir -p build-fuzz/crashes
for reader in "${readers[@]}"; do
  harness=build-fuzz/bin/fuzz_$reader
  if compgen -G "fuzz/regressions/$reader/*" >/dev/null; then
    if ! "$harness" fuzz/regressions/$reader/* >build-fuzz/crashes/replay.log 2>&1; then
      cat build-fuzz/crashes/replay.log >&2
      echo "a regression input of the $reader reader fails again" >&2
      exit 1
    fi
    echo "replayed $(ls fuzz/regressions/$reader | wc -l) regression inputs of the $reader reader"
  fi
  corpus=build-fuzz/corpus/$reader
  mkdir -p "$corpus"
  echo "fuzzing the $reader reader for ${seconds} s"
  "$harness" -max_total_time="$seconds" -max_len=65536 -timeout=10 -rss_limit_mb=4096 -print_final_stats=1 \
    -artifact_prefix="build-fuzz/crashes/$reader-" "$corpus" ${seeds[$reader]} 2>&1 | grep -E '^(stat::number_of_executed_units|stat::new_units_added|==|SUMMARY|INFO: Seed)' || true
  if compgen -G "build-fuzz/crashes/$reader-*" >/dev/null; then
    echo "the $reader reader crashed; inputs: $(ls build-fuzz/crashes/$reader-*)" >&2
    exit 1
  fi
done
echo "no reader crashed"
