#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# A long run: N synthetic scans (default 5,000) through hif-clean, its resident memory sampled
# every second. The sensor creeps along the street at $HIF_EGO_SPEED m/s (default 0.3: 150 m in
# 5,000 scans; the generator traces every ray against the whole street, so a street as long as
# 5,000 scans at driving speed would take hours to make), cars passing it. Prints the curve (seconds, phase, MiB) and writes it to
# <work>/memory.csv. The generated sequence (about 1.2 MB a scan) is deleted at the end unless
# HIF_KEEP=1. Not a test: it takes minutes and several GB of disk.
#   bash scripts/long-run.sh [scans] [work folder]     (after scripts/build.sh)
#   HIF_CLEAN_ARGS="--online" bash scripts/long-run.sh  (the online mode)
set -euo pipefail
cd "$(dirname "$0")/.."
N=${1:-5000}
WORK=${2:-/tmp/hif-long-run}
BIN=${HIF_BUILD_DIR:-build}/apps
mkdir -p "$WORK"
echo "[long-run] $N scans in $WORK"
"$BIN/hif-synthetic-kitti" -n "$N" -o "$WORK/seq" --ego-speed "${HIF_EGO_SPEED:-0.3}" --overwrite \
  | tail -1
"$BIN/kitti2rawlog" -i "$WORK/seq" -o "$WORK/seq.rawlog" --external --overwrite | tail -1
# shellcheck disable=SC2086
"$BIN/hif-clean" -i "$WORK/seq.rawlog" -o "$WORK/out" --overwrite ${HIF_CLEAN_ARGS:-} \
  > "$WORK/hif-clean.out" 2> "$WORK/hif-clean.err" &
pid=$!
echo "seconds,phase,rss_mib" > "$WORK/memory.csv"
t0=$(date +%s)
while kill -0 "$pid" 2> /dev/null; do
  rss=$(awk '/^VmRSS/ {print $2}' "/proc/$pid/status" 2> /dev/null || true)
  [ -n "$rss" ] || break
  phase=$(tail -c 300 "$WORK/hif-clean.err" | tr '\r' '\n' | grep -o 'inserting\|classifying' \
    | tail -1 || true)
  awk -v t=$(( $(date +%s) - t0 )) -v p="${phase:-inserting}" -v kb="$rss" \
    'BEGIN {printf "%d,%s,%.1f\n", t, p, kb / 1024}' >> "$WORK/memory.csv"
  sleep 1
done
wait "$pid" || { cat "$WORK/hif-clean.err"; exit 1; }
cat "$WORK/hif-clean.out"
echo "[long-run] resident memory (MiB), one sample in ten:"
awk -F, 'NR > 1 && (NR - 2) % 10 == 0 {printf "  %4d s  %-11s %7.1f\n", $1, $2, $3}' "$WORK/memory.csv"
awk -F, 'NR > 1 {n++; if ($3 > max) max = $3} END {printf "[long-run] %d samples, peak %.1f MiB\n", n, max}' \
  "$WORK/memory.csv"
[ "${HIF_KEEP:-0}" = 1 ] || rm -rf "$WORK/seq" "$WORK/seq.rawlog"
