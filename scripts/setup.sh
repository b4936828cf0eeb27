#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Set up and build: Debian packages, then a Release build in ./build.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
echo "[setup] built: libraries in build/libs, tests in build/tests (run: bash scripts/test.sh)"
