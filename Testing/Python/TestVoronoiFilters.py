# SPDX-License-Identifier: BSD-3-Clause
"""The sampling / Voronoi / Delaunay / quality filters from Python (/usr/bin/python3).

Gaussian2D (paper §6.2) on a 25 x 25 grid: embedding in 3D, 200 sites, then
- the Voronoi polygons tile the square [-1, 1]^2 (shoelace areas = "Measure", sum = 4),
  each polygon is counter-clockwise and belongs to one site;
- the edges output: boundary edges have total length 8 (the square's perimeter);
- the dual mesh uses every site, has no inverted triangle and its quality is good;
- ShrinkFactor scales areas by its square.
Then Cube1 tets (feature sites kept, sliver push, boundary improvement), a box surface
(feature sites on the creases with KeepFeatureSites, closer to the box) and a sphere whose
hemispheres are given as feature patches (sites on the equator).
"""
import math
import sys

from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkCommonDataModel import vtkPolyData, vtkUnstructuredGrid
from vtkmodules.vtkFiltersCore import vtkCleanPolyData, vtkTriangleFilter
from vtkmodules.vtkFiltersModeling import vtkLinearSubdivisionFilter
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkIntArray
from vtkmodules.vtkFiltersSources import vtkCubeSource, vtkSphereSource
from anisovoronoi import (vtkAnisoAnalyticMetricSource, vtkAnisoCurvatureMetric, vtkAnisoEmbedding,
                          vtkAnisoParticleSampler, vtkAnisoRestrictedVoronoi,
                          vtkAnisoRestrictedDelaunay, vtkAnisoMeshQuality)


def field(obj, name):
    arr = obj.GetFieldData().GetArray(name)
    assert arr is not None, name
    return arr.GetTuple1(0)


def polygon_area(pts, ids):
    a = 0.0
    for i in range(len(ids)):
        x0, y0, _ = pts.GetPoint(ids[i])
        x1, y1, _ = pts.GetPoint(ids[(i + 1) % len(ids)])
        a += x0 * y1 - x1 * y0
    return 0.5 * a


def surface_sites(surface, sites):
    """Curvature metric -> embedding -> sampler on a surface (a port or a data object)."""
    metric = vtkAnisoCurvatureMetric()
    if hasattr(surface, "GetProducer"):
        metric.SetInputConnection(surface)
    else:
        metric.SetInputData(surface)
    embedded = vtkAnisoEmbedding()
    embedded.SetInputConnection(metric.GetOutputPort())
    sampled = vtkAnisoParticleSampler()
    sampled.SetInputConnection(embedded.GetOutputPort())
    sampled.SetNumberOfSites(sites)
    return metric, embedded, sampled


source = vtkAnisoAnalyticMetricSource()
source.SetPreset(0)  # Gaussian2D on [-1, 1]^2
source.SetResolution(25)
embedding = vtkAnisoEmbedding()
embedding.SetInputConnection(source.GetOutputPort())
embedding.SetTargetDimension(3)
sampler = vtkAnisoParticleSampler()
sampler.SetInputConnection(embedding.GetOutputPort())
sampler.SetNumberOfSites(200)
sampler.SetIterations(30)
rvd = vtkAnisoRestrictedVoronoi()
rvd.SetInputConnection(0, embedding.GetOutputPort())
rvd.SetInputConnection(1, sampler.GetOutputPort())
rvd.Update()

sites = sampler.GetOutput()
assert sites.GetNumberOfPoints() == 200
for name in ("Embedding", "CellId", "Barycentric", "Metric"):
    assert sites.GetPointData().GetArray(name) is not None, name
assert sites.GetPointData().GetArray("Barycentric").GetNumberOfComponents() == 4
assert field(sites, "Sigma") > 0
# The warm-up runs first by default and is switched off with WarmupIterations = 0.
assert sampler.GetWarmupIterations() == 100
assert 0 < field(sites, "SamplerWarmupIterations") <= 100
warm_first = [sites.GetPoint(i) for i in range(5)]
sampler.SetWarmupIterations(0)
sampler.Update()
assert field(sampler.GetOutput(), "SamplerWarmupIterations") == 0
assert [sampler.GetOutput().GetPoint(i) for i in range(5)] != warm_first
sampler.SetWarmupIterations(100)
sampler.Update()
assert [sampler.GetOutput().GetPoint(i) for i in range(5)] == warm_first
sites = sampler.GetOutput()

