#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Runs a rendering test on the X server of the whole CTest run (scripts/run-tests.sh starts one
# Xvfb and exports DISPLAY). Without DISPLAY the test is skipped (exit 77, SKIP_RETURN_CODE).
if [[ -z ${DISPLAY:-} ]]; then
  echo "skipped: this rendering test needs an X display; scripts/run-tests.sh starts one Xvfb" \
    "for the whole suite (or set DISPLAY, e.g. to a running Xvfb)" >&2
  exit 77
fi
exec "$@"
