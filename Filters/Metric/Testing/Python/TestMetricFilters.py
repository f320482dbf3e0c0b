# SPDX-License-Identifier: BSD-3-Clause
"""The metric filters from Python (/usr/bin/python3 with ParaView's vtkmodules):
vtkAnisoTensorToMetric, vtkAnisoSimplexMesh and vtkAnisoCurvatureMetric, chained with
vtkAnisoAnalyticMetricSource and vtkAnisoEmbedding. Asserts values, not only that it ran."""
import math
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkImageData, vtkPolyData
from vtkmodules.vtkFiltersCore import vtkCleanPolyData, vtkTriangleFilter
from vtkmodules.vtkFiltersSources import vtkCubeSource, vtkPlaneSource, vtkSphereSource

from anisovoronoi import (vtkAnisoAnalyticMetricSource, vtkAnisoCurvatureMetric,
                          vtkAnisoEmbedding, vtkAnisoSimplexMesh, vtkAnisoTensorToMetric)

# The shared check() / Messages helpers (Testing/Python/vtk_test_checks.py).
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), *[os.pardir] * 4,
                                "Testing", "Python"))
from vtk_test_checks import Messages, check, finish  # noqa: E402


def field(ds, name):
    a = ds.GetFieldData().GetArray(name)
    return a.GetTuple1(0) if a is not None else float("nan")


def rotation(axis, angle):
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + math.sin(angle) * k + (1 - math.cos(angle)) * k @ k


def sym6(t):  # 3x3 -> VTK order XX, YY, ZZ, XY, YZ, XZ
    return [t[0, 0], t[1, 1], t[2, 2], t[0, 1], t[1, 2], t[0, 2]]


def full3(v):
    return np.array([[v[0], v[3], v[5]], [v[3], v[1], v[4]], [v[5], v[4], v[2]]])


# 1. Analytic source (Cube1, Resolution 6) -> embedding (5 iterations).
source = vtkAnisoAnalyticMetricSource()
source.SetPresetByName("cube1")
source.SetResolution(6)
embedding = vtkAnisoEmbedding()
embedding.SetInputConnection(source.GetOutputPort())
embedding.SetIterations(5)
embedding.SetMaxIterations(0)  # a fixed count (no run to convergence)
msgs = Messages(embedding)
check(embedding.GetExecutive().Update() == 1, "embedding of cube1 ran")
check(not msgs.errors, "no embedding error: %s" % msgs.errors)
mesh = embedding.GetOutputDataObject(0)
check(mesh.GetNumberOfPoints() == 6 ** 3, "cube1 resolution 6 has 216 points")
emb = vtk_to_numpy(mesh.GetPointData().GetArray("Embedding"))
pts = vtk_to_numpy(mesh.GetPoints().GetData())
check(emb.shape == (216, 8), "8-dimensional embedding")
check(np.allclose(emb[:, :3], pts, atol=1e-9), "first coordinates are the input's")
l_avg = field(mesh, "L_avg")
check(math.isfinite(l_avg) and 0 <= l_avg < 100, "L_avg finite: %g" % l_avg)
energy = embedding.GetOutputDataObject(1)
etot = vtk_to_numpy(energy.GetColumnByName("E_total"))
check(len(etot) == 6, "energy table: initial state + 5 iterations")
check(np.all(np.diff(etot) <= 1e-9 * etot[0]), "energy never increases")
check(etot[-1] < etot[0], "energy decreases")

# 2. TensorToMetric on a synthetic rotated tensor field over the same mesh.
tets = source.GetOutputDataObject(0)
n = tets.GetNumberOfPoints()
r = rotation([1.0, -2.0, 0.5], 0.9)
xyz = vtk_to_numpy(tets.GetPoints().GetData())
lams = np.stack([0.5 + xyz[:, 0], np.ones(n), 2.0 + xyz[:, 1]], axis=1)  # in [0.5, 3]
tensors = np.array([sym6(r @ np.diag(l) @ r.T) for l in lams])
data = tets.NewInstance()
data.ShallowCopy(tets)
arr = numpy_to_vtk(tensors, deep=True)
arr.SetName("Stress")
data.GetPointData().AddArray(arr)
analytic_metric = vtk_to_numpy(data.GetPointData().GetArray("Metric")).copy()
num_arrays = data.GetPointData().GetNumberOfArrays()
t2m = vtkAnisoTensorToMetric()
t2m.SetInputData(data)
t2m.SetInputArrayToProcess(0, 0, 0, 0, "Stress")
t2m.SetMaximumAnisotropy(0)
t2m.GradationOff()  # the conversion alone: no metric preparation
t2m.SetNumberOfSites(0)
msgs = Messages(t2m)
check(t2m.GetExecutive().Update() == 1, "tensor to metric ran")
out = t2m.GetOutputDataObject(0)
metric = vtk_to_numpy(out.GetPointData().GetArray("Metric"))
c = 1.0 / 0.25  # smallest eigenvalue 0.5, squared
check(abs(field(out, "MetricScale") - c) < 1e-9, "MetricScale = 4: %g" % field(out, "MetricScale"))
expected = np.array([sym6(c * r @ np.diag(l ** 2) @ r.T) for l in lams])
check(np.allclose(metric, expected, rtol=1e-9, atol=1e-9), "metric = c V diag(lambda^2) V^T")
eig = np.array([np.linalg.eigvalsh(full3(m)) for m in metric])
check(abs(eig.min() - 1.0) < 1e-9, "smallest eigenvalue is 1 after the scale")
check(out.GetPointData().GetTensors().GetName() == "Metric", "Metric is the active tensor")
check(data.GetPointData().GetNumberOfArrays() == num_arrays and np.array_equal(
    vtk_to_numpy(data.GetPointData().GetArray("Metric")), analytic_metric), "input unmodified")
