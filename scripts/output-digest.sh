#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# A digest of everything hif-clean writes, to show that a change of code leaves its outputs
# byte for byte the same: the synthetic street (30 scans) and the real KITTI clips 01 and 08
# (../shared/data/kitti, or $HIF_KITTI_DIR), each cleaned offline and online with the shipped
# configs, from a rawlog (kitti2rawlog) and straight from the sequence folder. Prints one line per
# output file (sha256, then the file) and, from summary.json, the counts (timings left out: they
# differ from run to run). Clouds are written in both formats (--format both). The map file is
# digested by its content (decompressed).
#
#   bash scripts/output-digest.sh > before.txt     # on the old code
#   bash scripts/output-digest.sh > after.txt      # on the new code
#   diff before.txt after.txt
#
# Work files go to ${HIF_DIGEST_DIR:-build/digest}/ and are replaced on every run.
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${HIF_BUILD_DIR:-build}/apps
ROOT=${HIF_DIGEST_DIR:-build/digest}
KITTI=${HIF_KITTI_DIR:-../shared/data/kitti}
mkdir -p "$ROOT"

inputs=(synthetic)
"$BIN/hif-synthetic-kitti" -o "$ROOT/synthetic/seq" -n 30 --overwrite > /dev/null 2>&1
for seq in 01 08; do
  if [ -d "$KITTI/sequences/$seq" ]; then
    inputs+=("$seq")
    mkdir -p "$ROOT/$seq"
    ln -sfn "$(realpath "$KITTI/sequences/$seq")" "$ROOT/$seq/seq"
  else
    echo "[output-digest] $KITTI/sequences/$seq missing: left out" >&2
  fi
done

for name in "${inputs[@]}"; do
  d=$ROOT/$name
  "$BIN/kitti2rawlog" -i "$d/seq" -o "$d/scans.rawlog" --overwrite > /dev/null 2>&1
  for mode in offline online; do
    flag=""; [ $mode = online ] && flag=--online
    for input in rawlog folder; do
      src=$d/scans.rawlog; out=$d/$mode; [ $input = folder ] && src=$d/seq out=$d/$mode-from-folder
      rm -rf "${out:?}"
      "$BIN/hif-clean" -i "$src" -o "$out" $flag --format both -q > /dev/null
      (cd "$out" && find . -type f ! -name summary.json ! -name map.hifmap | LC_ALL=C sort \
        | xargs sha256sum) | sed "s|  \./|  $name/${out##*/}/|"
      # The map by what it holds, not by how the gzip file around it is compressed.
      echo "$(gzip -dc "$out/map.hifmap" | sha256sum | cut -d' ' -f1)  $name/${out##*/}/map.hifmap (content)"
      grep -E '"(scans|points_in|points_kept|points_removed|points_invalid|pillars|intervals)"' \
        "$out/summary.json" | tr -d ' ,' | sed "s|^|$name/${out##*/}/summary.json |"
    done
  done
done
