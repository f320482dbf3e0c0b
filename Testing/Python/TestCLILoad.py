# SPDX-License-Identifier: BSD-3-Clause
"""Load: 20 CLI runs back to back (five small inputs, four times each) and then 4 at once (on
four different inputs) all succeed, and every run's outputs equal the first single run of its
input exactly (timings aside)."""
import os
import subprocess
import sys
import tempfile

from cli_compare import CLI, check, failures, output_signature

DATA = os.environ["AV_DATA"]
COMMON = ["--sites", "60", "--iterations", "8", "--sample-iterations", "10", "--quiet"]
INPUTS = {
    "cube1": ["--metric", "preset:cube1", "--resolution", "7", "--dim", "5"],
    "cube2": ["--metric", "preset:cube2", "--resolution", "6", "--dim", "5"],
    "gaussian2d-preset": ["--metric", "preset:gaussian2d", "--resolution", "15", "--dim", "3"],
    "gaussian2d": [os.path.join(DATA, "gaussian2d.mesh"), "--sol",
                   os.path.join(DATA, "gaussian2d.sol"), "--metric", "metric:Metric", "--dim",
                   "3"],
    "cube1-seed2": ["--metric", "preset:cube1", "--resolution", "7", "--dim", "5", "--seed", "2"],
}


def command(name, out):
    return [CLI] + INPUTS[name] + COMMON + ["--output-dir", out]


with tempfile.TemporaryDirectory() as tmp:
    reference = {}
    for k in range(4):
        for name in INPUTS:
            out = os.path.join(tmp, "seq-%d-%s" % (k, name))
            p = subprocess.run(command(name, out), capture_output=True, text=True, timeout=300)
            check(p.returncode == 0, "back-to-back %s #%d exits 0 (%s)" %
                  (name, k, p.stderr.strip()[-300:]))
            if p.returncode != 0:
                continue
            sig = output_signature(out)
            if name not in reference:
                reference[name] = sig
            else:
                check(sig == reference[name], "back-to-back %s #%d equals the first run" % (name, k))
    concurrent = list(INPUTS)[:4]
    procs = [(name, subprocess.Popen(command(name, os.path.join(tmp, "par-" + name)),
                                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True))
             for name in concurrent]
    for name, proc in procs:
        _, err = proc.communicate(timeout=600)
        check(proc.returncode == 0, "concurrent %s exits 0 (%s)" % (name, err.strip()[-300:]))
        if proc.returncode == 0 and name in reference:
            check(output_signature(os.path.join(tmp, "par-" + name)) == reference[name],
                  "concurrent %s equals the single run" % name)
    print("20 back-to-back runs and 4 concurrent runs compared")

if failures:
    print("%d failure(s)" % len(failures))
    sys.exit(1)
print("OK")
