#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Builds (Release) and runs the benchmark suite on real KITTI scans (sequence 08 of
# ../shared/data/kitti, or $HIF_KITTI_DIR/sequences/08, or the folder in $HIF_BENCH_SEQUENCE),
# 5 repetitions of each, and prints the medians. Extra arguments go to the benchmark, e.g.
#   bash scripts/bench.sh --benchmark_filter=Insert
set -euo pipefail
cd "$(dirname "$0")/.."
HIF_BUILD_BENCH=ON bash scripts/build.sh > /dev/null
"${HIF_BUILD_DIR:-build}/bench/hif_bench" --benchmark_repetitions="${HIF_BENCH_REPETITIONS:-5}" \
  --benchmark_enable_random_interleaving=true \
  --benchmark_report_aggregates_only=true --benchmark_display_aggregates_only=true "$@" \
  | grep -vE "_(mean|stddev|cv) "
