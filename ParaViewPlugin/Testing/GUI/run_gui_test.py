# SPDX-License-Identifier: BSD-3-Clause
"""Runs a GUI test script in the paraview client and passes only on its own verdict.

The client's exit status alone proves nothing (a script that stops early, or never starts,
leaves `paraview --exit` at 0), so the script writes its log and, last, a status file with
"OK" or "FAILED"; this driver clears both, runs the command, prints the log and exits 0 only
for "OK". Usage: run_gui_test.py OUTPUT_DIR TIMEOUT_S COMMAND...
"""
import os
import subprocess
import sys

out, timeout, command = sys.argv[1], float(sys.argv[2]), sys.argv[3:]
os.makedirs(out, exist_ok=True)
status_file, log_file = os.path.join(out, "status.txt"), os.path.join(out, "log.txt")
for f in (status_file, log_file):
    if os.path.exists(f):
        os.remove(f)
env = dict(os.environ, AV_OUTPUT=out)
try:
    p = subprocess.run(command, env=env, timeout=timeout, capture_output=True, text=True)
    print(p.stdout[-4000:], p.stderr[-4000:], sep="\n")
    print("client exit status %d" % p.returncode)
except subprocess.TimeoutExpired:
    print("the GUI client ran past %g s" % timeout)
if os.path.exists(log_file):
    print(open(log_file).read())
status = open(status_file).read().strip() if os.path.exists(status_file) else "no status"
print("verdict: " + status)
sys.exit(0 if status == "OK" else 1)
