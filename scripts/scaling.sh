#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# How time per scan and memory grow with the length of the sequence: synthetic streets of 1, 2,
# 4 and 8 times 40 scans (hif-synthetic-kitti: the street, and so the map, grows with the
# length), each converted and cleaned offline, then one table from the summary.json files.
#
#   bash scripts/scaling.sh            # 40, 80, 160, 320 scans
#   bash scripts/scaling.sh 1 2 16     # other multiples of 40
#
# Outputs go to ${HIF_SCALING_DIR:-build/scaling}/<scans>/ and are replaced on every run.
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${HIF_BUILD_DIR:-build}/apps
for app in hif-synthetic-kitti kitti2rawlog hif-clean; do
  [ -x "$BIN/$app" ] || { echo "[scaling] $BIN/$app not built: run bash scripts/build.sh" >&2; exit 1; }
done
ROOT=${HIF_SCALING_DIR:-build/scaling}
FACTORS=("$@")
[ ${#FACTORS[@]} -eq 0 ] && FACTORS=(1 2 4 8)

# Value of a top-level number in summary.json (one key per line, as hif-clean writes it).
field() { sed -n "s/^  \"$2\": \([0-9.eE+-]*\),\{0,1\}$/\1/p" "$1"; }

rows=()
for f in "${FACTORS[@]}"; do
  n=$((40 * f))
  out=$ROOT/$n
  mkdir -p "$out"
  echo "[scaling] $n scans: generating, converting, cleaning" >&2
  "$BIN/hif-synthetic-kitti" -o "$out/seq" -n "$n" --overwrite > "$out/generate.log" 2>&1
  "$BIN/kitti2rawlog" -i "$out/seq" -o "$out/scans.rawlog" --overwrite > "$out/convert.log" 2>&1
  "$BIN/hif-clean" -i "$out/scans.rawlog" -o "$out/clean" --overwrite -q > "$out/clean.log"
  s=$out/clean/summary.json
  rows+=("$(printf '| %5d | %9d | %8d | %7.2f | %11.2f | %8.2f | %10.2f | %9.1f | %7.2f |' \
    "$n" "$(($(field "$s" points_in) / n))" "$(field "$s" pillars)" \
    "$(awk "BEGIN { print $(field "$s" map_bytes) / 1048576 }")" \
    "$(field "$s" insert_ms_median)" "$(field "$s" scan_ms_p90)" \
    "$(field "$s" classify_ms_median)" "$(field "$s" peak_rss_mb)" "$(field "$s" total_s)")")
done
echo "| scans | points/scan | pillars | map MiB | insert ms (median) | insert p90 | classify ms | peak RSS MiB | total s |"
echo "|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
printf '%s\n' "${rows[@]}"
