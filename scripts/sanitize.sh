#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The whole test suite under AddressSanitizer + UndefinedBehaviorSanitizer: every target (the
# library, the apps the tests run, the tests) is built with clang and -fsanitize=address,undefined
# into ./build-sanitize (or $HIF_SANITIZE_BUILD_DIR; scripts/sanitize-config.sh, shared with
# scripts/fuzz.sh), and any finding aborts the test that hit it.
# MRPT itself is not instrumented; its heap is still checked through ASan's malloc.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/sanitize-config.sh
start=$(date +%s)
cmake --build "$BUILD_DIR" -j "$(nproc)"
echo "[sanitize] built in $(( $(date +%s) - start )) s"
export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_stack_use_after_return=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/tests/sanitize/lsan.supp:print_suppressions=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
start=$(date +%s)
ctest --test-dir "$BUILD_DIR" --output-on-failure -j 2
echo "[sanitize] suite ran in $(( $(date +%s) - start )) s"
