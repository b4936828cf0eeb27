#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Sourced by scripts/walkers.sh and scripts/sensors.sh. scene_switches PREFIX TAG reads the
# environment variables PREFIX_FOLIAGE and PREFIX_ROADSIDE (0, the default, or 1) and sets
# SCENE_FLAGS (hif-synthetic-kitti's --foliage and --roadside, for those set to 1) and SUFFIX
# (of the work folder: -foliage, -roadside, both, or nothing); any other value is an error,
# reported as [TAG].
scene_switches() {
  SCENE_FLAGS=()
  SUFFIX=""
  local name var value
  for name in foliage roadside; do
    var=${1}_${name^^}
    value=${!var:-0}
    case "$value" in
      0) ;;
      1) SCENE_FLAGS+=(--$name); SUFFIX+=-$name ;;
      *) echo "[$2] $var=$value is not 0 or 1" >&2; exit 1;;
    esac
  done
}
