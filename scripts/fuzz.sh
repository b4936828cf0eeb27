#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Builds the libFuzzer targets of tests/fuzz with clang (+ AddressSanitizer and
# UndefinedBehaviorSanitizer) in the sanitizer build, ./build-sanitize (or
# $HIF_SANITIZE_BUILD_DIR; scripts/sanitize-config.sh: after scripts/sanitize.sh they are built
# already), then runs each for $HIF_FUZZ_SECONDS seconds (default 60) from the seed corpus in
# tests/fuzz/corpus. The corpus
# grown by a run is kept in the build folder (the seeds in the repository are not touched); a
# crash leaves its input in <build>/artifacts/ and fails the script.
#   bash scripts/fuzz.sh                 all targets, 60 s each
#   HIF_FUZZ_SECONDS=600 bash scripts/fuzz.sh fuzz_pcd
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_EACH=${HIF_FUZZ_SECONDS:-60}
TARGETS=("$@")
[ ${#TARGETS[@]} -eq 0 ] && TARGETS=(fuzz_kitti fuzz_pcd fuzz_rawlog fuzz_map)
source scripts/sanitize-config.sh
start=$(date +%s)
cmake --build "$BUILD_DIR" -j "$(nproc)" --target "${TARGETS[@]}"
echo "[fuzz] built in $(( $(date +%s) - start )) s"
mkdir -p "$BUILD_DIR/artifacts"
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# One target per core at a time: each fuzzer is one process on one core.
JOBS=${HIF_FUZZ_JOBS:-$(nproc)}
run_target() {
  local t=$1 corpus="$BUILD_DIR/corpus/$1"
  mkdir -p "$corpus"
  # Memory: a reader must refuse a size that its file cannot hold, not try to allocate it.
  "$BUILD_DIR/tests/fuzz/$t" "$corpus" "tests/fuzz/corpus/$t" \
    -max_total_time="$SECONDS_EACH" -rss_limit_mb=2048 -malloc_limit_mb=1024 -timeout=20 \
    -max_len=16384 -print_final_stats=1 -artifact_prefix="$BUILD_DIR/artifacts/$t-" \
    > "$BUILD_DIR/$t.log" 2>&1
}
# Reports target t (its run's exit code in $2): its executions, or its log and the input that
# failed it.
report() {
  local t=$1 rc=$2
  if [ "$rc" -ne 0 ]; then
    tail -60 "$BUILD_DIR/$t.log"
    echo "[fuzz] $t FAILED: input in $BUILD_DIR/artifacts/ (run $BUILD_DIR/tests/fuzz/$t <file>)"
    return 1
  fi
  local runs
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$BUILD_DIR/$t.log" | grep -o '[0-9]*$')
  echo "[fuzz] $t: $runs executions in ${SECONDS_EACH} s, no crash; corpus $(ls "$BUILD_DIR/corpus/$t" | wc -l) inputs"
}
failed=0
for ((i = 0; i < ${#TARGETS[@]}; i += JOBS)); do
  batch=("${TARGETS[@]:i:JOBS}")
  pids=()
  for t in "${batch[@]}"; do
    echo "[fuzz] $t: ${SECONDS_EACH} s from tests/fuzz/corpus/$t"
    run_target "$t" &
    pids+=($!)
  done
  for k in "${!batch[@]}"; do
    rc=0
    wait "${pids[$k]}" || rc=$?
    report "${batch[$k]}" "$rc" || failed=1
  done
  [ "$failed" -eq 0 ] || exit 1
done