cells = rvd.GetOutput()
pts = cells.GetPoints()
measure = cells.GetCellData().GetArray("Measure")
site_id = cells.GetCellData().GetArray("SiteId")
total = 0.0
seen = set()
for c in range(cells.GetNumberOfCells()):
    assert cells.GetCellType(c) == 7  # VTK_POLYGON
    cell = cells.GetCell(c)
    ids = [cell.GetPointId(i) for i in range(cell.GetNumberOfPoints())]
    area = polygon_area(pts, ids)
    assert area > 0, "polygon %d is not counter-clockwise" % c
    assert abs(area - measure.GetTuple1(c)) <= 1e-9 * max(area, 1e-12), (area, measure.GetTuple1(c))
    total += area
    seen.add(int(site_id.GetTuple1(c)))
print("RVD: %d polygons, area %.15g" % (cells.GetNumberOfCells(), total))
assert abs(total - 4.0) < 1e-9
assert seen == set(range(200))
assert field(cells, "RelativeVolumeError") < 1e-9
assert field(cells, "NumberOfVoronoiCells") == 200

edges = rvd.GetOutputDataObject(1)
kind = edges.GetCellData().GetArray("FaceKind")
perimeter = 0.0
for c in range(edges.GetNumberOfCells()):
    if kind.GetTuple1(c) == 1:
        cell = edges.GetCell(c)
        p0 = edges.GetPoint(cell.GetPointId(0))
        p1 = edges.GetPoint(cell.GetPointId(1))
        perimeter += math.dist(p0, p1)
print("boundary length %.15g" % perimeter)
assert abs(perimeter - 8.0) < 1e-9

rvd.SetShrinkFactor(0.8)
rvd.Update()
shrunk = sum(rvd.GetOutput().GetCellData().GetArray("Measure").GetTuple1(c)
             for c in range(rvd.GetOutput().GetNumberOfCells()))
assert abs(shrunk / total - 0.64) < 1e-9, shrunk / total

rdt = vtkAnisoRestrictedDelaunay()
rdt.SetInputConnection(0, embedding.GetOutputPort())
rdt.SetInputConnection(1, sampler.GetOutputPort())
quality = vtkAnisoMeshQuality()
quality.SetInputConnection(rdt.GetOutputPort())
quality.Update()
mesh = rdt.GetOutput()
print("RDT: %d triangles, inverted %g, unused %g" % (
    mesh.GetNumberOfCells(), field(mesh, "NumInverted"), field(mesh, "NumUnusedSites")))
# The mesh improvement's splits append sites, its collapses leave unused points.
splits, collapses = field(mesh, "NumImprovementSplits"), field(mesh, "NumImprovementCollapses")
assert mesh.GetNumberOfPoints() == 200 + splits
assert field(mesh, "NumInverted") == 0
assert field(mesh, "NumUnusedSites") == collapses
# A triangulated disk with V used vertices: F = 2V - 2 - B (B boundary vertices), so F < 2V.
used = 200 + splits - collapses
assert used < mesh.GetNumberOfCells() < 2 * used
q = quality.GetOutput()
print("quality: G_min %.3f G_avg %.3f theta_min %.2f pct_bad %.2f" % (
    field(q, "G_min"), field(q, "G_avg"), field(q, "theta_min"), field(q, "pct_bad")))
assert field(q, "G_avg") > 0.75  # measured 0.82
assert quality.GetGAvg() == field(q, "G_avg")
hist = quality.GetOutputDataObject(1)
assert hist.GetNumberOfRows() == 18
assert sum(hist.GetValueByName(r, "Count").ToInt() for r in range(18)) == mesh.GetNumberOfCells()

