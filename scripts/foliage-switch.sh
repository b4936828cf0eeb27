#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Sourced by scripts/walkers.sh and scripts/sensors.sh. foliage_switch VAR TAG reads the
# environment variable VAR (0, the default, or 1) and sets FOLIAGE (hif-synthetic-kitti's
# --foliage, or nothing) and SUFFIX (of the work folder: -foliage, or nothing); any other value
# is an error, reported as [TAG].
foliage_switch() {
  local value=${!1:-0}
  FOLIAGE=()
  SUFFIX=""
  case "$value" in
    0) ;;
    1) FOLIAGE=(--foliage); SUFFIX=-foliage ;;
    *) echo "[$2] $1=$value is not 0 or 1" >&2; exit 1;;
  esac
}