# The converted field feeds the embedding directly, which then needs no scale of its own.
embedding2 = vtkAnisoEmbedding()
embedding2.SetInputConnection(t2m.GetOutputPort())
embedding2.SetIterations(2)
embedding2.SetTargetDimension(6)
Messages(embedding2)
check(embedding2.GetExecutive().Update() == 1, "embedding of the converted metric ran")
check(abs(field(embedding2.GetOutputDataObject(0), "MetricScale") - 1.0) < 1e-9,
      "no further scale needed")

# Errors: 3 components, NaN.
vec = numpy_to_vtk(np.ones((n, 3)), deep=True)
vec.SetName("Vec")
data.GetPointData().AddArray(vec)
t2m.SetInputArrayToProcess(0, 0, 0, 0, "Vec")
msgs = Messages(t2m)
check(t2m.GetExecutive().Update() == 0 and any("components" in m for m in msgs.errors),
      "3-component array rejected")
bad = tensors.copy()
bad[7, 2] = float("nan")
nan_arr = numpy_to_vtk(bad, deep=True)
nan_arr.SetName("NaN")
data.GetPointData().AddArray(nan_arr)
t2m.SetInputArrayToProcess(0, 0, 0, 0, "NaN")
msgs = Messages(t2m)
check(t2m.GetExecutive().Update() == 0 and any("NaN" in m for m in msgs.errors),
      "NaN rejected: %s" % msgs.errors)

# 3. SimplexMesh: voxels -> conforming tets, point data kept exactly at the corners.
image = vtkImageData()
image.SetDimensions(4, 3, 3)
ramp = numpy_to_vtk(np.arange(36, dtype=float), deep=True)
ramp.SetName("Ramp")
image.GetPointData().AddArray(ramp)
splitter = vtkAnisoSimplexMesh()
splitter.SetInputData(image)
msgs = Messages(splitter)
check(splitter.GetExecutive().Update() == 1, "simplex mesh ran")
tet = splitter.GetOutputDataObject(0)
check(tet.GetNumberOfCells() == 12 * 12, "12 voxels -> 144 tets")
check(tet.GetNumberOfPoints() == 36 + 12, "36 corners + 12 centers")
check(len(msgs.warnings) == 1 and "12 voxels" in msgs.warnings[0], "split summary: %s" % msgs.warnings)
check("12 voxels" in tet.GetFieldData().GetAbstractArray("SplitSummary").GetValue(0), "SplitSummary")
ramp_out = vtk_to_numpy(tet.GetPointData().GetArray("Ramp"))
check(np.array_equal(ramp_out[:36], np.arange(36.0)), "corner point data kept with its ids")
# Ramp = i + 4 j + 12 k is linear, so each center gets the ramp at the center.
cp = vtk_to_numpy(tet.GetPoints().GetData())[36:]
check(np.allclose(ramp_out[36:], cp[:, 0] + 4 * cp[:, 1] + 12 * cp[:, 2]), "centers interpolated")

# 4. Curvature metric: sphere (umbilic: KMin = KMax = 1/R, Stretch 1) and cylinder.
sphere = vtkSphereSource()
sphere.SetRadius(2.0)
sphere.SetThetaResolution(48)
sphere.SetPhiResolution(48)
curv = vtkAnisoCurvatureMetric()
curv.SetInputConnection(sphere.GetOutputPort())
msgs = Messages(curv)
check(curv.GetExecutive().Update() == 1, "curvature metric on a sphere ran")
s = curv.GetOutputDataObject(0)
kmin = np.abs(vtk_to_numpy(s.GetPointData().GetArray("KMin")))
kmax = np.abs(vtk_to_numpy(s.GetPointData().GetArray("KMax")))
check(np.median(kmin) > 0.45 and np.median(kmax) < 0.55, "sphere curvatures ~ 1/R = 0.5")
check(np.median(vtk_to_numpy(s.GetPointData().GetArray("Stretch"))) < 1.2, "sphere: isotropic")

