#!/usr/bin/env bash
# The check of the CUDA backend on a machine with an NVIDIA GPU, in one run of a few minutes (and
# of the Vulkan backend on the same GPU when the NVIDIA Vulkan driver is installed):
#   1. builds the release preset with every core (only the targets below; the Debian packages of
#      scripts/install-deps.sh must be installed, and nvcc in /usr/local/cuda or CMAKE_CUDA_COMPILER)
#   2. posekit devices: stops unless cuda is available (the CUDA 13 runtime needs an NVIDIA driver
#      of the R580 series or later; an older one is reported as cudaErrorInsufficientDriver);
#      records the GPU's fp64 peak
#   3. the conformance suite with POSEKIT_EXPECT_BACKENDS=cpu,cuda (and vulkan), and the CUDA
#      backend's own tests
#   4. posekit correct lion-reference -> lion-01 with --device cuda and --device cpu (and vulkan):
#      the results must agree within 1e-6 of the bounding-box diagonal (posekit_mesh_difference)
#   5. end-to-end times with cuda: lion-01 (best of 3 runs) and elephant-01 -> elephant-02
#   6. posekit_device_bench on cuda, cpu (and vulkan): RBF evaluation of 65,000 points x 2,700
#      centers as a fraction of the fp64 peak, and the Vulkan / CUDA ratios
# Usage: scripts/gpu-check.sh [RESULTS_DIR]   (default: $OUT when set, else build/gpu-check)
# Logs, meshes, reports, the benchmark's JSON and summary.txt go to RESULTS_DIR. The real poses are
# read from $POSEKIT_DATA_DIR, else ../shared/data beside the checkout. Exit status 0 when every
# check passed, 1 otherwise (the summary says which).
set -uo pipefail
cd "$(dirname "$0")/.." || exit 1
checkout=$(pwd)
results=${1:-${OUT:-build/gpu-check}}
mkdir -p "$results"
results=$(cd "$results" && pwd)
data=${POSEKIT_DATA_DIR:-$checkout/../shared/data}
summary=$results/summary.txt
: >"$summary"
started=$(date +%s)
failures=0

say() { printf '%s\n' "$*" | tee -a "$summary"; }
pass() { say "PASS  $*"; }
fail() {
  say "FAIL  $*"
  failures=$((failures + 1))
}
now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3f", b - a }'; }
# The number after "KEY": in a JSON file (first occurrence).
json_number() { grep -o "\"$2\": *[-0-9.eE+]*" "$1" | head -n 1 | sed 's/.*: *//'; }

say "posekit GPU check, $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, commit $(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
if command -v nvidia-smi >/dev/null; then
  nvidia-smi --query-gpu=name,driver_version,clocks.max.sm,memory.total --format=csv \
    >"$results/nvidia-smi.txt" 2>&1
  say "nvidia-smi: $(tail -n 1 "$results/nvidia-smi.txt")"
fi

# 1. Build.
bin=build/release
# ccache when the machine has it; otherwise an empty launcher, in case the build folder came from
# a machine that had it.
launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER= -DCMAKE_CUDA_COMPILER_LAUNCHER=)
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_CUDA_COMPILER_LAUNCHER=ccache)
fi
t0=$(now)
if ! cmake --preset release "${launcher[@]}" >"$results/configure.log" 2>&1; then
  fail "configure (see configure.log)"
  exit 1
fi
if ! grep -q "posekit: CUDA backend enabled" "$results/configure.log"; then
  fail "configure did not enable the CUDA backend: $(grep 'CUDA backend' "$results/configure.log")"
  exit 1
fi
if ! cmake --build --preset release -j "$(nproc)" --target posekit_cli posekit_conformance_tests \
    posekit_cuda_tests posekit_device_bench posekit_mesh_difference >"$results/build.log" 2>&1; then
  fail "build (see build.log)"
  tail -n 30 "$results/build.log"
  exit 1
fi
pass "build in $(elapsed "$t0" "$(now)") s"
posekit=$bin/tools/cli/posekit
difference=$bin/tools/compare/posekit_mesh_difference

# 2. Devices.
"$posekit" devices >"$results/devices.txt" 2>&1
tee -a "$summary" <"$results/devices.txt"
cuda_line=$(grep '^cuda ' "$results/devices.txt")
if ! grep -q '^cuda *available' "$results/devices.txt"; then
  fail "cuda is not available: $cuda_line"
  exit 1
