# SPDX-License-Identifier: BSD-3-Clause
"""pvbatch: the proxies of ParaViewPlugin/Metric.xml load and run (AV_PLUGIN = plugin path).
Builds Aniso Analytic Metric Source -> Aniso Embedding (both output ports), and runs Aniso
Tensor To Metric, Aniso Simplex Mesh, Aniso Curvature Metric, Aniso Analytic Metric and
Aniso Tet Mesher on small inputs, checking values from the fetched data."""
import math
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

LoadPlugin(os.environ["AV_PLUGIN"], ns=globals())

failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAILED:", what)


def field(data, name):
    a = data.GetFieldData().GetArray(name)
    return a.GetTuple1(0) if a is not None else float("nan")


# Analytic source -> embedding (5-dimensional, 5 iterations), both output ports.
src = AnisoAnalyticMetricSource(Preset="Cube1", Resolution=5)
emb = AnisoEmbedding(Input=src, TargetDimension=5, Iterations=5, MaxIterations=0)  # a fixed count
emb.Metric = ["POINTS", "Metric"]
emb.UpdatePipeline()
mesh = servermanager.Fetch(emb)
check(mesh.GetNumberOfPoints() == 125, "5^3 points: %d" % mesh.GetNumberOfPoints())
l_avg = field(mesh, "L_avg")
check(math.isfinite(l_avg) and l_avg >= 0, "L_avg finite: %g" % l_avg)
check(mesh.GetPointData().GetArray("Embedding").GetNumberOfComponents() == 5, "5 components")
energy = servermanager.Fetch(emb, idx=1)
check(energy.GetNumberOfRows() == 6, "energy table rows: %d" % energy.GetNumberOfRows())

# Tensor To Metric on the analytic metric used as a tensor: Cube1 is diag(S^2, 1, 1), S in
# [1, 10]; Eigenvalues As Stretch squares it (stretch S^2 up to 100), capped at 25.
an = AnisoAnalyticMetric(Input=Wavelet(WholeExtent=[0, 4, 0, 4, 0, 4]), Preset="Cube1")
t2m = AnisoTensorToMetric(Input=an, MaximumAnisotropy=25.0, MetricArrayName="M2",
                          Gradation=0, NumberOfSites=0)  # the conversion alone
t2m.Tensors = ["POINTS", "Metric"]
t2m.UpdatePipeline()
out = servermanager.Fetch(t2m)
check(out.GetPointData().GetArray("M2") is not None, "M2 array")
check(abs(field(out, "StretchMax") - 25.0) < 1e-6, "StretchMax capped at 25: %g" % field(out, "StretchMax"))
check(abs(field(out, "MetricScale") - 1.0) < 1e-9, "MetricScale 1")
t2m.Interpretation = "Tensor As Metric"
t2m.MaximumAnisotropy = 0.0
t2m.MinimumEigenvalue = 1e-6  # the default floor (1e-3 x 37^2) would raise the eigenvalue 1
t2m.UpdatePipeline()
out = servermanager.Fetch(t2m)
# Wavelet points are at integer x in [0, 4] -> x = 4 gives S = 37; the metric comes back.
m2 = out.GetPointData().GetArray("M2")
metric = out.GetPointData().GetArray("Metric")
diff = max(abs(m2.GetComponent(i, k) - metric.GetComponent(i, k))
           for i in range(out.GetNumberOfPoints()) for k in range(6))
check(diff < 1e-6 * 37 ** 2, "Tensor As Metric of a metric is itself: %g" % diff)

# Simplex Mesh: image voxels -> tets, with the summary.
split = AnisoSimplexMesh(Input=Wavelet(WholeExtent=[0, 2, 0, 2, 0, 2]), ReportSplit=0)
split.UpdatePipeline()
tets = servermanager.Fetch(split)
check(tets.GetNumberOfCells() == 8 * 12, "8 voxels -> 96 tets: %d" % tets.GetNumberOfCells())
summary = tets.GetFieldData().GetAbstractArray("SplitSummary")
check(summary is not None and "8 voxels" in summary.GetValue(0), "SplitSummary")

# Curvature metric on a sphere.
curv = AnisoCurvatureMetric(Input=Sphere(Radius=1.0, ThetaResolution=32, PhiResolution=32))
curv.UpdatePipeline()
cs = servermanager.Fetch(curv)
check(cs.GetPointData().GetArray("Metric") is not None and
      cs.GetPointData().GetArray("KMax") is not None, "curvature arrays")

# Tet mesher without input (a ball).
ball = AnisoTetMesher(Input=None, Shape="Ball", TargetVertices=500, Radius=2.0)
ball.UpdatePipeline()
bm = servermanager.Fetch(ball)
check(200 < bm.GetNumberOfPoints() < 1500, "ball vertices: %d" % bm.GetNumberOfPoints())
b = bm.GetBounds()
check(abs(b[1] - 2.0) < 0.05 and abs(b[0] + 2.0) < 0.05, "ball radius 2: %s" % (b,))

if failures:
    print("%d failure(s)" % len(failures))
    sys.exit(1)
print("TestPluginMetric passed")