# Cylinder of radius 1 along z, height 4: KMax = 1 around, KMin = 0 along the axis.
nt, nz = 64, 41
pts = vtkPoints()
for k in range(nz):
    for i in range(nt):
        a = 2 * math.pi * i / nt
        pts.InsertNextPoint(math.cos(a), math.sin(a), -2.0 + 4.0 * k / (nz - 1))
cells = vtkCellArray()
for k in range(nz - 1):
    for i in range(nt):
        a, b = k * nt + i, k * nt + (i + 1) % nt
        cells.InsertNextCell(3, [a, b, b + nt])
        cells.InsertNextCell(3, [a, b + nt, a + nt])
cyl = vtkPolyData()
cyl.SetPoints(pts)
cyl.SetPolys(cells)
curv.SetInputData(cyl)
check(curv.GetExecutive().Update() == 1, "curvature metric on a cylinder ran")
c_out = curv.GetOutputDataObject(0)
z = vtk_to_numpy(c_out.GetPoints().GetData())[:, 2]
inner = np.abs(z) < 1.0
kmax = np.abs(vtk_to_numpy(c_out.GetPointData().GetArray("KMax")))[inner]
kmin = np.abs(vtk_to_numpy(c_out.GetPointData().GetArray("KMin")))[inner]
vmin = vtk_to_numpy(c_out.GetPointData().GetArray("VMin"))[inner]
vmax = vtk_to_numpy(c_out.GetPointData().GetArray("VMax"))[inner]
check(np.all(np.abs(kmax - 1.0) < 0.05), "cylinder KMax ~ 1: %g..%g" % (kmax.min(), kmax.max()))
check(np.all(kmin < 0.05), "cylinder KMin ~ 0: max %g" % kmin.max())
check(np.all(np.abs(vmin[:, 2]) > 0.99), "VMin along the axis")
check(np.all(np.abs(vmax[:, 2]) < 0.05), "VMax around the axis")
m = vtk_to_numpy(c_out.GetPointData().GetArray("Metric"))[inner]
stretch = vtk_to_numpy(c_out.GetPointData().GetArray("Stretch"))[inner]
# Eq. 19: M v_min = v_min, M v_max = stretch^2 v_max, M n = 0.
ok = True
for mi, a, b, st in zip(m, vmin, vmax, stretch):
    M = full3(mi)
    normal = np.cross(a, b)
    ok = ok and np.allclose(M @ a, a, atol=1e-6) and np.allclose(M @ b, st * st * b, rtol=1e-6)
    ok = ok and np.linalg.norm(M @ normal) < 1e-6 * st * st
check(ok, "Eq. 19 structure of the metric")
check(np.all(stretch > 3.0) and np.all(stretch <= 10.0 + 1e-9), "cylinder stretch in (3, 10]")
floor = field(c_out, "CurvatureFloor")
diag = math.sqrt(2 * 2 ** 2 + 4 ** 2)
check(abs(floor - 0.1 / diag) < 1e-9, "CurvatureFloor = 0.1 / diagonal: %g" % floor)

# Creases: a closed box (VTK's cube, triangulated and merged) is flat on every face. By default
# (CreaseAngle 180) its 12 edges read as curvature; with CreaseAngle 30 they are the creases and
# the metric is isotropic everywhere.
cube = vtkCubeSource()
cube.SetXLength(2.0)
tri = vtkTriangleFilter()
tri.SetInputConnection(cube.GetOutputPort())
merged = vtkCleanPolyData()
merged.SetInputConnection(tri.GetOutputPort())
box = vtkAnisoCurvatureMetric()
box.SetInputConnection(merged.GetOutputPort())
check(box.GetCreaseAngle() == 180.0, "CreaseAngle default 180 (off)")
check(box.GetExecutive().Update() == 1, "curvature metric on a box ran")
b_out = box.GetOutputDataObject(0)
check(field(b_out, "CreaseEdges") == 0, "no creases by default")
check(np.max(np.abs(vtk_to_numpy(b_out.GetPointData().GetArray("KMax")))) > 0.1,
      "box edges read as curvature without creases")
box.SetCreaseAngle(30.0)
check(box.GetExecutive().Update() == 1, "curvature metric on a box with creases ran")
b_out = box.GetOutputDataObject(0)
check(field(b_out, "CreaseEdges") == 12, "12 crease edges: %g" % field(b_out, "CreaseEdges"))
check(np.max(np.abs(vtk_to_numpy(b_out.GetPointData().GetArray("KMax")))) < 1e-9,
      "flat box faces with creases")
check(np.max(vtk_to_numpy(b_out.GetPointData().GetArray("Stretch"))) < 1.0 + 1e-9,
      "box with creases: isotropic")

# Quads are rejected with a hint to triangulate.
plane = vtkPlaneSource()
plane.SetResolution(3, 3)
curv.SetInputConnection(plane.GetOutputPort())
msgs = Messages(curv)
check(curv.GetExecutive().Update() == 0 and any("vtkTriangleFilter" in e for e in msgs.errors),
      "quads rejected with a hint: %s" % msgs.errors)

finish("TestMetricFilters")