# Tets (Cube1): the sliver perturbation (default 1 round) moves sites; their point data must be
# recomputed: the first 3 embedded coordinates of every output point are its position.
cube = vtkAnisoAnalyticMetricSource()
cube.SetPreset(1)  # Cube1
cube.SetResolution(9)
cube_embedding = vtkAnisoEmbedding()
cube_embedding.SetInputConnection(cube.GetOutputPort())
cube_sites = vtkAnisoParticleSampler()
cube_sites.SetInputConnection(cube_embedding.GetOutputPort())
cube_sites.SetNumberOfSites(300)
cube_rdt = vtkAnisoRestrictedDelaunay()
cube_rdt.SetInputConnection(0, cube_embedding.GetOutputPort())
cube_rdt.SetInputConnection(1, cube_sites.GetOutputPort())
cube_rdt.Update()
tets = cube_rdt.GetOutput()
emb = tets.GetPointData().GetArray("Embedding")
worst = max(abs(emb.GetComponent(i, d) - tets.GetPoint(i)[d])
            for i in range(tets.GetNumberOfPoints()) for d in range(3))
print("cube1 RDT: %d tets, slivers perturbed %g, moved sites %g, inverted %g, worst "
      "position/embedding mismatch %.3g" % (tets.GetNumberOfCells(), field(tets, "NumSliversPerturbed"),
                                            field(tets, "NumMovedSites"), field(tets, "NumInverted"), worst))
assert cube_rdt.GetImprovementRounds() == 1 and cube_rdt.GetOdtIterations() == 3
assert field(tets, "NumOdtMovedSites") > 0
assert field(tets, "NumMovedSites") > 0 and field(tets, "NumInverted") == 0
assert worst < 1e-9
# Sharp features: 8 corner sites and sites on the cube's edges. The improvement round (ODT
# steps, sliver pushes) leaves them where the sampler put them; the final mesh improvement may
# slide a line site along its straight crease, never off it: corners stay exactly, and a line
# site keeps the coordinates that put it on its cube edge (those at 0 or 1).
sampled = cube_sites.GetOutput()
kind = sampled.GetPointData().GetArray("FeatureKind")
assert kind is not None and field(sampled, "NumCornerSites") == 8
assert field(sampled, "NumFeatureLineSites") > 0
feature_ids = [i for i in range(sampled.GetNumberOfPoints()) if kind.GetValue(i) != 0]
assert len(feature_ids) == 8 + field(sampled, "NumFeatureLineSites")
def off_feature(i):
    before, after = sampled.GetPoint(i), tets.GetPoint(i)
    if kind.GetValue(i) == 2:  # corner
        return before != after
    on_edge = [d for d in range(3) if before[d] in (0.0, 1.0)]
    return len(on_edge) < 2 or any(after[d] != before[d] for d in on_edge)
assert sorted(set(kind.GetValue(i) for i in feature_ids)) == [1, 2]
moved_feature = [i for i in feature_ids if off_feature(i)]
assert not moved_feature, moved_feature
out_kind = tets.GetPointData().GetArray("FeatureKind")
assert out_kind is not None and all(out_kind.GetValue(i) == kind.GetValue(i) for i in feature_ids)
# With every site flagged as a corner site, the sliver push and the final improvement must
# move none of them; flagged as feature-line sites, only those on an edge of the cube may move,
# along it (the straight-crease slide of the final improvement).
def flagged_run(kind):
    flagged = vtkPolyData()
    flagged.DeepCopy(sampled)
    flags = flagged.GetPointData().GetArray("FeatureKind")
    for i in range(flagged.GetNumberOfPoints()):
        flags.SetValue(i, kind)
    f = vtkAnisoRestrictedDelaunay()
    f.SetInputConnection(0, cube_embedding.GetOutputPort())
    f.SetInputData(1, flagged)
    f.SetOdtIterations(0)  # sliver pushes only
    f.Update()
    return f
pinned = flagged_run(2)
lines = flagged_run(1).GetOutput()
cube_bounds = cube_embedding.GetOutput().GetBounds()
slid = 0
for i in range(sampled.GetNumberOfPoints()):
    before, after = sampled.GetPoint(i), lines.GetPoint(i)
    if after != before:
        on = [d for d in range(3) if before[d] in (cube_bounds[2 * d], cube_bounds[2 * d + 1])]
        assert len(on) >= 2 and all(after[d] == before[d] for d in on), (i, before, after)
        slid += 1