fi
peak_gflops=$(sed -n 's/.*fp64 peak \([0-9]*\) GFLOP\/s.*/\1/p' <<<"$cuda_line")
with_vulkan=0
if grep -q '^vulkan *available.*NVIDIA' "$results/devices.txt"; then with_vulkan=1; fi
backends=cpu,cuda
disabled=opencl
if [ "$with_vulkan" = 1 ]; then backends=cpu,cuda,vulkan; else disabled=opencl,vulkan; fi
say "checking $backends (not: $disabled)"

# 3. Conformance and the backend's own tests.
t0=$(now)
if POSEKIT_EXPECT_BACKENDS=$backends POSEKIT_DISABLE_BACKENDS=$disabled timeout 300 \
    "$bin/tests/conformance/posekit_conformance_tests" --gtest_brief=1 \
    >"$results/conformance.log" 2>&1; then
  pass "conformance on $backends: $(grep -E '^\[  PASSED  \]' "$results/conformance.log"), $(elapsed "$t0" "$(now)") s"
else
  fail "conformance on $backends (see conformance.log): $(grep -cE '^\[  FAILED  \]' "$results/conformance.log") failed"
fi
if POSEKIT_EXPECT_BACKENDS=cuda timeout 300 "$bin/tests/unit/cuda/posekit_cuda_tests" \
    --gtest_brief=1 >"$results/cuda_tests.log" 2>&1; then
  pass "posekit_cuda_tests: $(grep -E '^\[  PASSED  \]' "$results/cuda_tests.log")"
else
  fail "posekit_cuda_tests (see cuda_tests.log)"
fi

# 4. and 5. Corrections. correct STEM DEVICE REFERENCE TARGET: writes STEM.obj, .json and .log and
# prints the process's wall time.
correct() {
  local stem=$1 device=$2 reference=$3 target=$4 t_start
  t_start=$(now)
  if ! timeout 300 "$posekit" correct "$reference" "$target" -o "$results/$stem.obj" \
      --device "$device" --report "$results/$stem.json" >"$results/$stem.log" 2>&1; then
    return 1
  fi
  elapsed "$t_start" "$(now)"
}
lion=$data/lion-poses
elephant=$data/elephant-poses
if [ ! -f "$lion/lion-01.obj" ]; then
  fail "no shared poses at $data (set POSEKIT_DATA_DIR)"
else
  devices=(cuda cpu)
  if [ "$with_vulkan" = 1 ]; then devices+=(vulkan); fi
  for device in "${devices[@]}"; do
    # cuda: the best of 3 runs, kept as lion-01-cuda.*; the comparison devices run once.
    runs=1
    [ "$device" = cuda ] && runs=3
    best=""
    failed=0
    for run in $(seq 1 "$runs"); do
      if ! wall=$(correct "lion-01-$device-run$run" "$device" "$lion/lion-reference.obj" \
          "$lion/lion-01.obj"); then
        failed=1
        break
      fi
      if [ -z "$best" ] || awk -v a="$wall" -v b="$best" 'BEGIN { exit !(a < b) }'; then
        best=$wall
        for extension in obj json log; do
          cp "$results/lion-01-$device-run$run.$extension" "$results/lion-01-$device.$extension"
        done
      fi
    done
    rm -f "$results/lion-01-$device-run"*.obj
    if [ "$failed" = 1 ]; then
      fail "posekit correct lion-01 --device $device (see lion-01-$device-run$run.log)"
      continue
    fi
    report=$results/lion-01-$device.json
    say "lion-01 on $device: $best s end to end (process, best of $runs), report total $(json_number "$report" total) s, fitting $(json_number "$report" fitting) s, integration $(json_number "$report" integration) s, $(json_number "$report" centers) centers, $(json_number "$report" new_in_result) new intersecting faces"
    eval "lion_seconds_$device=$best"
  done
  for device in "${devices[@]}"; do
    [ "$device" = cpu ] && continue
    if [ ! -f "$results/lion-01-$device.obj" ] || [ ! -f "$results/lion-01-cpu.obj" ]; then
      continue
    fi
    if line=$("$difference" "$results/lion-01-cpu.obj" "$results/lion-01-$device.obj" \
        --tolerance 1e-6 2>&1); then
      pass "lion-01 $device against cpu: $line"
    else
      fail "lion-01 $device against cpu: $line"
    fi
  done
  if [ -f "$elephant/elephant-02.obj" ]; then
    if wall=$(correct elephant-02-cuda cuda "$elephant/elephant-01.obj" \
        "$elephant/elephant-02.obj"); then
      report=$results/elephant-02-cuda.json
      say "elephant-02 (against elephant-01) on cuda: $wall s end to end (process), report total $(json_number "$report" total) s, fitting $(json_number "$report" fitting) s, $(json_number "$report" centers) centers, $(json_number "$report" new_in_result) new intersecting faces"
    else
      fail "posekit correct elephant-02 --device cuda (see elephant-02-cuda.log)"
    fi
  fi
