# SPDX-License-Identifier: BSD-3-Clause
"""The anisovoronoi command-line tool: a small run end to end (files read back, report keys,
Voronoi partition, nothing written outside the output folder) and its error paths (one-line
message, non-zero exit, fast)."""
import json
import os
import subprocess
import sys
import tempfile
import time

from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLUnstructuredGridReader

CLI = os.path.join(os.environ["AV_BUILD"], "bin", "anisovoronoi")
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAILED:", what)


def run(args, cwd):
    t0 = time.time()
    p = subprocess.run([CLI] + args, cwd=cwd, capture_output=True, text=True, timeout=300)
    return p, time.time() - t0


def read(path):
    r = vtkXMLPolyDataReader() if path.endswith(".vtp") else vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    return r.GetOutput()


with tempfile.TemporaryDirectory() as tmp:
    work = os.path.join(tmp, "work")
    os.makedirs(work)
    out = os.path.join(work, "out")
    p, _ = run(["--metric", "preset:cube1", "--resolution", "6", "--sites", "60", "--dim", "5",
                "--iterations", "10", "--max-iterations", "0", "--sample-iterations", "10",
                "--shrink", "1",
                "--output-dir", "out", "--quiet"], work)
    check(p.returncode == 0, "small run exits 0 (stderr: %s)" % p.stderr.strip())
    check(sorted(os.listdir(work)) == ["out"], "nothing written outside the output folder")
    names = sorted(os.listdir(out))
    check(names == sorted(["embedded.vtu", "sites.vtp", "voronoi.vtu", "voronoi_faces.vtp",
                           "mesh.vtu", "energy.csv", "report.json"]), "output files: %s" % names)
    report = json.load(open(os.path.join(out, "report.json")))
    for key in ["input_vertices", "L_avg", "L_max", "embed_seconds", "sample_seconds",
                "rvd_seconds", "rdt_seconds", "mesh_seconds", "G_min", "G_avg", "theta_min",
                "theta_avg", "pct_bad", "inverted", "edges_in_unit_range", "rvd_volume_error"]:
        check(key in report and report[key] is not None, "report has " + key)
    check(report["input_vertices"] == 216, "6^3 input vertices")
    check(report["rvd_volume_error"] < 1e-9, "Voronoi cells partition the cube")
    emb = read(os.path.join(out, "embedded.vtu"))
    check(emb.GetNumberOfPoints() == 216, "embedded.vtu reads back")
    check(emb.GetPointData().GetArray("Embedding").GetNumberOfComponents() == 5,
          "embedding array has 5 components")
    cells = read(os.path.join(out, "voronoi.vtu"))
    check(cells.GetNumberOfCells() == 60, "one Voronoi cell per site (read back)")
    vol = sum(cells.GetCellData().GetArray("Measure").GetValue(i)
              for i in range(cells.GetNumberOfCells()))
    check(abs(vol - 1.0) < 1e-9, "cell volumes sum to the cube volume (%r)" % vol)
    mesh = read(os.path.join(out, "mesh.vtu"))
    check(mesh.GetNumberOfPoints() == 60, "mesh vertices are the sites")
    check(len(open(os.path.join(out, "energy.csv")).read().splitlines()) == 12,
          "energy.csv has the initial state + 10 iterations")

    # A Medit mesh + .sol tensor metric (bundled) through the CLI.
    data = os.environ["AV_DATA"]
    p, _ = run([os.path.join(data, "gaussian2d.mesh"), "--sol", os.path.join(data, "gaussian2d.sol"),
                "--metric", "metric:Metric", "--dim", "3", "--iterations", "20", "--sites", "150",
                "--output-dir", "medit", "--quiet"], work)
    check(p.returncode == 0, "Medit input runs (stderr: %s)" % p.stderr.strip()[-300:])
    if p.returncode == 0:
        r = json.load(open(os.path.join(work, "medit", "report.json")))
        check(r["input_vertices"] == 441 and r["voronoi_cells"] == 150, "Medit run sizes")
        check(r["L_avg"] < 5.0, "Medit run embeds the Gaussian metric (L_avg %r)" % r["L_avg"])
        check(r["rvd_volume_error"] < 1e-9, "Medit run: cells partition the square")
        check(r["hausdorff"] is None and r["euler"] is None, "2D domain: no surface measures")

    # A closed surface (OFF) with the curvature metric: the dual mesh of a sphere-like
    # surface with V vertices must have 2V - 4 triangles (Euler).
    from vtkmodules.vtkFiltersSources import vtkSphereSource
    sphere = vtkSphereSource()
    sphere.SetThetaResolution(40)
    sphere.SetPhiResolution(30)
    sphere.Update()
    sp = sphere.GetOutput()
    off = os.path.join(tmp, "sphere.off")
    with open(off, "w") as f:
        f.write("OFF\n%d %d 0\n" % (sp.GetNumberOfPoints(), sp.GetNumberOfCells()))
        for i in range(sp.GetNumberOfPoints()):
            f.write("%r %r %r\n" % sp.GetPoint(i))
        for c in range(sp.GetNumberOfCells()):
            ids = sp.GetCell(c).GetPointIds()
            f.write("3 %d %d %d\n" % (ids.GetId(0), ids.GetId(1), ids.GetId(2)))
    p, _ = run([off, "--metric", "curvature", "--sites", "120", "--iterations", "20",
                "--output-dir", "surface", "--quiet"], work)
    check(p.returncode == 0, "OFF surface runs (stderr: %s)" % p.stderr.strip()[-300:])
    if p.returncode == 0:
        r = json.load(open(os.path.join(work, "surface", "report.json")))
        check(r["voronoi_cells"] == 120, "one cell per site on the surface")
        check(r["mesh_elements"] == 2 * 120 - 4 and r["nonmanifold_faces"] == 0,
              "closed dual surface mesh: %r triangles" % r["mesh_elements"])
        # Fidelity to the input surface (paper §6.3), in report.json and mesh.vtu's field data.
        check(r["euler"] == 2 and r["input_euler"] == 2 and r["boundary_loops"] == 0,
              "surface report: chi %r (input %r)" % (r["euler"], r["input_euler"]))
        check(r["self_intersections"] == 0 and r["flipped"] == 0 and r["nonmanifold_edges"] == 0,
              "surface report: embedded, oriented, manifold")
        check(r["hausdorff"] is not None and 0 < r["hausdorff"] < 3.0 and
              r["hausdorff"] >= max(r["hausdorff_to_input"], r["hausdorff_from_input"]) - 1e-12,
              "surface report: Hausdorff %r %% of the diagonal" % r["hausdorff"])

    # Feature lines from a Medit file's triangle references (--feature-patches Ref): a sphere
    # whose hemispheres have refs 1 and 2 gets sites on the equator, none without the option.
    halves = vtkSphereSource()
    halves.SetThetaResolution(40)
    halves.SetPhiResolution(31)  # a ring of points at z = 0
    halves.Update()
    hp = halves.GetOutput()
    medit = os.path.join(tmp, "halves.mesh")
    with open(medit, "w") as f:
        f.write("MeshVersionFormatted 2\nDimension 3\nVertices\n%d\n" % hp.GetNumberOfPoints())
        for i in range(hp.GetNumberOfPoints()):
            f.write("%r %r %r 0\n" % hp.GetPoint(i))
        f.write("Triangles\n%d\n" % hp.GetNumberOfCells())
        for c in range(hp.GetNumberOfCells()):
            ids = [hp.GetCell(c).GetPointIds().GetId(k) for k in range(3)]
            z = sum(hp.GetPoint(i)[2] for i in ids) / 3.0
            f.write("%d %d %d %d\n" % (ids[0] + 1, ids[1] + 1, ids[2] + 1, 1 if z > 0 else 2))
        f.write("End\n")
    for patches in (False, True):
        args = [medit, "--metric", "curvature", "--sites", "200", "--output-dir",
                "halves%d" % patches, "--quiet", "--keep-feature-sites"]
        p, _ = run(args + (["--feature-patches", "Ref"] if patches else []), work)
        check(p.returncode == 0, "Medit surface runs (stderr: %s)" % p.stderr.strip()[-300:])
        if p.returncode == 0:
            r = json.load(open(os.path.join(work, "halves%d" % patches, "report.json")))
            if patches:
                check(r["feature_line_sites"] > 10 and r["feature_edges_required"] >= r["feature_line_sites"],
                      "--feature-patches Ref: %r sites on the equator, %r crease pairs" % (
                          r["feature_line_sites"], r["feature_edges_required"]))
                check(r["euler"] == 2 and r["flipped"] == 0 and r["self_intersections"] == 0,
                      "--feature-patches Ref: a valid sphere")
            else:
                check(r["feature_line_sites"] == 0, "no feature lines on a sphere by angle")
    # The same equator as Medit Edges + Ridges (as MMG writes them): read as feature lines.
    ring = set(i for i in range(hp.GetNumberOfPoints()) if abs(hp.GetPoint(i)[2]) < 1e-12)
    ring_edges = set()
    for c in range(hp.GetNumberOfCells()):
        ids = [hp.GetCell(c).GetPointIds().GetId(k) for k in range(3)]
        for k in range(3):
            a_, b_ = ids[k], ids[(k + 1) % 3]
            if a_ in ring and b_ in ring:
                ring_edges.add((min(a_, b_), max(a_, b_)))
    ridged = os.path.join(tmp, "ridges.mesh")
    with open(medit) as src, open(ridged, "w") as f:
        body = src.read().replace("End\n", "")
        f.write(body + "Edges\n%d\n" % len(ring_edges))
        for a_, b_ in sorted(ring_edges):
            f.write("%d %d 0\n" % (a_ + 1, b_ + 1))
        f.write("Ridges\n%d\n" % len(ring_edges))
        f.write("".join("%d\n" % (i + 1) for i in range(len(ring_edges))) + "End\n")
    p, _ = run([ridged, "--metric", "curvature", "--sites", "200", "--output-dir", "ridges",
                "--quiet", "--keep-feature-sites"], work)
    check(p.returncode == 0, "Medit surface with Ridges runs (stderr: %s)" % p.stderr.strip()[-300:])
    if p.returncode == 0:
        r = json.load(open(os.path.join(work, "ridges", "report.json")))
        check(len(ring_edges) == 40 and r["feature_line_sites"] > 10,
              "Ridges: %r sites on the %r ridge edges" % (r["feature_line_sites"], len(ring_edges)))
        check(r["euler"] == 2 and r["flipped"] == 0, "Ridges: a valid sphere")
    p, _ = run([medit, "--metric", "curvature", "--feature-corners", "Ref", "--output-dir", "e9"], work)
    check(p.returncode == 2 and "--feature-patches" in p.stderr, "--feature-corners alone is refused")

    # Error paths: exit != 0, one line on stderr naming the problem, within seconds.
    bad_mesh = os.path.join(tmp, "bad.mesh")
    with open(bad_mesh, "w") as f:
        f.write("MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n")
    nan_vtk = os.path.join(tmp, "nan.vtk")
    with open(nan_vtk, "w") as f:
        f.write("# vtk DataFile Version 3.0\nnan\nASCII\nDATASET UNSTRUCTURED_GRID\n"
                "POINTS 4 double\n0 0 0\n1 0 0\n0 1 0\n0 0 1\nCELLS 1 5\n4 0 1 2 3\n"
                "CELL_TYPES 1\n10\nPOINT_DATA 4\nTENSORS T double\n"
                "1 0 0 0 1 0 0 0 1\nnan 0 0 0 1 0 0 0 1\n1 0 0 0 1 0 0 0 1\n"
                "1 0 0 0 1 0 0 0 1\n")
    # A NaN that survives reading (XML): the metric stage must reject it.
    from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkUnstructuredGrid, VTK_TETRA
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter
    grid = vtkUnstructuredGrid()
    pts = vtkPoints()
    for x in [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]:
        pts.InsertNextPoint(*x)
    grid.SetPoints(pts)
    grid.InsertNextCell(VTK_TETRA, 4, [0, 1, 2, 3])
    t = vtkDoubleArray()
    t.SetName("T")
    t.SetNumberOfComponents(6)
    for i in range(4):
        t.InsertNextTuple([float("nan") if i == 1 else 1.0, 1, 1, 0, 0, 0])
    grid.GetPointData().AddArray(t)
    nan_vtu = os.path.join(tmp, "nan.vtu")
    w = vtkXMLUnstructuredGridWriter()
    w.SetInputData(grid)
    w.SetFileName(nan_vtu)
    w.SetDataModeToBinary()
    w.Write()
    cases = [
        (["missing.vtu", "--metric", "tensor:S", "--output-dir", "e1"], "no such file"),
        (["--metric", "preset:nope", "--output-dir", "e2"], "unknown preset"),
        (["--metric", "banana", "--output-dir", "e3"], "--metric"),
        (["--metric", "preset:cube1"], "--output-dir"),
        (["--metric", "preset:cube1", "--sites", "0", "--output-dir", "e4"], "--sites"),
        ([bad_mesh, "--metric", "metric:Metric", "--output-dir", "e5"], "bad.mesh:4:"),
        ([nan_vtk, "--metric", "tensor:T", "--output-dir", "e6"], "nan"),
        ([nan_vtu, "--metric", "tensor:Missing", "--output-dir", "e7"], "Missing"),
        ([nan_vtu, "--metric", "tensor:T", "--output-dir", "e9"], "NaN"),
        (["--metric", "preset:cube1", "--resolution", "6", "--sites", "100000",
          "--output-dir", "e8"], "sites"),
    ]
    for args, expect in cases:
        p, seconds = run(args, work)
        lines = [l for l in p.stderr.splitlines() if l.startswith("anisovoronoi: error:")]
        check(p.returncode != 0, "%s: non-zero exit" % args)
        check(len(lines) == 1 and expect.lower() in lines[0].lower(),
              "%s: one error line mentioning %r, got %r" % (args, expect, p.stderr.strip()[-300:]))
        check(seconds < 30, "%s: fails fast (%.1f s)" % (args, seconds))

print("%d failure(s)" % len(failures))
sys.exit(1 if failures else 0)