print("all flagged as feature lines: %d slid along an edge of the cube" % slid)
free = vtkAnisoRestrictedDelaunay()
free.SetInputConnection(0, cube_embedding.GetOutputPort())
free.SetInputData(1, sampled)
free.SetOdtIterations(0)
free.Update()
print("sliver push: %g slivers, %g sites moved; all flagged: %g moved" % (
    field(free.GetOutput(), "NumSliversPerturbed"), field(free.GetOutput(), "NumMovedSites"),
    field(pinned.GetOutput(), "NumMovedSites")))
assert field(free.GetOutput(), "NumMovedSites") > 0
assert field(free.GetOutput(), "NumSliversPerturbed") > 0
assert field(pinned.GetOutput(), "NumMovedSites") == 0
# The final improvement on the boundary (ImproveBoundary): off, no vertex of a boundary face
# moves; on, some do, and those on a face of the cube stay on it exactly.
def boundary_points(grid):
    count = {}
    for c in range(grid.GetNumberOfCells()):
        ids = grid.GetCell(c).GetPointIds()
        t = [ids.GetId(k) for k in range(4)]
        for skip in range(4):
            f = tuple(sorted(t[:skip] + t[skip + 1:]))
            count[f] = count.get(f, 0) + 1
    return sorted({v for f, n in count.items() if n == 1 for v in f})
bounds = cube_embedding.GetOutput().GetBounds()
def on_cube_face(x):
    return [d for d in range(3) if x[d] in (bounds[2 * d], bounds[2 * d + 1])]
cube_rdt.SetImprovementRounds(0)
cube_rdt.SetImproveBoundary(False)
cube_rdt.Update()
kept = vtkUnstructuredGrid()
kept.DeepCopy(cube_rdt.GetOutput())
# Points past the sampled ones are sites the repair inserted (NumInsertedSites), not sampled.
kept_boundary = [i for i in boundary_points(kept) if i < sampled.GetNumberOfPoints()]
assert kept.GetNumberOfPoints() == sampled.GetNumberOfPoints() + field(kept, "NumInsertedSites")
assert kept_boundary and all(kept.GetPoint(i) == sampled.GetPoint(i) for i in kept_boundary)
cube_rdt.SetImproveBoundary(True)
cube_rdt.Update()
improved = cube_rdt.GetOutput()
moved_boundary = [i for i in boundary_points(improved) if i < sampled.GetNumberOfPoints() and
                  improved.GetPoint(i) != sampled.GetPoint(i)]
print("boundary improvement: %d of %d boundary sites moved" % (len(moved_boundary),
                                                            len(boundary_points(improved))))
assert moved_boundary
for i in moved_boundary:
    before = sampled.GetPoint(i)
    after = improved.GetPoint(i)
    assert all(after[d] == before[d] for d in on_cube_face(before)), (i, before, after)
cube_rdt.SetImproveMesh(False)  # the final mesh improvement moves sites too
cube_rdt.Update()
assert field(cube_rdt.GetOutput(), "NumMovedSites") == 0

