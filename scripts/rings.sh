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
# "01 03 04 08"), HIF_RINGS_EVERY (default "1 2 4"), HIF_RINGS_PHASES ("all": every choice of
# the rings kept, 0 to k-1, each on a line of its own ("16+1": every 4th ring from ring 1),
# then their mean ("16 mean"); default 0 only, the rings 0, k, 2k, ...). Which rings a
# decimated copy keeps moves its scores by several points (a car 30 m away seen by one ring or
# by two): compare changes over all of them. The copies go to ${HIF_RINGS_DIR:-build/rings}/
# (made once, by the test tool hif_decimate_rings).
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
    phases=0
    [ "${HIF_RINGS_PHASES:-0}" = all ] && phases=$(seq 0 $((k - 1)))
    lines=""
    for phase in $phases; do
      if [ "$k" = 1 ]; then clip=$src; name=${seq}_every$k; label=64; else
        name=${seq}_every$k; label=$((64 / k))
        [ "$phase" = 0 ] || { name=${name}_from$phase; label=$label+$phase; }
        clip=$ROOT/$name
        [ -f "$clip/times.txt" ] || "$TOOL" "$src" "$clip" "$k" "$phase" > /dev/null
      fi
      out=$ROOT/runs/$name
      mkdir -p "$(dirname "$out")"
      "$BIN/hif-clean" -i "$clip" -o "$out" -q --overwrite --no-png "$@" > "$out.log" 2>&1 \
        || { cat "$out.log" >&2; exit 1; }
      "$BIN/hif-eval" --labels "$clip/labels" --predictions "$out/predictions" -q > "$out.eval"
      line=$(awk -v a="$seq" -v b="$label" -f scripts/score-line.awk "$out.eval")
      echo "$line"
      lines+="$line"$'\n'
    done
    # The mean of each column over the phases ("-" where a phase has no such points).
    if [ "$k" != 1 ] && [ "$(echo "$phases" | wc -w)" -gt 1 ]; then
      printf "%s" "$lines" | awk -v a="$seq" -v b="$((64 / k)) mean" -f scripts/mean-line.awk
    fi
  done
done
