# SPDX-License-Identifier: BSD-3-Clause
"""vtkAnisoMeshQuality's surface fidelity measures (paper §6.3) from Python: topology,
self-intersections, and with a reference surface on input 1 the Hausdorff distance and the
flipped triangles, each with a known answer; the warning / error paths."""
import math
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import VTK_TETRA, vtkPolyData, vtkUnstructuredGrid
from vtkmodules.vtkFiltersCore import vtkAppendPolyData
from vtkmodules.vtkFiltersGeneral import vtkTransformPolyDataFilter
from vtkmodules.vtkCommonTransforms import vtkTransform
from vtkmodules.vtkFiltersSources import vtkSphereSource

from anisovoronoi import vtkAnisoMeshQuality

# The shared check() / Messages helpers (Testing/Python/vtk_test_checks.py).
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), *[os.pardir] * 4,
                                "Testing", "Python"))
from vtk_test_checks import Messages, check, finish  # noqa: E402


def with_metric(data):
    """`data` with an identity "Metric" point array (6 components)."""
    m = numpy_to_vtk(np.tile([1.0, 1.0, 1.0, 0.0, 0.0, 0.0], (data.GetNumberOfPoints(), 1)),
                     deep=True)
    m.SetName("Metric")
    data.GetPointData().AddArray(m)
    return data


def sphere(radius, theta=40, phi=30):
    s = vtkSphereSource()
    s.SetRadius(radius)
    s.SetThetaResolution(theta)
    s.SetPhiResolution(phi)
    s.Update()
    out = vtkPolyData()
    out.DeepCopy(s.GetOutput())
    return out


def field(data, name):
    a = data.GetFieldData().GetArray(name)
    return a.GetTuple1(0) if a is not None else None


def run(mesh, reference=None, configure=None):
    q = vtkAnisoMeshQuality()
    q.SetInputData(with_metric(mesh))
    if reference is not None:
        q.SetReferenceSurfaceData(reference)
    if configure:
        configure(q)
    msgs = Messages(q)
    ok = q.GetExecutive().Update()
    return q, ok, msgs


# The same sphere as its own reference: distance 0, nothing flipped, chi 2 on both sides.
mesh = sphere(0.5)
q, ok, msgs = run(mesh, sphere(0.5))
out = q.GetOutput()
check(ok == 1 and not msgs.errors, "sphere runs: %s" % msgs.errors)
check(field(out, "euler") == 2 and field(out, "input_euler") == 2, "sphere: chi 2")
check(field(out, "boundary_loops") == 0 and field(out, "components") == 1, "closed, one piece")
check(field(out, "self_intersections") == 0 and field(out, "nonmanifold_edges") == 0,
      "sphere is embedded and manifold")
check(field(out, "hausdorff") is not None and field(out, "hausdorff") < 1e-9,
      "identical surfaces: Hausdorff 0 (%r)" % field(out, "hausdorff"))
check(field(out, "flipped") == 0 and q.GetNumberOfFlipped() == 0, "no flipped triangle")

# Against a sphere of radius 0.55: every point of the r = 0.5 mesh is >= 0.05 away, at most
# 0.05 + the chord sagitta; in % of the reference's diagonal 1.1 sqrt(3).
q, ok, _ = run(sphere(0.5), sphere(0.55, 80, 60))
h = q.GetHausdorffPercent()
low = 100 * 0.05 / (1.1 * math.sqrt(3))
check(ok == 1 and low - 1e-6 < h < low * 1.25, "Hausdorff to a larger sphere: %r (>= %r)" % (h, low))
check(abs(field(q.GetOutput(), "hausdorff") - h) < 1e-12, "field data = getter")

# One reversed triangle is flipped, and marked in the cell data.
flipped_mesh = sphere(0.5)
polys = flipped_mesh.GetPolys()
ids = vtk_to_numpy(polys.GetConnectivityArray())
ids[3 * 7 + 1], ids[3 * 7 + 2] = ids[3 * 7 + 2], ids[3 * 7 + 1]
polys.Modified()
q, ok, _ = run(flipped_mesh, sphere(0.5))
flags = vtk_to_numpy(q.GetOutput().GetCellData().GetArray("Flipped"))
check(ok == 1 and q.GetNumberOfFlipped() == 1 and flags[7] == 1 and flags.sum() == 1,
      "one reversed triangle flipped: %r" % q.GetNumberOfFlipped())

# No reference: topology and self-intersections only. Two overlapping spheres intersect.
tr = vtkTransform()
tr.Translate(0.3, 0, 0)
moved = vtkTransformPolyDataFilter()
moved.SetInputData(sphere(0.5))
moved.SetTransform(tr)
both = vtkAppendPolyData()
both.AddInputData(sphere(0.5))
both.AddInputConnection(moved.GetOutputPort())
both.Update()
q, ok, _ = run(both.GetOutput())
out = q.GetOutput()
check(ok == 1 and field(out, "hausdorff") is None and q.GetHausdorffPercent() == -1,
      "no reference: no Hausdorff")
check(field(out, "components") == 2 and field(out, "euler") == 4, "two spheres: chi 4")
check(field(out, "self_intersections") > 10 and q.GetNumberOfSelfIntersections() > 10,
      "overlapping spheres intersect: %r" % field(out, "self_intersections"))

# SurfaceFidelity off: none of the fidelity figures.
q, ok, _ = run(sphere(0.5), sphere(0.5), lambda f: f.SurfaceFidelityOff())
check(ok == 1 and field(q.GetOutput(), "euler") is None and q.GetHausdorffPercent() == -1,
      "SurfaceFidelity off")


def one_tet():
    g = vtkUnstructuredGrid()
    pts = vtkPoints()
    for p in [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]:
        pts.InsertNextPoint(p)
    g.SetPoints(pts)
    g.InsertNextCell(VTK_TETRA, 4, [0, 1, 2, 3])
    return g


# A tetrahedral mesh with a reference: quality as usual, the reference ignored with a warning.
q, ok, msgs = run(one_tet(), sphere(0.5))
check(ok == 1 and field(q.GetOutput(), "G_avg") is not None and
      field(q.GetOutput(), "euler") is None, "tet mesh: no surface measures")
check(any("reference surface is ignored" in w for w in msgs.warnings),
      "tet mesh: warning about the reference: %s" % msgs.warnings)

# A reference that is not a surface, or is empty: a clear error and a failed update.
q, ok, msgs = run(sphere(0.5), one_tet())
check(ok == 0 and any("reference surface" in e and "tetrahedra" in e for e in msgs.errors),
      "tet reference rejected: %s" % msgs.errors)
q, ok, msgs = run(sphere(0.5), vtkPolyData())
check(ok == 0 and any("empty" in e for e in msgs.errors), "empty reference rejected: %s" % msgs.errors)

finish("TestMeshQualityFidelity")
