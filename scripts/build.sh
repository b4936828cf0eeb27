#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Configures and builds hif (Release) into ./build (or $HIF_BUILD_DIR): library, apps, tests
# and the benchmark suite (HIF_BUILD_BENCH=OFF to leave it out). Warnings are errors, as in
# scripts/test.sh, so that switching between the two does not rebuild everything.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${HIF_BUILD_DIR:-build}
mkdir -p "$BUILD_DIR"
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=${CMAKE_BUILD_TYPE:-Release} \
  -DHIF_WARNINGS_AS_ERRORS=${HIF_WARNINGS_AS_ERRORS:-ON} -DHIF_BUILD_BENCH=${HIF_BUILD_BENCH:-ON} \
  > "$BUILD_DIR/configure.log" 2>&1 \
  || { cat "$BUILD_DIR/configure.log"; exit 1; }
cmake --build "$BUILD_DIR" -j "$(nproc)"
