#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Speed on real KITTI scans (sequence 08 of ../shared/data/kitti, or $HIF_KITTI_DIR/sequences/08,
# or the folder in $HIF_BENCH_SEQUENCE), in two parts (HIF_BENCH_PARTS, default both):
#   algorithm  the Google Benchmark suite (bench/), 5 interleaved repetitions of each, medians;
#   command    the whole hif-clean command as a user runs it, timed by /usr/bin/time: on the
#              sequence in the DynamicMap benchmark layout (made once by kitti2rawlog
#              --dynamicmap), the same without map.png (--no-png), and on the KITTI folder
#              itself, $HIF_BENCH_RUNS runs each (default
#              7), interleaved, outputs removed between runs; medians of wall time, CPU time and
#              peak memory, the insertion and classification medians of summary.json, and the
#              start of the process alone (hif-clean --version: MRPT and its libraries loaded).
# A long run (issue 21: at least 128 scans of about 120,000 points) on a synthetic sequence:
#   build/apps/hif-synthetic-kitti -o /tmp/long -n 160 --sensor os1-128
#   HIF_BENCH_SEQUENCE=/tmp/long HIF_BENCH_PARTS=command bash scripts/bench.sh
# Side by side with DUFOMap on the same DynamicMap folder: HIF_BENCH_DUFOMAP=<its dufomap_run>
# (built outside this repository, e.g. KTH-RPL/dufomap's commit d3df8fc with src/ and assets/
# of its main) and HIF_BENCH_DUFOMAP_CONFIG=<its assets/config.toml>; it runs
# $HIF_BENCH_DUFOMAP_RUNS times (default 1: it takes 20-40 x as long), after hif-clean's runs.
# Extra arguments go to the Google Benchmark, e.g.
#   bash scripts/bench.sh --benchmark_filter=Insert
#   HIF_BENCH_PARTS=command bash scripts/bench.sh
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${HIF_BUILD_DIR:-build}
PARTS=${HIF_BENCH_PARTS:-algorithm command}
HIF_BUILD_BENCH=ON bash scripts/build.sh > /dev/null

if [[ " $PARTS " == *" algorithm "* ]]; then
  "$BUILD/bench/hif_bench" --benchmark_repetitions="${HIF_BENCH_REPETITIONS:-5}" \
    --benchmark_enable_random_interleaving=true \
    --benchmark_report_aggregates_only=true --benchmark_display_aggregates_only=true "$@" \
    | grep -vE "_(mean|stddev|cv) "
fi

[[ " $PARTS " == *" command "* ]] || exit 0
SEQ=${HIF_BENCH_SEQUENCE:-${HIF_KITTI_DIR:-../shared/data/kitti}/sequences/08}
if [ ! -d "$SEQ/velodyne" ]; then
  echo "[bench] $SEQ/velodyne missing: the command benchmark needs KITTI scans" >&2
  exit 1
fi
RUNS=${HIF_BENCH_RUNS:-7}
WORK=$BUILD/bench-data
DM=$WORK/dynamicmap
mkdir -p "$WORK"
# The benchmark layout, made once from the sequence (remade for another sequence, or if the
# sequence is newer).
src_id=$(realpath "$SEQ")
if [ ! -d "$DM/pcd" ] || [ "$SEQ/velodyne" -nt "$DM/pcd" ] \
    || [ "$(cat "$WORK/dynamicmap.source" 2> /dev/null)" != "$src_id" ]; then
  "$BUILD/apps/kitti2rawlog" -i "$SEQ" -o "$DM" --dynamicmap --overwrite -q > /dev/null
  echo "$src_id" > "$WORK/dynamicmap.source"
fi
median() { sort -g | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }
field() { grep -E "\"$1\"" "$2" | head -1 | sed -E 's/.*: *([0-9.eE+-]+),?/\1/'; }

