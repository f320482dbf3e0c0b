# SPDX-License-Identifier: BSD-3-Clause
"""Determinism: the same input, seed and thread count give the same output, bit for bit.
The CLI runs twice on a 3D preset and on the bundled 2D Medit case: every point, cell and
field array of every output file, energy.csv and report.json must match exactly, except the
timing values (names with "Seconds" / keys ending in "_seconds"). The benchmark's JSON line
likewise (timings and peak memory aside), at a fixed thread count."""
import json
import os
import subprocess
import sys
import tempfile

from cli_compare import check, compare_runs, failures, is_timing, run_cli

BENCH = os.path.join(os.environ["AV_BUILD"], "bin", "anisovoronoi-bench")
DATA = os.environ["AV_DATA"]


CASES = {
    "cube1": ["--metric", "preset:cube1", "--resolution", "11", "--sites", "300",
              "--iterations", "20", "--sample-iterations", "30"],
    "gaussian2d": [os.path.join(DATA, "gaussian2d.mesh"), "--sol",
                   os.path.join(DATA, "gaussian2d.sol"), "--metric", "metric:Metric", "--dim",
                   "3", "--iterations", "20", "--sites", "150"],
}

with tempfile.TemporaryDirectory() as tmp:
    for label, args in CASES.items():
        a, b = os.path.join(tmp, label + "-a"), os.path.join(tmp, label + "-b")
        if run_cli(args, a) and run_cli(args, b):
            compare_runs(label, a, b)

    # The benchmark: identical JSON values at a fixed thread count.
    bench = [BENCH, "gaussian2d", "--stage", "all", "--resolution", "31", "--sites", "300",
             "--threads", "2"]
    lines = []
    for _ in range(2):
        p = subprocess.run(bench, capture_output=True, text=True, timeout=600)
        check(p.returncode == 0, "bench exits 0 (%s)" % p.stderr.strip()[-300:])
        lines.append([json.loads(l) for l in p.stdout.splitlines() if l.startswith("{")])
    check(len(lines[0]) >= 1 and len(lines[0]) == len(lines[1]), "bench prints its JSON lines")
    compared = 0
    for ja, jb in zip(lines[0], lines[1]):
        for key in ja:
            if not is_timing(key):
                check(ja[key] == jb.get(key), "bench %s: %r vs %r" % (key, ja[key], jb.get(key)))
                compared += 1
    print("bench: %d values compared" % compared)
    check(compared > 10, "bench: something was compared")

if failures:
    print("%d failure(s)" % len(failures))
    sys.exit(1)
print("OK")
