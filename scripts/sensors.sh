#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The sensors suite: each simulated LiDAR of hif-synthetic-kitti (--sensor) in each scene
# (street: cars and people; walkers; cyclists; traffic: cars leading and following the
# sensor), 10 scans, cleaned offline with the shipped defaults (or the hif-clean flags given,
# e.g. --online) and scored per moving class: one line per sensor and scene, SA, DA, AA and DA
# per class (car 252, cyclist 253, person 254).
#
#   bash scripts/sensors.sh                                      # shipped configs
#   bash scripts/sensors.sh -c share/hif/config/kitti-paper.ini  # extra hif-clean flags
#
# Environment: HIF_SENSORS (default: every sensor), HIF_SENSORS_SCENES (default "street walkers
# cyclists traffic"), HIF_SENSORS_SCANS (default 10), HIF_SENSORS_SEEDS (default 1; with
# several, e.g. "1 2 3 4 5 6", a line per seed, "scene:seed", and the mean of each column over
# them, "scene mean": one seed's scene places a few people and cars, and scores vary by tens of
# points from seed to seed),
# HIF_SENSORS_FOLIAGE (1: hif-synthetic-kitti --foliage, porous canopies, bushes and hedges),
# HIF_SENSORS_ROADSIDE (1: --roadside, traffic signs, street lights and railings).
# Work files go to ${HIF_SENSORS_DIR:-build/sensors, build/sensors-foliage with foliage,
# -roadside with street furniture}/; clips are generated once per sensor, scene, number of scans
# and seed (their folder names all four) and reused. With street furniture
# each line also gives its SA per class (fence, pole, traffic-sign).
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${HIF_BUILD_DIR:-build}/apps
source scripts/scene-switches.sh
scene_switches HIF_SENSORS sensors
ROOT=${HIF_SENSORS_DIR:-build/sensors$SUFFIX}
SENSORS=${HIF_SENSORS:-hdl-64e hdl-32e vlp-16 os1-128 vlp-32c mid-70}
SCENES=${HIF_SENSORS_SCENES:-street walkers cyclists traffic}
SCANS=${HIF_SENSORS_SCANS:-10}
SEEDS=${HIF_SENSORS_SEEDS:-1}
several=0  # more than one seed: each line labelled with its seed, then their mean
[ "$(echo $SEEDS | wc -w)" -gt 1 ] && several=1
for app in hif-synthetic-kitti hif-clean hif-eval; do
  [ -x "$BIN/$app" ] || { echo "[sensors] $BIN/$app not built: run bash scripts/build.sh" >&2; exit 1; }
done
mkdir -p "$ROOT/runs"
FURNITURE=0  # the clips have street furniture: its classes' SA are printed too
[[ " ${SCENE_FLAGS[*]} " == *" --roadside "* ]] && FURNITURE=1
printf "%-8s %-9s %7s %7s %7s %7s %7s %7s" sensor scene SA DA AA car cyclist person
[ $FURNITURE = 1 ] && printf " %7s %7s %7s" fence pole sign
printf "\n"
for sensor in $SENSORS; do
  for scene in $SCENES; do
    lines=""
    for seed in $SEEDS; do
      name=${sensor}_${scene}_n${SCANS}_s$seed
      seq=$ROOT/clips/$name
      if [ ! -f "$seq/times.txt" ]; then
        "$BIN/hif-synthetic-kitti" -o "$seq" --scene "$scene" --sensor "$sensor" --seed "$seed" \
          -n "$SCANS" "${SCENE_FLAGS[@]}" --overwrite > /dev/null 2>&1
      fi
      out=$ROOT/runs/$name
      "$BIN/hif-clean" -i "$seq" -o "$out" -q --overwrite --no-png "$@" > "$out.log" 2>&1 \
        || { cat "$out.log" >&2; exit 1; }
      "$BIN/hif-eval" --labels "$seq/labels" --predictions "$out/predictions" -q > "$out.eval"
      label=$scene
      [ $several = 1 ] && label=$scene:$seed
      line=$(awk -v a="$sensor" -v b="$label" -v furniture=$FURNITURE -f scripts/score-line.awk "$out.eval")
      echo "$line"
      lines+="$line"$'\n'
    done
    # The mean of each column over the seeds ("-" where no seed has such points).
    if [ $several = 1 ]; then
      printf "%s" "$lines" | awk -v a="$sensor" -v b="$scene mean" -f scripts/mean-line.awk
    fi
  done
done
