#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Install the Debian 12 packages VarSurf needs to build, test and run (skipped when all present).
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config dpkg-dev
  libeigen3-dev libsuitesparse-dev libopenblas0-pthread libblas-dev liblapack-dev libosd-dev
  libocct-foundation-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev
  libocct-data-exchange-dev libocct-ocaf-dev libocct-visualization-dev
  pybind11-dev python3-pybind11 python3-dev python3-numpy python3-pytest python3-pytest-xdist
  python3-flake8
  libgtest-dev libgmock-dev libbenchmark-dev
  freecad python3-matplotlib libgl1-mesa-dri xvfb xauth clang-format
  clang libclang-rt-14-dev
)

missing=()
for pkg in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$pkg")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} packages present"
  exit 0
fi

echo "setup: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  SUDO="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