declare -A COL
record() { COL[$1]+="$2 "; }
INPUTS=(dynamicmap nopng kitti)
for ((r = 1; r <= RUNS; r++)); do
  for input in "${INPUTS[@]}"; do
    src=$DM; [ $input = kitti ] && src=$SEQ
    flags=(-q); [ $input = nopng ] && flags+=(--no-png)
    out=$WORK/out-$input
    rm -rf "$out" "$DM/hif_output.pcd"   # a run replacing old results also deletes them
    t=$( { /usr/bin/time -f "%e %U %S %M" "$BUILD/apps/hif-clean" -i "$src" -o "$out" \
           "${flags[@]}" > /dev/null; } 2>&1 | tail -1)
    read -r wall user sys rss <<< "$t"
    record "$input.wall" "$wall"
    record "$input.cpu" "$(awk -v u="$user" -v s="$sys" 'BEGIN {print u + s}')"
    record "$input.rss" "$(awk -v k="$rss" 'BEGIN {print k / 1024}')"
    record "$input.insert" "$(field insert_ms_median "$out/summary.json")"
    record "$input.classify" "$(field classify_ms_median "$out/summary.json")"
    record "$input.scans" "$(field scans "$out/summary.json")"
  done
  t=$( { /usr/bin/time -f "%e" "$BUILD/apps/hif-clean" --version > /dev/null; } 2>&1 | tail -1)
  record start.wall "$t"
done
med() { tr ' ' '\n' <<< "${COL[$1]}" | grep . | median; }
echo "[bench] hif-clean, whole command, $RUNS runs each, medians (sequence $SEQ)"
printf "%-44s %8s %8s %9s %10s %11s %10s\n" input "wall s" "CPU s" "peak MiB" "insert ms" \
  "classify ms" "wall/alg"
for input in "${INPUTS[@]}"; do
  n=$(med "$input.scans"); ins=$(med "$input.insert"); cls=$(med "$input.classify")
  wall=$(med "$input.wall")
  case $input in
    dynamicmap) label="DynamicMap folder (dynamicmap.ini)" ;;
    nopng) label="DynamicMap folder, --no-png" ;;
    kitti) label="KITTI folder (kitti.ini)" ;;
  esac
  printf "%-44s %8.2f %8.2f %9.1f %10.2f %11.2f %10.2f\n" "$label" "$wall" "$(med "$input.cpu")" \
    "$(med "$input.rss")" "$ins" "$cls" \
    "$(awk -v w="$wall" -v n="$n" -v a="$ins" -v b="$cls" 'BEGIN {print w / (n * (a + b) / 1000)}')"
done
printf "%-44s %8.2f\n" "process start alone (hif-clean --version)" "$(med start.wall)"
echo "[bench] wall/alg: the whole run over scans x (insert + classify medians) of its summary"

[ -n "${HIF_BENCH_DUFOMAP:-}" ] || exit 0
CONFIG=${HIF_BENCH_DUFOMAP_CONFIG:-$(dirname "$HIF_BENCH_DUFOMAP")/../assets/config.toml}
[ -x "$HIF_BENCH_DUFOMAP" ] || { echo "[bench] $HIF_BENCH_DUFOMAP is not a program" >&2; exit 1; }
[ -f "$CONFIG" ] || { echo "[bench] DUFOMap's config $CONFIG is missing" >&2; exit 1; }
for ((r = 1; r <= ${HIF_BENCH_DUFOMAP_RUNS:-1}; r++)); do
  t=$( { /usr/bin/time -f "%e %U %S %M" "$HIF_BENCH_DUFOMAP" "$DM" "$CONFIG" > /dev/null; } \
       2>&1 | tail -1)
  rm -f "$DM/dufomap_output.pcd"
  read -r wall user sys rss <<< "$t"
  record dufo.wall "$wall"
  record dufo.cpu "$(awk -v u="$user" -v s="$sys" 'BEGIN {print u + s}')"
  record dufo.rss "$(awk -v k="$rss" 'BEGIN {print k / 1024}')"
done
dw=$(med dufo.wall)
printf "%-44s %8.2f %8.2f %9.1f\n" "DUFOMap, DynamicMap folder" "$dw" "$(med dufo.cpu)" \
  "$(med dufo.rss)"
echo "[bench] DUFOMap over hif-clean (DynamicMap folder, wall): $(awk -v d="$dw" \
  -v h="$(med dynamicmap.wall)" 'BEGIN {printf "%.1f", d / h}') x"
