#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs what is missing on Debian 12 (apt-get, as root), then configures and builds
# AnisoVoronoi into ./build. Used by run-main.sh and run-tests.sh; safe to run again.
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(cmake g++ ninja-build paraview paraview-dev python3-paraview mpi-default-dev
  libdouble-conversion-dev libeigen3-dev libnanoflann-dev libtet1.5-dev tetgen libtbb-dev
  libsuitesparse-dev libopenblas0-pthread liblbfgspp-dev xvfb xauth python3-dev libhypre-dev
  calculix-cgx-examples
  # the plugin's in-GUI help (XML_DOCUMENTATION): xmlpatterns, Qt5Help and qhelpgenerator
  qttools5-dev qtxmlpatterns5-dev-tools)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "[setup] installing: ${missing[*]}" >&2
  SUDO=""
  [[ $(id -u) -ne 0 ]] && SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  # python3-vtk9 (pulled by libvtk9-dev) conflicts with python3-paraview: never install it.
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

BUILD_DIR=${AV_BUILD_DIR:-build}
if [[ ! -f "$BUILD_DIR/build.ninja" ]]; then
  cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
echo "[setup] building in $BUILD_DIR ..." >&2
cmake --build "$BUILD_DIR"
