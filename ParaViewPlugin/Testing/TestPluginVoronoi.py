# SPDX-License-Identifier: BSD-3-Clause
"""pvbatch: the plugin's sampling / Voronoi / Delaunay / quality proxies.

Cube1 (6^3 grid) -> Aniso Embedding (5D) -> Aniso Particle Sampler (80 sites) ->
Aniso Restricted Voronoi (ShrinkFactor 0.8) and Aniso Restricted Delaunay -> Aniso Mesh
Quality. Checks the numbers that come back to the client (one cell per site, shrunk volume =
0.8^3 of the box, dual mesh vertices = sites, quality in range, histogram total) and renders
the shrunken cells colored by SiteId into a PNG that must not be blank.
Run: xvfb-run -a pvbatch --force-offscreen-rendering TestPluginVoronoi.py (env AV_PLUGIN).
"""
import os
import tempfile

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

plugin = os.environ.get("AV_PLUGIN")
assert plugin and os.path.exists(plugin), "set AV_PLUGIN to the built AnisoVoronoi.so"
LoadPlugin(plugin, ns=globals())


def field(proxy, name, port=0):
    data = servermanager.Fetch(proxy, idx=port)
    arr = data.GetFieldData().GetArray(name)
    assert arr is not None, name
    return arr.GetTuple1(0)


source = AnisoAnalyticMetricSource(Preset=1, Resolution=6)  # Cube1 on [0, 1]^3
embedding = AnisoEmbedding(Input=source, TargetDimension=5, Iterations=10)
sampler = AnisoParticleSampler(Input=embedding, NumberOfSites=80, Iterations=10)
sampler.UpdatePipeline()
sites = servermanager.Fetch(sampler)
assert sites.GetNumberOfPoints() == 80, sites.GetNumberOfPoints()
assert sites.GetPointData().GetArray("Embedding").GetNumberOfComponents() == 5

voronoi = AnisoRestrictedVoronoi(Input=embedding, Sites=sampler, ShrinkFactor=0.8)
voronoi.UpdatePipeline()
cells = servermanager.Fetch(voronoi)
measure = cells.GetCellData().GetArray("Measure")
site_ids = {int(cells.GetCellData().GetArray("SiteId").GetTuple1(c))
            for c in range(cells.GetNumberOfCells())}
total = sum(measure.GetTuple1(c) for c in range(cells.GetNumberOfCells()))
print("RVD: %d cells, shrunk volume %.12g" % (cells.GetNumberOfCells(), total))
assert cells.GetNumberOfCells() == 80
assert site_ids == set(range(80))
assert cells.GetCellType(0) == 42  # VTK_POLYHEDRON
assert abs(total - 0.8 ** 3) < 1e-9, total
assert field(voronoi, "RelativeVolumeError") < 1e-9
faces = servermanager.Fetch(voronoi, idx=1)
kinds = faces.GetCellData().GetArray("FaceKind")
assert kinds is not None and faces.GetNumberOfCells() > cells.GetNumberOfCells()
assert {int(kinds.GetTuple1(c)) for c in range(faces.GetNumberOfCells())} == {0, 1}

delaunay = AnisoRestrictedDelaunay(Input=embedding, Sites=sampler)
quality = AnisoMeshQuality(Input=delaunay)
quality.UpdatePipeline()
mesh = servermanager.Fetch(delaunay)
print("RDT: %d tets, inverted %g, non-manifold %g" % (
    mesh.GetNumberOfCells(), field(delaunay, "NumInverted"), field(delaunay, "NumNonManifoldFaces")))
