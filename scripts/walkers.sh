#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The walking-people suite: short synthetic clips (hif-synthetic-kitti --scene walkers, 10 scans,
# 1 s) where only people move, in groups, along the sidewalks and across the road at 0.8, 1.2
# and 1.6 m/s, 8-25 m away, with the sensor standing or moving at 1, 3 and 5 m/s (0 to 0.5 m
# per scan), several seeds each. Every clip is cleaned offline and online with hif-clean, and
# all clips of a mode are scored together by hif-eval (per moving class and range band).
#
#   bash scripts/walkers.sh                          # shipped configs
#   bash scripts/walkers.sh -c share/hif/config/kitti-paper.ini    # extra hif-clean flags
#   HIF_WALKERS_SCENE=cyclists bash scripts/walkers.sh   # cyclists at 3 to 6 m/s instead
#   HIF_WALKERS_SCENE=radial bash scripts/walkers.sh     # people walking along the line of sight
#   HIF_WALKERS_FOLIAGE=1 bash scripts/walkers.sh        # vegetation beams enter (--foliage)
#
# Environment: HIF_WALKERS_SCENE (walkers, the default, radial or cyclists), HIF_WALKERS_SEEDS
# (default "1 2 3"), HIF_WALKERS_SPEEDS (default "0 1 3 5"), HIF_WALKERS_SCANS (default 10),
# HIF_WALKERS_MODES (default "offline online"), HIF_WALKERS_FOLIAGE (1: hif-synthetic-kitti
# --foliage, porous canopies, bushes and hedges), HIF_WALKERS_ROADSIDE (1: --roadside, traffic
# signs, street lights and railings); the same people either way.
# Work files go to ${HIF_WALKERS_DIR:-build/<scene>, build/<scene>-foliage with foliage,
# -roadside with street furniture}/; clips are generated once per speed, seed and number of scans
# (their folder names all three) and reused.
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${HIF_BUILD_DIR:-build}/apps
SCENE=${HIF_WALKERS_SCENE:-walkers}
case "$SCENE" in walkers|radial|cyclists) ;; *) echo "[walkers] HIF_WALKERS_SCENE=$SCENE is not walkers, radial or cyclists" >&2; exit 1;; esac
source scripts/scene-switches.sh
scene_switches HIF_WALKERS walkers
ROOT=${HIF_WALKERS_DIR:-build/$SCENE$SUFFIX}
SEEDS=${HIF_WALKERS_SEEDS:-1 2 3}
SPEEDS=${HIF_WALKERS_SPEEDS:-0 1 3 5}
SCANS=${HIF_WALKERS_SCANS:-10}
MODES=${HIF_WALKERS_MODES:-offline online}
for app in hif-synthetic-kitti kitti2rawlog hif-clean hif-eval; do
  [ -x "$BIN/$app" ] || { echo "[walkers] $BIN/$app not built: run bash scripts/build.sh" >&2; exit 1; }
done
mkdir -p "$ROOT/clips"
for mode in $MODES; do
  all=$ROOT/$mode
  rm -rf "$all"
  mkdir -p "$all/labels" "$all/predictions" "$all/velodyne"
  for speed in $SPEEDS; do
    for seed in $SEEDS; do
      clip=v${speed}_s${seed}_n$SCANS
      seq=$ROOT/clips/$clip
      if [ ! -f "$seq/scans.rawlog" ]; then
        "$BIN/hif-synthetic-kitti" -o "$seq" --scene "$SCENE" --ego-speed "$speed" --seed "$seed" \
          -n "$SCANS" "${SCENE_FLAGS[@]}" --overwrite > /dev/null 2>&1
        "$BIN/kitti2rawlog" -i "$seq" -o "$seq/scans.rawlog" --overwrite > /dev/null 2>&1
      fi
      flag=""; [ "$mode" = online ] && flag=--online
      out=$ROOT/runs/$mode/$clip
      rm -rf "$out"; mkdir -p "$(dirname "$out")"
      "$BIN/hif-clean" -i "$seq/scans.rawlog" -o "$out" $flag -q "$@" > "$out.log" 2>&1 \
        || { cat "$out.log" >&2; exit 1; }
      for f in "$seq"/labels/*.label; do
        n=$(basename "$f" .label)
        ln -s "$(realpath "$f")" "$all/labels/${clip}_$n.label"
        ln -s "$(realpath "$out/predictions/$n.label")" "$all/predictions/${clip}_$n.label"
        ln -s "$(realpath "$seq/velodyne/$n.bin")" "$all/velodyne/${clip}_$n.bin"
      done
    done
  done
  echo "[walkers] $SCENE$SUFFIX, $mode: $(echo $SPEEDS | wc -w) sensor speeds x $(echo $SEEDS | wc -w) seeds, $SCANS scans each"
  "$BIN/hif-eval" --labels "$all/labels" --predictions "$all/predictions" --scans "$all/velodyne" \
    --ego-radius 0 --json "$all/scores.json" -q
done
