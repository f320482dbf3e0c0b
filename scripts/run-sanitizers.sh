#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The sanitizer run of CI (.ci/run, after scripts/run-tests.sh): the VTK-free kernels, their
# tests and the benchmark built with ASan + UBSan (-O1 -g, AV_SANITIZE) in build-asan/, then
# every test of that build. Any sanitizer report aborts its test, so the script fails.
# Extra arguments go to ctest (e.g. -R Kernel.IO).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${AV_ASAN_BUILD_DIR:-build-asan}
if [[ ! -f "$BUILD_DIR/build.ninja" ]]; then
  launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DAV_KERNELS_ONLY=ON \
    -DAV_SANITIZE=ON -DAV_REQUIRE_REAL_DATA=OFF "${launcher[@]}" >/dev/null
fi
echo "[sanitizers] building in $BUILD_DIR ..." >&2
cmake --build "$BUILD_DIR"
# halt/abort on the first report. The suppressions name third-party libraries only
# (Documentation/hardening.md).
# Leak checking is off: the process-lifetime allocations of MPI (started by hypre) and of the
# UBSan runtime show up as leaks from dlclosed modules that the suppressions did not catch.
export ASAN_OPTIONS="abort_on_error=1:detect_leaks=0:strict_string_checks=1:detect_stack_use_after_return=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
if [[ -f scripts/lsan.supp ]]; then
  export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0"
fi
cd "$BUILD_DIR"
# The whole surface remeshing pipeline (torus, tube, Cyclide1) is too slow under ASan for CI's
# budget; the release suite runs it.
ctest --output-on-failure --timeout 1200 -E "Kernel.Delaunay.TestSurfaceRemeshing" "$@"
