# SPDX-License-Identifier: BSD-3-Clause
"""The memory guard: under an address-space limit (bash `ulimit -v`), a case whose Cholesky
factor cannot fit is refused before the factorization with a one-line message giving the
estimate and the limit, exit status 1, and no signal (no crash, no OOM kill). The limit is
calibrated on this machine: the peak virtual size of a small run (libraries, thread stacks,
malloc arenas) plus a margin far below the big case's factor."""
import os
import subprocess
import sys
import time

CLI = os.path.join(os.environ["AV_BUILD"], "bin", "anisovoronoi")
failures = []
MARGIN_KB = 300 * 1024  # the big case's factor needs ~0.8 GB (64k vertices, 8D)


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAILED:", what)


def peak_virtual_kb(args):
    """Runs the CLI; returns (exit status, its largest VmPeak seen, in kB)."""
    p = subprocess.Popen([CLI] + args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    peak = 0
    while p.poll() is None:
        try:
            for line in open("/proc/%d/status" % p.pid):
                if line.startswith("VmPeak:"):
                    peak = max(peak, int(line.split()[1]))
        except (FileNotFoundError, ProcessLookupError, ValueError):
            pass
        time.sleep(0.02)
    p.communicate()
    return p.returncode, peak


def under_limit(limit_kb, args):
    quoted = " ".join("'%s'" % a for a in [CLI] + args)
    return subprocess.run(["bash", "-c", "ulimit -v %d && exec %s" % (limit_kb, quoted)],
                          capture_output=True, text=True, timeout=900)


out = os.path.join(os.environ["AV_BUILD"], "Testing", "Temporary", "memory-guard")
small = ["--metric", "preset:cube1", "--resolution", "11", "--sites", "100", "--iterations",
         "5", "--sample-iterations", "5", "--quiet", "--output-dir", out + "-small"]
# --solver direct: at 64k tet vertices the automatic choice is the iterative solver (no factor).
big = ["--metric", "preset:cube1", "--resolution", "40", "--sites", "1000", "--iterations", "5",
       "--solver", "direct", "--quiet", "--output-dir", out + "-big"]
status, base_kb = peak_virtual_kb(small)
check(status == 0 and base_kb > 0, "small run exits 0 (VmPeak %d kB)" % base_kb)
limit = base_kb + MARGIN_KB
print("small run VmPeak %d MB; limit %d MB" % (base_kb // 1024, limit // 1024))

# The small run itself still fits under the limit (the guard does not refuse what fits).
p = under_limit(limit, small)
check(p.returncode == 0, "small run under the limit exits 0 (%s)" % p.stderr.strip()[-300:])

t0 = time.time()
p = under_limit(limit, big)
err = p.stderr.strip()
print("big run: exit %d after %.1f s: %s" % (p.returncode, time.time() - t0, err))
check(p.returncode == 1, "big run exits with status 1, not a signal (%d)" % p.returncode)
check(err.startswith("anisovoronoi: error:") and err.count("\n") == 0, "one-line error")
check("needs about" in err and "ulimit -v" in err,
      "the message gives the estimate and names the limit")

if failures:
    print("%d failure(s)" % len(failures))
    sys.exit(1)
print("OK")
