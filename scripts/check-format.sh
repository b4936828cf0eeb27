#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Fails if any C++ file differs from .clang-format. Fix with: bash scripts/check-format.sh --fix
set -euo pipefail
cd "$(dirname "$0")/.."
mapfile -t files < <(git ls-files '*.cpp' '*.h')
if [ "${1:-}" = "--fix" ]; then
  clang-format -i "${files[@]}"
  exit 0
fi
clang-format --dry-run --Werror "${files[@]}"
echo "[check-format] ${#files[@]} files formatted"
