#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The test command: format check, warnings-as-errors build, then every test through CTest.
# Real-KITTI tests read ../shared/data/kitti (or $HIF_KITTI_DIR); they skip when it is
# missing unless HIF_REQUIRE_DATA=1, which makes them fail instead.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/check-format.sh
HIF_WARNINGS_AS_ERRORS=ON bash scripts/build.sh
start=$(date +%s)
ctest --test-dir "${HIF_BUILD_DIR:-build}" --output-on-failure -j 2
echo "[test] suite ran in $(( $(date +%s) - start )) s"
