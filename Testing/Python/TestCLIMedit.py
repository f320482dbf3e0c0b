# SPDX-License-Identifier: BSD-3-Clause
"""The anisovoronoi tool used the MMG way: `anisovoronoi in.mesh --sol in.sol -o out.mesh`
(the .sol is the metric, no --metric needed), output as Medit .mesh + .sol read back and
compared with the VTK output of the same run bit for bit, the binary .meshb/.solb path
(output, then input again), --format medit, and the command-line errors (exit status 2)."""
import os
import subprocess
import tempfile

from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
from anisovoronoi import vtkAnisoMeditReader

CLI = os.path.join(os.environ["AV_BUILD"], "bin", "anisovoronoi")
DATA = os.environ["AV_DATA"]
SMALL = ["--dim", "3", "--iterations", "10", "--sites", "120", "--sample-iterations", "20",
         "--quiet"]
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAILED:", what)


def run(args, cwd):
    return subprocess.run([CLI] + args, cwd=cwd, capture_output=True, text=True, timeout=300)


def read_medit(mesh, sol):
    r = vtkAnisoMeditReader()
    r.SetFileName(mesh)
    r.SetSolFileName(sol)
    r.Update()
    return r.GetOutput()


def tensors(ds):
    a = ds.GetPointData().GetArray("Metric")
    return [a.GetTuple(i) for i in range(a.GetNumberOfTuples())]


with tempfile.TemporaryDirectory() as work:
    mesh_in = os.path.join(DATA, "gaussian2d.mesh")
    sol_in = os.path.join(DATA, "gaussian2d.sol")

    # MMG style: the .sol is the metric; only out.mesh and out.sol are written.
    p = run([mesh_in, "--sol", sol_in, "-o", "out.mesh"] + SMALL, work)
    check(p.returncode == 0, "in.mesh --sol in.sol -o out.mesh exits 0 (%s)" % p.stderr.strip())
    check(sorted(os.listdir(work)) == ["out.mesh", "out.sol"],
          "only out.mesh and out.sol written: %s" % sorted(os.listdir(work)))
    out = read_medit(os.path.join(work, "out.mesh"), os.path.join(work, "out.sol"))
    check(out.GetNumberOfPoints() >= 120 and out.GetNumberOfCells() > 120,
          "out.mesh reads back: %d points, %d triangles" % (out.GetNumberOfPoints(),
                                                              out.GetNumberOfCells()))
    m = tensors(out)
    check(len(m) == out.GetNumberOfPoints(), "out.sol has one tensor per vertex")
    # 2D metric in VTK order: XX, YY > 0, det > 0, and no z part.
    check(all(t[0] > 0 and t[1] > 0 and t[0] * t[1] - t[3] ** 2 > 0 and t[2] == 0 for t in m),
          "out.sol holds SPD 2D tensors")

    # The same run with the VTK output and --format medit: the Medit files hold exactly the
    # mesh.vtu points, triangles and Metric (Medit tensor order converted back).
    p = run([mesh_in, "--sol", sol_in, "--output-dir", "both", "--format", "medit"] + SMALL, work)
    check(p.returncode == 0, "--format medit exits 0 (%s)" % p.stderr.strip())
    both = os.path.join(work, "both")
    check({"mesh.vtu", "mesh.mesh", "mesh.sol", "report.json"} <= set(os.listdir(both)),
          "--format medit adds mesh.mesh and mesh.sol: %s" % sorted(os.listdir(both)))
    r = vtkXMLUnstructuredGridReader()
    r.SetFileName(os.path.join(both, "mesh.vtu"))
    r.Update()
    vtu = r.GetOutput()
    medit = read_medit(os.path.join(both, "mesh.mesh"), os.path.join(both, "mesh.sol"))
    check(medit.GetNumberOfPoints() == vtu.GetNumberOfPoints() and
          medit.GetNumberOfCells() == vtu.GetNumberOfCells(), "Medit files match mesh.vtu sizes")
    check(all(medit.GetPoint(i) == vtu.GetPoint(i) for i in range(vtu.GetNumberOfPoints())),
          "Medit points equal mesh.vtu's bit for bit")
    check(all([medit.GetCell(c).GetPointId(k) for k in range(3)] ==
              [vtu.GetCell(c).GetPointId(k) for k in range(3)]
              for c in range(vtu.GetNumberOfCells())), "Medit triangles equal mesh.vtu's")
    check(tensors(medit) == tensors(vtu), "mesh.sol equals mesh.vtu's Metric bit for bit")
    # Same command, same seed: -o out.mesh wrote the same mesh.
    check(out.GetNumberOfPoints() == vtu.GetNumberOfPoints() and tensors(out) == tensors(vtu),
          "-o out.mesh and --format medit write the same mesh")

    # Binary: -o out.meshb writes .meshb + .solb, which read back equal to the ASCII files,
    # and which the tool takes as input again.
    p = run([mesh_in, "--sol", sol_in, "-o", "bin/out.meshb"] + SMALL, work)
    check(p.returncode != 0, "-o into a missing folder fails")
    os.makedirs(os.path.join(work, "bin"))
    p = run([mesh_in, "--sol", sol_in, "-o", "bin/out.meshb"] + SMALL, work)
    check(p.returncode == 0, "-o out.meshb exits 0 (%s)" % p.stderr.strip())
    binary = read_medit(os.path.join(work, "bin", "out.meshb"), os.path.join(work, "bin", "out.solb"))
    with open(os.path.join(work, "bin", "out.meshb"), "rb") as f:
        check(f.read(8) == b"\x01\x00\x00\x00\x02\x00\x00\x00", ".meshb starts with code 1, version 2")
    check(binary.GetNumberOfPoints() == vtu.GetNumberOfPoints() and tensors(binary) == tensors(vtu),
          ".meshb/.solb read back equal to the ASCII output")
    p = run([os.path.join("bin", "out.meshb"), "--sol", os.path.join("bin", "out.solb"),
             "-o", "again.mesh"] + SMALL, work)
    check(p.returncode == 0, ".meshb/.solb as input (%s)" % p.stderr.strip())

    # Command-line errors: exit status 2 and a one-line reason.
    for args, what in [([mesh_in, "-o", "x.mesh"] + SMALL, "no metric"),
                       ([mesh_in, "--sol", sol_in] + SMALL, "no output"),
                       ([mesh_in, "--sol", sol_in, "-o", "x.mesh", "--format", "medit"] + SMALL,
                        "--format medit without --output-dir"),
                       ([mesh_in, "--sol", sol_in, "--output-dir", "y", "--format", "stl"],
                        "unknown format")]:
        p = run(args, work)
        check(p.returncode == 2 and p.stderr.count("\n") == 1 and "error" in p.stderr,
              "%s: exit 2 with one line (got %d: %s)" % (what, p.returncode, p.stderr.strip()))

if failures:
    raise SystemExit("TestCLIMedit: %d failure(s)" % len(failures))
print("TestCLIMedit: OK")
