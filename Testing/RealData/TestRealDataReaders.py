# SPDX-License-Identifier: BSD-3-Clause
"""Every input of scripts/make-real-data.sh read back with the project's readers: the expected
point and cell counts, finite fields, and tensors that vtkAnisoTensorToMetric turns into a
finite SPD metric at every point; the .frd copy of each flow matches its .vtu. Needs
AV_REAL_DATA_DIR (set by CTest); fails naming the missing file and the command otherwise."""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLUnstructuredGridReader

from anisovoronoi import vtkAnisoFRDReader, vtkAnisoSimplexMesh, vtkAnisoTensorToMetric

DATA = os.environ.get("AV_REAL_DATA_DIR", "")
failures = []

# file: (points, cells, tensor array, step index)
FRD = {
    "compressor.frd": (3150, 560, "STRESS", 0),
    "ccx-rotor.frd": (2656, 368, "STRESS", 0),
    "ccx-segmenttet.frd": (5512, 2978, "STRESS", 1),
    "ccx-cubef2f1.frd": (2960, 632, "STRESS", 0),
    "ccx-hueeber1.frd": (17524, 8500, "STRESS", 0),
    "foam-squarebend.frd": (17061, 14000, "SRATE", 0),
    "foam-mixer.frd": (8750, 7200, "SRATE", 0),
}
# file: (points, cells, velocity array)
VTU = {
    "foam-squarebend.vtu": (17061, 14000, "U"),
    "foam-mixer.vtu": (8750, 7200, "Urel"),
}
# name: (points, triangles, boundary edges > 0)
SURFACES = {
    "turbine": (9210, 18460, False),
    "knot1": (3200, 6400, False),
    "mushroom": (2337, 4608, True),
    "fandisk_large": (15843, 31682, False),
}


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAILED:", what)


def require(path):
    if not os.path.isfile(path):
        print("real data missing: %s\n  make it with: scripts/make-real-data.sh %s" % (path, DATA))
        sys.exit(1)


def point_array(ds, name):
    a = ds.GetPointData().GetArray(name)
    return None if a is None else vtk_to_numpy(a).astype(np.float64)


def check_metric_of(ds, array, label):
    """The tensor -> metric filter's defaults (the CLI's tensor:ARRAY) on the split mesh."""
    split = vtkAnisoSimplexMesh()
    split.SetInputData(ds)
    m = vtkAnisoTensorToMetric()
    m.SetInputConnection(split.GetOutputPort())
    m.SetInputArrayToProcess(0, 0, 0, 0, array)
    m.SetGradation(False)  # the conversion itself is under test, not the preparation
    m.Update()
    metric = point_array(m.GetOutput(), "Metric")
    check(metric is not None, label + ": no Metric output")
    if metric is None:
        return
    t = metric
    full = np.stack([t[:, 0], t[:, 3], t[:, 5], t[:, 3], t[:, 1], t[:, 4], t[:, 5], t[:, 4],
                     t[:, 2]], axis=1).reshape(-1, 3, 3)
    check(np.all(np.isfinite(full)), label + ": metric not finite")
    lo = np.linalg.eigvalsh(full)[:, 0].min()
    check(lo > 0.0, "%s: metric not SPD (smallest eigenvalue %g)" % (label, lo))


def read_frd(name, step):
    r = vtkAnisoFRDReader()
    r.SetFileName(os.path.join(DATA, name))
    r.SetStepIndex(step)
    r.Update()
    return r.GetOutput()


def check_frd(name, points, cells, array, step):
    require(os.path.join(DATA, name))
    ds = read_frd(name, step)
    check(ds.GetNumberOfPoints() == points, "%s: %d points" % (name, ds.GetNumberOfPoints()))
    check(ds.GetNumberOfCells() == cells, "%s: %d cells" % (name, ds.GetNumberOfCells()))
    t = point_array(ds, array)
    check(t is not None and t.shape == (points, 6), name + ": no 6-component " + array)
    if t is None:
        return
    check(np.all(np.isfinite(t)), name + ": " + array + " not finite")
    check(np.abs(t).max() > 0.0, name + ": " + array + " is zero")
    check_metric_of(ds, array, name)
    print("%s: %d points, %d cells, |%s| max %.4g" % (name, points, cells, array, np.abs(t).max()))


