#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Command 2 of the README: install what is missing, build, run the whole CTest suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
BUILD_DIR=${AV_BUILD_DIR:-build}
# The realdata tests read what this makes (Documentation/real-data.md); kept between runs.
bash scripts/make-real-data.sh "$BUILD_DIR/real-data"
cd "$BUILD_DIR"
ctest --output-on-failure --timeout 900 "$@"