# A surface with creases (a 2 x 1 x 1 box, its squares cut into 512 triangles each): the
# sampler puts sites on the 12 edges and the 8 corners and records its FeatureAngle. By default
# the ODT steps move them off the creases; with KeepFeatureSites they stay on them (sliding
# along them at most), the edges along the creases are flipped into the mesh and the mesh is
# closer to the box.
box = vtkCubeSource()
box.SetXLength(2.0)
box_tris = vtkTriangleFilter()
box_tris.SetInputConnection(box.GetOutputPort())
box_clean = vtkCleanPolyData()
box_clean.SetInputConnection(box_tris.GetOutputPort())
box_fine = vtkLinearSubdivisionFilter()
box_fine.SetInputConnection(box_clean.GetOutputPort())
box_fine.SetNumberOfSubdivisions(4)
box_metric, box_embedding, box_sites = surface_sites(box_fine.GetOutputPort(), 600)
# Default (vertex-mean) embedding. With EDGE_LENGTHS the first dual has inverted triangles at
# one corner, and the ODT releases the kept sites of bad cells by design (MeshingPipeline.h,
# OdtKeepsFixedSites): 2 sites then leave their edge.
box_sites.Update()
box_sampled = box_sites.GetOutput()
assert field(box_sampled, "FeatureAngle") == 30.0 and field(box_sampled, "NumCornerSites") == 8
box_kind = box_sampled.GetPointData().GetArray("FeatureKind")
box_features = [i for i in range(box_sampled.GetNumberOfPoints()) if box_kind.GetValue(i) != 0]
box_bounds = box_fine.GetOutput().GetBounds()
box_results = {}
for keep in (False, True):
    box_rdt = vtkAnisoRestrictedDelaunay()
    box_rdt.SetInputConnection(0, box_embedding.GetOutputPort())
    box_rdt.SetInputConnection(1, box_sites.GetOutputPort())
    box_rdt.SetKeepFeatureSites(keep)
    box_quality = vtkAnisoMeshQuality()
    box_quality.SetInputConnection(box_rdt.GetOutputPort())
    box_quality.SetReferenceSurfaceConnection(box_fine.GetOutputPort())
    box_quality.Update()
    out = box_quality.GetOutput()
    moved = [i for i in box_features if out.GetPoint(i) != box_sampled.GetPoint(i)]
    # Kept: a site may only slide along its edge of the box (the mesh improvement's crease
    # slide): the two coordinates that put it on the edge stay exactly.
    off_edge = [i for i in moved
                if sum(1 for d in range(3) if out.GetPoint(i)[d] == box_sampled.GetPoint(i)[d]
                       and box_sampled.GetPoint(i)[d] in (box_bounds[2 * d], box_bounds[2 * d + 1])) < 2]
    box_results[keep] = (len(off_edge), field(out, "hausdorff"), field(out, "NumFeatureEdgesRequired"))
    assert field(out, "euler") == 2 and field(out, "flipped") == 0
    assert field(out, "self_intersections") == 0 and field(out, "NumInverted") == 0
print("box, feature sites off their edge / Hausdorff %% / crease pairs: default %s, kept %s" % (
    box_results[False], box_results[True]))
assert box_results[False][0] > 0 and box_results[True][0] == 0
assert box_results[True][2] > len(box_features) / 2
assert box_results[True][1] < 0.5 * box_results[False][1]

# Feature lines given as patch ids (FeaturePatchArray): a sphere has no crease, but with its two
# hemispheres as patches the equator becomes a feature line; the sampler puts sites on it and
# hands its features to the Delaunay filter in field data; with KeepFeatureSites the sites stay
# on the equator. A patch array that is not there is an error.
ball = vtkSphereSource()
ball.SetThetaResolution(48)
ball.SetPhiResolution(25)  # a ring of points at z = 0
ball.Update()
halves = vtkPolyData()
halves.DeepCopy(ball.GetOutput())
patch = vtkIntArray()
patch.SetName("Patch")
for c in range(halves.GetNumberOfCells()):
    ids = halves.GetCell(c).GetPointIds()
    z = sum(halves.GetPoint(ids.GetId(k))[2] for k in range(3)) / 3.0
    patch.InsertNextValue(1 if z > 0.0 else 2)