# Repair properties (defaults): no inverted element is left; the points are the 80 sampled
# sites followed by the inserted ones.
assert delaunay.RepairInverted == 1 and delaunay.MaxRepairRounds == 10
assert delaunay.RepairNonManifold == 1
inserted = int(field(delaunay, "NumInsertedSites"))
assert field(delaunay, "NumInverted") == 0
assert inserted == 0 or field(delaunay, "NumInvertedBeforeRepair") > 0
assert mesh.GetNumberOfPoints() == 80 + inserted
assert mesh.GetNumberOfCells() > 80
# The mesh improvement (on by default) found the metric the embedding passes through, although
# the script built the proxy before its input ran (it used to be skipped with a warning).
assert delaunay.ImproveMesh == 1
assert field(delaunay, "NumImprovementFlips") + field(delaunay, "NumImprovementMoves") > 0
q = servermanager.Fetch(quality)
gavg, gmin = q.GetFieldData().GetArray("G_avg").GetTuple1(0), q.GetFieldData().GetArray("G_min").GetTuple1(0)
print("quality: G_min %.3f G_avg %.3f theta_min %.2f" % (
    gmin, gavg, q.GetFieldData().GetArray("theta_min").GetTuple1(0)))
assert 0.0 <= gmin <= gavg <= 1.0 and gavg > 0.5
hist = servermanager.Fetch(quality, idx=1)
assert sum(hist.GetValueByName(r, "Count").ToInt() for r in range(hist.GetNumberOfRows())) == \
    mesh.GetNumberOfCells()

# A surface: Sphere -> curvature metric -> embedding -> sites -> dual triangles, with the sphere
# as the quality filter's Reference Surface: the fidelity measures come back to the client.
ball = Sphere(ThetaResolution=40, PhiResolution=30)
ball_metric = AnisoCurvatureMetric(Input=ball)
ball_embedding = AnisoEmbedding(Input=ball_metric, TargetDimension=5, Iterations=10)
ball_sites = AnisoParticleSampler(Input=ball_embedding, NumberOfSites=100, Iterations=10)
ball_mesh = AnisoRestrictedDelaunay(Input=ball_embedding, Sites=ball_sites)
ball_quality = AnisoMeshQuality(Input=ball_mesh, ReferenceSurface=ball)
assert ball_quality.SurfaceFidelity == 1 and ball_quality.HausdorffSamplesPerEdge == 3
ball_quality.UpdatePipeline()
print("surface: euler %g, hausdorff %.3f %%, self-intersections %g, flipped %g" % (
    field(ball_quality, "euler"), field(ball_quality, "hausdorff"),
    field(ball_quality, "self_intersections"), field(ball_quality, "flipped")))
assert field(ball_quality, "euler") == 2 and field(ball_quality, "input_euler") == 2
assert 0 < field(ball_quality, "hausdorff") < 3.0
assert field(ball_quality, "self_intersections") == 0 and field(ball_quality, "flipped") == 0
flags = servermanager.Fetch(ball_quality).GetCellData().GetArray("Flipped")
assert flags is not None and flags.GetRange()[1] == 0

# Render the shrunken cells colored by SiteId; the picture must not be blank.
view = CreateView("RenderView")
view.ViewSize = [400, 300]
view.OrientationAxesVisibility = 0
display = Show(voronoi, view)
ColorBy(display, ("CELLS", "SiteId"))
display.RescaleTransferFunctionToDataRange(True)
view.CameraPosition = [2.2, -1.6, 1.9]
view.CameraFocalPoint = [0.5, 0.5, 0.5]
view.CameraViewUp = [0, 0, 1]
view.ResetCamera()
Render(view)
png = os.path.join(tempfile.mkdtemp(), "voronoi_cells.png")
SaveScreenshot(png, view, ImageResolution=[400, 300])
assert os.path.getsize(png) > 1000

from vtkmodules.vtkIOImage import vtkPNGReader  # noqa: E402

reader = vtkPNGReader()
reader.SetFileName(png)
reader.Update()
scalars = reader.GetOutput().GetPointData().GetScalars()
colors = {scalars.GetTuple(i) for i in range(0, scalars.GetNumberOfTuples(), 7)}
print("distinct colors sampled: %d" % len(colors))
assert len(colors) > 20, "the screenshot looks blank"
# Release the view while the GL context is alive (else a GLXBadContext at exit fails the run).
Delete(view)
del view
print("OK")
