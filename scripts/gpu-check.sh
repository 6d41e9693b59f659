#!/usr/bin/env bash
# The CUDA checks for a lent GPU machine, in two halves (the GPU machine has nvcc and CMake but not skein's
# Debian libraries, and cannot fetch them):
#
#   scripts/gpu-check.sh bundle   here: builds with CUDA for sm_90 into build-gpu/ and packs the binaries and
#                                 the shared libraries the GPU machine lacks into build-gpu/bundle/ (~25 MB)
#   scripts/gpu-check.sh          there (device tool, carry build-gpu/bundle and out/sweater/relaxed.skein):
#                                 the cuda-labelled tests, compute-sanitizer memcheck and racecheck on the
#                                 parity tests, the GPU benchmarks and a per-kernel profile, then a short table.
#
# Outputs go to $OUT (the device tool brings them back) or out/gpu-check/. The benchmark figures belong in
# docs/BENCHMARKS.md with the device named.
set -euo pipefail
cd "$(dirname "$0")/.."
bundle=build-gpu/bundle

if [[ "${1:-}" == bundle ]]; then
  scripts/install-deps.sh
  cmake --preset gpu-check >/dev/null
  cmake --build build-gpu --target skein test_cuda
  rm -rf "$bundle" && mkdir -p "$bundle/bin" "$bundle/lib"
  cp build-gpu/bin/skein build-gpu/bin/test_cuda "$bundle/bin/"
  # Everything the binaries load except the C and C++ runtimes, which the GPU machine has in newer versions.
  ldd "$bundle"/bin/* | awk '$3 ~ /^\// {print $3}' | sort -u | grep -Ev '/(libc|libm|libstdc\+\+|libgcc_s|ld-linux[^/]*)\.so' |
    xargs -I{} cp -L {} "$bundle/lib/"
  du -sh "$bundle"
  exit 0
fi

[[ -x "$bundle/bin/test_cuda" ]] || { echo "no $bundle: run 'scripts/gpu-check.sh bundle' first and carry $bundle" >&2; exit 2; }
out="${OUT:-out/gpu-check}"
mkdir -p "$out"
export LD_LIBRARY_PATH="$PWD/$bundle/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export SKEIN_STITCHES="$PWD/stitches"
skein="$bundle/bin/skein"
table="$out/table.txt"
: >"$table"
row() { printf '%-44s %s\n' "$1" "$2" | tee -a "$table"; }

nvidia-smi --query-gpu=name,memory.total,driver_version,clocks.max.sm --format=csv | tee "$out/gpu.txt"
"$skein" devices | tee -a "$out/gpu.txt"

# 1. The cuda-labelled tests.
set +e
"$bundle/bin/test_cuda" --gtest_output="json:$out/test_cuda.json" >"$out/test_cuda.log" 2>&1
tests_rc=$?
set -e
row "test_cuda" "$(grep -E '^\[  (PASSED|FAILED|SKIPPED) ' "$out/test_cuda.log" | tr '\n' ' ') (rc $tests_rc)"

# 2. compute-sanitizer on the parity tests (small models: the sanitizers slow kernels 10-100x).
filter='CudaYarnRelaxer.ContactPairs*:CudaYarnRelaxer.FireSteps*:CudaYarnRelaxer.EulerSteps*'
for tool in memcheck racecheck; do
  set +e
  compute-sanitizer --tool "$tool" --error-exitcode 3 "$bundle/bin/test_cuda" --gtest_filter="$filter" >"$out/sanitizer-$tool.log" 2>&1
  rc=$?
  set -e
  row "compute-sanitizer $tool" "$(grep -m1 -E 'ERROR SUMMARY|RACECHECK SUMMARY' "$out/sanitizer-$tool.log" || echo 'no summary') (rc $rc)"
done

# 3. The device's copy rate: the ceiling for a memory-bound step (bytes read + written).
python3 - <<'EOF' | tee -a "$table" || true
import torch
x = torch.empty(2 ** 30, dtype=torch.uint8, device="cuda"); y = torch.empty_like(x)
for _ in range(3): y.copy_(x)
s, e = torch.cuda.Event(enable_timing=True), torch.cuda.Event(enable_timing=True)
times = []
for _ in range(20):
    s.record(); y.copy_(x); e.record(); torch.cuda.synchronize(); times.append(s.elapsed_time(e))
times.sort()
print(f"{'device-to-device copy (read + write)':44s} {2 * x.numel() / (times[10] * 1e-3) / 1e12:.2f} TB/s")
EOF

# 4. Whole runs: ms per step at ~250k control points (the sweater at 10 mm stitches), and the main job's
# sweater (mesh-relaxed, rib borders: out/sweater/relaxed.skein from scripts/main-job.sh) to convergence.
report() { python3 -c "import json,sys; r=json.load(open(sys.argv[1])); print(f\"{r['control_points']} points, {r['steps']} steps, {r['wall_seconds']:.1f} s, {1e3*r['wall_seconds']/max(r['steps'],1):.2f} ms/step, {r['stopped_by']}, residual {r['residual']:.3g}\")" "$1"; }
"$skein" -q stitch models/sweater.obj --labels models/sweater.skein --stitch-size 10 -o "$out/sweater10.skein"
"$skein" -q relax-yarn "$out/sweater10.skein" -o "$out/sweater10.bcc" --backend cuda --no-audit --max-steps 300 --tolerance 0 \
    --report "$out/sweater10.json"
row "sweater 10 mm, 300 steps" "$(report "$out/sweater10.json")"
if [[ -f out/sweater/relaxed.skein ]]; then
  "$skein" -q relax-yarn out/sweater/relaxed.skein -o "$out/sweater.bcc" --backend cuda --no-audit --max-seconds 420 \
      --report "$out/sweater.json" --log "$out/sweater-log.csv" --png "$out/sweater.png"
  row "sweater (main job) to convergence" "$(report "$out/sweater.json")"
else
  row "sweater (main job)" "skipped: carry out/sweater/relaxed.skein"
fi
"$skein" -q stitch models/mitten.obj --labels models/mitten.skein -o "$out/mitten.skein"
"$skein" -q relax-yarn "$out/mitten.skein" -o "$out/mitten.bcc" --backend cuda --report "$out/mitten.json"
row "mitten, audited, to convergence" "$(report "$out/mitten.json"), pull-through $(python3 -c "import json; print(json.load(open('$out/mitten.json'))['pull_through_events'])")"

# 5. Where the time goes: one profiled stretch of steps (kernel names and durations).
set +e
ncu --graph-profiling node --launch-skip 3000 --launch-count 120 --metrics gpu__time_duration.sum,dram__bytes.sum --csv \
    "$skein" -q relax-yarn "$out/sweater10.skein" -o "$out/profiled.bcc" --backend cuda --no-audit --max-steps 60 --tolerance 0 \
    >"$out/ncu.csv" 2>"$out/ncu.log"
set -e
python3 - "$out/ncu.csv" <<'EOF' | tee -a "$table" || true
import csv, sys, collections, re
rows = [r for r in csv.reader(open(sys.argv[1])) if len(r) > 10]
if not rows: sys.exit("ncu: no rows (see ncu.log)")
head = rows[0]; k = head.index("Kernel Name"); m = head.index("Metric Name"); v = head.index("Metric Value")
time, dram = collections.defaultdict(float), collections.defaultdict(float)
for r in rows[1:]:
    name = re.sub(r"\(.*", "", r[k]).split("::")[-1]
    value = float(r[v].replace(",", ""))
    if r[m] == "gpu__time_duration.sum": time[name] += value
    elif r[m] == "dram__bytes.sum": dram[name] += value
total = sum(time.values())
for name, t in sorted(time.items(), key=lambda x: -x[1])[:10]:
    print(f"{'  kernel ' + name:44s} {100 * t / total:5.1f}% of time, {dram[name] / max(t, 1):.0f} GB/s")
EOF
echo
echo "== gpu-check summary ($(head -2 "$out/gpu.txt" | tail -1)) =="
cat "$table"
exit $tests_rc