fi

# 6. Device benchmark.
bench_json=$results/device_bench.json
bench_filter='BM_Backend(RbfEvaluation|RbfAssembly|Rk45Batch)/(cuda|cpu|vulkan)/'
t0=$(now)
if POSEKIT_DISABLE_BACKENDS=$disabled timeout 300 "$bin/tools/bench/posekit_device_bench" \
    --benchmark_filter="$bench_filter" --benchmark_repetitions=3 --benchmark_min_time=0.2 \
    --benchmark_out="$bench_json" --benchmark_out_format=json >"$results/device_bench.txt" 2>&1; then
  pass "device benchmark in $(elapsed "$t0" "$(now)") s (device_bench.txt, device_bench.json)"
else
  fail "device benchmark (see device_bench.txt)"
fi
# The best of the repetitions of one benchmark's counter.
best_counter() {
  awk -v want="$1" -v key="\"$2\":" '
    /"name":/ { name = $0; sub(/.*"name": *"/, "", name); sub(/".*/, "", name) }
    index($0, key) { v = $0; sub(/.*": */, "", v); sub(/,.*/, "", v);
                     if (name == want && v + 0 > best) best = v + 0 }
    END { if (best > 0) printf "%.6g", best }' "$bench_json"
}
if [ -f "$bench_json" ]; then
  evaluation=points:65000/centers:2700/real_time
  cuda_flops=$(best_counter "BM_BackendRbfEvaluation/cuda/$evaluation" "fp64_flop/s")
  cuda_rate=$(best_counter "BM_BackendRbfEvaluation/cuda/$evaluation" "evaluations/s")
  cpu_rate=$(best_counter "BM_BackendRbfEvaluation/cpu/$evaluation" "evaluations/s")
  if [ -n "$cuda_flops" ] && [ -n "$peak_gflops" ]; then
    say "RBF evaluation on cuda: $cuda_rate evaluations/s, $cuda_flops fp64 flop/s (49 per evaluation) = $(awk -v f="$cuda_flops" -v p="$peak_gflops" 'BEGIN { printf "%.1f", 100 * f / (p * 1e9) }') % of the fp64 peak $peak_gflops GFLOP/s; cpu: $cpu_rate evaluations/s"
  else
    fail "no RBF evaluation rate or fp64 peak for cuda (rate '$cuda_flops', peak '$peak_gflops')"
  fi
  for bench in "BM_BackendRbfEvaluation/DEVICE/points:65000/centers:128/real_time" \
      "BM_BackendRbfAssembly/DEVICE/points:65000/centers:128/real_time" \
      "BM_BackendRbfAssembly/DEVICE/points:65000/centers:2700/real_time" \
      "BM_BackendRk45Batch/DEVICE/particles:5000/centers:2700/real_time"; do
    line="${bench/DEVICE\//}: evaluations/s cuda $(best_counter "${bench/DEVICE/cuda}" "evaluations/s")"
    if [ "$with_vulkan" = 1 ]; then
      line="$line, vulkan $(best_counter "${bench/DEVICE/vulkan}" "evaluations/s")"
    fi
    say "$line, cpu $(best_counter "${bench/DEVICE/cpu}" "evaluations/s")"
  done
  if [ "$with_vulkan" = 1 ]; then
    vulkan_rate=$(best_counter "BM_BackendRbfEvaluation/vulkan/$evaluation" "evaluations/s")
    say "RBF evaluation vulkan / cuda: $(awk -v v="$vulkan_rate" -v c="$cuda_rate" 'BEGIN { if (c > 0) printf "%.2f", v / c }')"
    if [ -n "${lion_seconds_vulkan:-}" ] && [ -n "${lion_seconds_cuda:-}" ]; then
      say "lion-01 end to end vulkan / cuda: $(awk -v v="$lion_seconds_vulkan" -v c="$lion_seconds_cuda" 'BEGIN { printf "%.2f", v / c }')"
    fi
  fi
fi

say "total $(($(date +%s) - started)) s; $failures check(s) failed; results in $results"
[ "$failures" = 0 ]
