#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The real clips as sparser LiDARs: KITTI 01, 03, 04 and 08 with all 64 rings, every 2nd (32,
# about an HDL-32E's spacing) and every 4th (16, about a VLP-16's), cleaned offline with the
# shipped defaults, or the hif-clean flags given, and scored per moving class.
#
#   bash scripts/rings.sh                                   # shipped configs
#   bash scripts/rings.sh -c share/hif/config/kitti-paper.ini
#
# Environment: HIF_KITTI_DIR (default ../shared/data/kitti), HIF_RINGS_SEQS (default
# "01 03 04 08"), HIF_RINGS_EVERY (default "1 2 4"). The copies go to
# ${HIF_RINGS_DIR:-build/rings}/ (made once, by the test tool hif_decimate_rings).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${HIF_BUILD_DIR:-build}
BIN=$BUILD/apps
TOOL=$BUILD/tests/hif_decimate_rings
KITTI=${HIF_KITTI_DIR:-../shared/data/kitti}
ROOT=${HIF_RINGS_DIR:-build/rings}
SEQS=${HIF_RINGS_SEQS:-01 03 04 08}
EVERY=${HIF_RINGS_EVERY:-1 2 4}
for exe in "$BIN/hif-clean" "$BIN/hif-eval" "$TOOL"; do
  [ -x "$exe" ] || { echo "[rings] $exe not built: run bash scripts/build.sh" >&2; exit 1; }
done
mkdir -p "$ROOT"
printf "%-8s %-9s %7s %7s %7s %7s %7s %7s\n" seq rings SA DA AA car cyclist person
for seq in $SEQS; do
  src=$KITTI/sequences/$seq
  [ -d "$src" ] || { echo "[rings] $src missing: left out" >&2; continue; }
  for k in $EVERY; do
    if [ "$k" = 1 ]; then clip=$src; else
      clip=$ROOT/${seq}_every$k
      [ -f "$clip/times.txt" ] || "$TOOL" "$src" "$clip" "$k" > /dev/null
    fi
    out=$ROOT/runs/${seq}_every$k
    mkdir -p "$(dirname "$out")"
    "$BIN/hif-clean" -i "$clip" -o "$out" -q --overwrite --no-png "$@" > "$out.log" 2>&1 \
      || { cat "$out.log" >&2; exit 1; }
    "$BIN/hif-eval" --labels "$clip/labels" --predictions "$out/predictions" -q > "$out.eval"
    awk -v a="$seq" -v b=$((64 / k)) -f scripts/score-line.awk "$out.eval"
  done
done
