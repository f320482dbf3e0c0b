# SPDX-License-Identifier: BSD-3-Clause
"""The CLI's output writing: each file is written under a temporary name and renamed (an
existing output is replaced, never rewritten in place, and no temporary file is left), and a
run never overwrites its input, also through a symbolic link or a hard link (clear message,
non-zero exit, input unchanged)."""
import hashlib
import os
import subprocess
import sys
import tempfile

CLI = os.path.join(os.environ["AV_BUILD"], "bin", "anisovoronoi")
failures = []
SMALL = ["--metric", "preset:cube1", "--resolution", "6", "--sites", "40", "--dim", "5",
         "--iterations", "5", "--sample-iterations", "5", "--quiet"]


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAILED:", what)


def run(args, cwd):
    return subprocess.run([CLI] + args, cwd=cwd, capture_output=True, text=True, timeout=300)


def digest(path):
    return hashlib.sha256(open(path, "rb").read()).hexdigest()


with tempfile.TemporaryDirectory() as tmp:
    out = os.path.join(tmp, "out")
    os.makedirs(out)
    # A file elsewhere that shares its inode with the future mesh.vtu: a writer that opens the
    # existing output in place rewrites it; write-then-rename leaves it alone.
    sentinel = os.path.join(tmp, "sentinel.vtu")
    with open(sentinel, "w") as f:
        f.write("not a mesh\n")
    os.link(sentinel, os.path.join(out, "mesh.vtu"))
    p = run(SMALL + ["--output-dir", "out"], tmp)
    check(p.returncode == 0, "small run exits 0 (%s)" % p.stderr.strip()[-300:])
    check(open(sentinel).read() == "not a mesh\n",
          "an existing output is replaced by rename, not rewritten in place")
    check(os.stat(os.path.join(out, "mesh.vtu")).st_ino != os.stat(sentinel).st_ino,
          "mesh.vtu is a new file")
    check(os.path.getsize(os.path.join(out, "mesh.vtu")) > 1000, "mesh.vtu was written")
    left = [n for n in os.listdir(out) if ".tmp-" in n]
    check(not left, "no temporary file left: %s" % left)

    # The input is never overwritten: out/embedded.vtu as the input, out as the output folder.
    src = os.path.join(out, "embedded.vtu")
    before = digest(src)
    p = run([src, "--metric", "preset:cube1", "--sites", "30", "--quiet", "--output-dir", "out"],
            tmp)
    check(p.returncode > 0, "same folder: refused with an exit status")
    check("is the input file" in p.stderr, "same folder: clear message (%s)" % p.stderr.strip())
    check(p.stderr.count("\n") <= 1, "same folder: one line")
    # Through a symbolic link to the output folder.
    os.symlink(out, os.path.join(tmp, "outlink"))
    p = run([src, "--metric", "preset:cube1", "--sites", "30", "--quiet", "--output-dir",
             "outlink"], tmp)
    check(p.returncode > 0 and "is the input file" in p.stderr,
          "symlinked output folder: refused (%d, %s)" % (p.returncode, p.stderr.strip()))
    # Through a hard link: the input is another name of an output file.
    other = os.path.join(tmp, "other")
    os.makedirs(other)
    hard = os.path.join(tmp, "input-hardlink.vtu")
    os.link(src, hard)
    os.link(src, os.path.join(other, "embedded.vtu"))
    p = run([hard, "--metric", "preset:cube1", "--sites", "30", "--quiet", "--output-dir",
             "other"], tmp)
    check(p.returncode > 0 and "is the input file" in p.stderr,
          "hard-linked input: refused (%d, %s)" % (p.returncode, p.stderr.strip()))
    check(digest(src) == before, "the input is unchanged")

if failures:
    print("%d failure(s)" % len(failures))
    sys.exit(1)
print("OK")
