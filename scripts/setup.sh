#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Set up, build and run the main job: Debian packages, a Release build in ./build, then the
# full pipeline (convert, clean, evaluate) on a built-in synthetic sequence, or on the KITTI
# sequence folder given as argument.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
bash scripts/demo.sh "$@"