def check_vtu(name, points, cells, velocity):
    require(os.path.join(DATA, name))
    r = vtkXMLUnstructuredGridReader()
    r.SetFileName(os.path.join(DATA, name))
    r.Update()
    ds = r.GetOutput()
    check(ds.GetNumberOfPoints() == points, "%s: %d points" % (name, ds.GetNumberOfPoints()))
    check(ds.GetNumberOfCells() == cells, "%s: %d cells" % (name, ds.GetNumberOfCells()))
    check({ds.GetCellType(i) for i in range(ds.GetNumberOfCells())} == {12},
          name + ": not all hexahedra")
    s, u = point_array(ds, "StrainRate"), point_array(ds, velocity)
    check(s is not None and s.shape == (points, 6), name + ": no 6-component StrainRate")
    check(u is not None and u.shape == (points, 3), name + ": no velocity " + velocity)
    if s is None or u is None:
        return
    check(np.all(np.isfinite(s)) and np.all(np.isfinite(u)), name + ": fields not finite")
    check(np.abs(u).max() > 0.0 and np.abs(s).max() > 0.0, name + ": zero flow")
    check_metric_of(ds, "StrainRate", name)
    # the .frd copy (E12.5: 6 significant digits) holds the same points and strain rates
    frd = read_frd(name[:-4] + ".frd", 0)
    p0 = vtk_to_numpy(ds.GetPoints().GetData()).astype(np.float64)
    p1 = vtk_to_numpy(frd.GetPoints().GetData()).astype(np.float64)
    scale = np.abs(p0).max()
    check(p1.shape == p0.shape and np.abs(p1 - p0).max() <= 1e-5 * scale,
          name + ": .frd points differ from the .vtu")
    s1 = point_array(frd, "SRATE")
    check(s1 is not None and np.abs(s1 - s).max() <= 1e-5 * np.abs(s).max(),
          name + ": .frd SRATE differs from the .vtu StrainRate")
    print("%s: %d points, %d hexahedra, |S| max %.4g" % (name, points, cells, np.abs(s).max()))


def off_counts(path):
    with open(path) as f:
        tok = f.read().split()
    nv, nf = int(tok[1]), int(tok[2])
    edges = {}
    i = 4 + 3 * nv
    for _ in range(nf):
        n = int(tok[i])
        ids = [int(v) for v in tok[i + 1:i + 1 + n]]
        i += 1 + n
        for a in range(n):
            e = tuple(sorted((ids[a], ids[(a + 1) % n])))
            edges[e] = edges.get(e, 0) + 1
    return nv, nf, sum(1 for c in edges.values() if c == 1)


def check_surface(name, points, triangles, open_boundary):
    require(os.path.join(DATA, name + ".off"))
    require(os.path.join(DATA, name + ".vtp"))
    nv, nf, boundary = off_counts(os.path.join(DATA, name + ".off"))
    check((nv, nf) == (points, triangles), "%s.off: %d points, %d faces" % (name, nv, nf))
    check((boundary > 0) == open_boundary, "%s.off: %d boundary edges" % (name, boundary))
    r = vtkXMLPolyDataReader()
    r.SetFileName(os.path.join(DATA, name + ".vtp"))
    r.Update()
    ds = r.GetOutput()
    check(ds.GetNumberOfPoints() == points and ds.GetNumberOfPolys() == triangles,
          "%s.vtp: %d points, %d polygons" % (name, ds.GetNumberOfPoints(), ds.GetNumberOfPolys()))
    print("%s: %d points, %d triangles, %d boundary edges" % (name, nv, nf, boundary))


def main():
    if not DATA:
        print("AV_REAL_DATA_DIR is not set (CTest sets it from the CMake cache variable)")
        return 1
    for name, (p, c, a, s) in FRD.items():
        check_frd(name, p, c, a, s)
    for name, (p, c, u) in VTU.items():
        check_vtu(name, p, c, u)
    for name, (p, t, o) in SURFACES.items():
        check_surface(name, p, t, o)
    if failures:
        print("%d check(s) failed" % len(failures))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
