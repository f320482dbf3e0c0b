#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Command 2 of the README: install what is missing, build, run the whole CTest suite.
# The rendering tests share one X server, started here for the whole run (Xvfb picks a free
# display itself and reports it when ready: no display race, whatever the load) and stopped on
# exit. -noreset: by default an X server resets when its last client disconnects, and a test
# connecting during that reset fails ("bad X server connection"). Without DISPLAY, a hand-run
# ctest skips the rendering tests with a message.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
BUILD_DIR=${AV_BUILD_DIR:-build}
# The realdata tests read what this makes (Documentation/real-data.md); kept between runs.
bash scripts/make-real-data.sh "$BUILD_DIR/real-data"

XVFB_PID=""
XVFB_DIR=$(mktemp -d)
cleanup()
{
  [[ -n $XVFB_PID ]] && kill "$XVFB_PID" 2>/dev/null && wait "$XVFB_PID" 2>/dev/null
  rm -rf "$XVFB_DIR"
}
trap cleanup EXIT
Xvfb -displayfd 3 -screen 0 1280x1024x24 -nolisten tcp -noreset 3>"$XVFB_DIR/display" \
  >"$XVFB_DIR/xvfb.log" 2>&1 &
XVFB_PID=$!
for _ in $(seq 300); do
  [[ -s $XVFB_DIR/display ]] && break
  if ! kill -0 "$XVFB_PID" 2>/dev/null; then
    echo "[run-tests] Xvfb did not start:" >&2
    cat "$XVFB_DIR/xvfb.log" >&2
    exit 1
  fi
  sleep 0.1
done
[[ -s $XVFB_DIR/display ]] || { echo "[run-tests] Xvfb gave no display within 30 s" >&2; exit 1; }
export DISPLAY=":$(tr -d '[:space:]' <"$XVFB_DIR/display")"
echo "[run-tests] one Xvfb for the suite on DISPLAY=$DISPLAY" >&2

cd "$BUILD_DIR"
ctest --output-on-failure --timeout 900 "$@"