halves.GetCellData().AddArray(patch)
ball_metric, ball_embedding, ball_sites = surface_sites(halves, 400)
ball_sites.Update()
assert field(ball_sites.GetOutput(), "NumFeatureLineSites") == 0  # by angle: none
ball_sites.SetFeaturePatchArray("Patch")
ball_rdt = vtkAnisoRestrictedDelaunay()
ball_rdt.SetInputConnection(0, ball_embedding.GetOutputPort())
ball_rdt.SetInputConnection(1, ball_sites.GetOutputPort())
ball_rdt.SetKeepFeatureSites(True)
ball_rdt.Update()
ball_sampled = ball_sites.GetOutput()
on_line = field(ball_sampled, "NumFeatureLineSites")
edges = ball_sampled.GetFieldData().GetArray("FeatureEdges")
assert on_line > 10 and edges is not None and edges.GetNumberOfTuples() == 48, on_line
ball_kind = ball_sampled.GetPointData().GetArray("FeatureKind")
ball_mesh = ball_rdt.GetOutput()
equator = [i for i in range(ball_sampled.GetNumberOfPoints()) if ball_kind.GetValue(i) == 1]
assert all(abs(ball_mesh.GetPoint(i)[2]) < 1e-9 for i in equator)
print("sphere halves: %d sites on the equator, %d of %d consecutive pairs flipped into the mesh" % (
    len(equator), field(ball_mesh, "NumFeatureEdgesRecovered"), field(ball_mesh, "NumFeatureEdgesRequired")))
assert field(ball_mesh, "NumFeatureEdgesRequired") >= len(equator)
assert field(ball_mesh, "NumInverted") == 0
# The "Metric" of moved and inserted sites is the surface's, as the sampler's: rank 2, its null
# direction the normal of the input triangle holding the site (plain barycentric weights of the
# vertices' metrics, whose null directions are the vertex normals, are not: |M n| ~ 1e-2 |M|).
surf = ball_embedding.GetOutput()
ball_metric_out = ball_mesh.GetPointData().GetArray("Metric")
ball_cell_ids = ball_mesh.GetPointData().GetArray("CellId")
worst_null = 0.0
for i in range(ball_mesh.GetNumberOfPoints()):
    tri = surf.GetCell(int(ball_cell_ids.GetValue(i))).GetPointIds()
    p0, p1, p2 = (surf.GetPoint(tri.GetId(k)) for k in range(3))
    u = [p1[d] - p0[d] for d in range(3)]
    w = [p2[d] - p0[d] for d in range(3)]
    n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
    ln = sum(x * x for x in n) ** 0.5
    xx, yy, zz, xy, yz, xz = ball_metric_out.GetTuple6(i)
    m = [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]]
    mn = [sum(m[r][c] * n[c] / ln for c in range(3)) for r in range(3)]
    worst_null = max(worst_null, sum(x * x for x in mn) ** 0.5 / max(abs(v) for v in (xx, yy, zz)))
print("sphere halves: largest |M n| / |M| at the mesh's points %.2e" % worst_null)
assert field(ball_mesh, "NumMovedSites") > 0 and worst_null < 1e-9, worst_null
errors = []
missing = vtkAnisoParticleSampler()
missing.AddObserver(vtkCommand.ErrorEvent, lambda obj, ev: errors.append(ev))
missing.SetInputConnection(ball_embedding.GetOutputPort())
missing.SetFeaturePatchArray("NoSuchArray")
missing.Update()
assert errors and missing.GetOutput().GetNumberOfPoints() == 0
# A patch id that is not a number: an error, not a cast of NaN.
nan_halves = vtkPolyData()
nan_halves.DeepCopy(halves)
nan_patch = vtkDoubleArray()
nan_patch.SetName("Patch")
for c in range(nan_halves.GetNumberOfCells()):
    nan_patch.InsertNextValue(float("nan") if c == 5 else 1.0)
nan_halves.GetCellData().AddArray(nan_patch)
errors.clear()
nan_metric, nan_embedding, nan_sites = surface_sites(nan_halves, 100)
nan_sites.AddObserver(vtkCommand.ErrorEvent, lambda obj, ev: errors.append(ev))
nan_sites.SetFeaturePatchArray("Patch")
nan_sites.Update()
assert errors and nan_sites.GetOutput().GetNumberOfPoints() == 0

# Bad input: no embedding array -> error event, empty output, no exception.
errors = []
bad = vtkAnisoParticleSampler()
bad.AddObserver(vtkCommand.ErrorEvent, lambda obj, ev: errors.append(ev))
bad.SetInputConnection(source.GetOutputPort())
bad.Update()
assert errors and bad.GetOutput().GetNumberOfPoints() == 0
print("OK")
sys.exit(0)
