#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs hif's build and test dependencies from Debian packages (bookworm). Idempotent.
set -euo pipefail
PKGS=(cmake g++ make pkg-config libmrpt-dev libeigen3-dev libabsl-dev libgtest-dev nlohmann-json3-dev
  liblzf-dev libtbb-dev libbenchmark-dev clang-format clang libclang-rt-14-dev libopencv-dev mrpt-apps)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "[install-deps] all ${#PKGS[@]} packages already installed"
  exit 0
fi
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
echo "[install-deps] installing: ${missing[*]}"
# Wait (up to 10 minutes) for another apt or dpkg to finish instead of failing on its lock.
LOCK=(-o DPkg::Lock::Timeout=600)
$SUDO apt-get "${LOCK[@]}" update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get "${LOCK[@]}" install -y -qq --no-install-recommends \
  "${missing[@]}"
