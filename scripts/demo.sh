#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The whole pipeline on one sequence: convert (kitti2rawlog), clean (hif-clean, offline and
# online), evaluate (hif-eval), then print the scores and where the outputs are.
#
#   bash scripts/demo.sh                      # a synthetic KITTI-layout street (generated)
#   bash scripts/demo.sh <sequence folder>    # a real KITTI sequence, e.g. .../sequences/04
#
# Outputs go to ${HIF_DEMO_DIR:-build/demo}/<name>/ and are replaced on every run.
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${HIF_BUILD_DIR:-build}/apps
for app in hif-synthetic-kitti kitti2rawlog hif-clean hif-eval; do
  [ -x "$BIN/$app" ] || { echo "[demo] $BIN/$app not built: run bash scripts/build.sh" >&2; exit 1; }
done
ROOT=${HIF_DEMO_DIR:-build/demo}
if [ $# -ge 1 ]; then
  SEQ=$1
  [ -d "$SEQ" ] || { echo "[demo] sequence folder '$SEQ' does not exist" >&2; exit 1; }
  NAME=kitti-$(basename "$SEQ")
  OUT=$ROOT/$NAME
  mkdir -p "$OUT"
else
  NAME=synthetic
  OUT=$ROOT/$NAME
  SEQ=$OUT/sequence
  mkdir -p "$OUT"
  "$BIN/hif-synthetic-kitti" -o "$SEQ" --scans 30 --overwrite
fi
"$BIN/kitti2rawlog" -i "$SEQ" -o "$OUT/scans.rawlog" --overwrite
for mode in offline online; do
  flag=""; [ $mode = online ] && flag=--online
  "$BIN/hif-clean" -i "$OUT/scans.rawlog" -o "$OUT/$mode" $flag --overwrite
  if [ -d "$SEQ/labels" ]; then
    "$BIN/hif-eval" --labels "$SEQ/labels" --predictions "$OUT/$mode/predictions" \
      --scans "$SEQ/velodyne" --json "$OUT/$mode/scores.json" --overwrite -q > "$OUT/$mode/scores.txt"
    tail -n 1 "$OUT/$mode/scores.txt" | sed "s/^\[hif-eval\]/[demo] $mode:/"
    grep "^moving-" "$OUT/$mode/scores.txt" | sed "s/^/[demo]   DA of /" || true
  fi
done
echo "[demo] outputs in $OUT/{offline,online}: static_map.ply (the cleaned map),"
echo "[demo]   removed.ply, predictions/*.label, map.hifmap, summary.json, scores.json"
