// SPDX-License-Identifier: BSD-3-Clause
// MetricAdaptedMesh: on a tet boundary layer, a fine tet grid, a 2D domain and a coarse sphere:
// conforming output (facets in at most two elements, no hanging node: the boundary measure is
// exact), volume / area and boundary kept, boundary points on the input boundary, every edge
// within the target after refinement, SPD metric at every point, no inverted element, parent
// weights that reproduce the points and carry a linear field exactly, new surface points on the
// input triangles, size following the sites, and bad input rejected.
#include "AnisoTestChecks.h"
#include "MeshTopology.h"
#include "MetricAdaptedMesh.h"
#include "MetricAlgebra.h"
#include "MetricFieldOps.h"
#include "StructuredMeshes.h"
#include "SurfaceGenerators.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

namespace
{
using namespace av;

/// Facets (sorted vertex ids) of the mesh with how many elements hold each.
std::map<std::vector<std::int32_t>, int> FacetCounts(const SimplexMesh& m)
{
  std::map<std::vector<std::int32_t>, int> count;
  const int nv = m.VerticesPerCell();
  for (std::size_t c = 0; c < m.NumCells(); ++c)
    for (int drop = 0; drop < nv; ++drop)
    {
      std::vector<std::int32_t> f;
      for (int k = 0; k < nv; ++k)
        if (k != drop)
          f.push_back(m.Cell(c)[k]);
      std::sort(f.begin(), f.end());
      ++count[f];
    }
  return count;
}

Eigen::Vector3d P(const SimplexMesh& m, std::int32_t i)
{
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int d = 0; d < m.AmbientDim; ++d)
    p[d] = m.Point(static_cast<std::size_t>(i))[d];
  return p;
}

/// Total measure of the facets held by one element (the boundary), and the largest count.
double BoundaryMeasure(const SimplexMesh& m, int& maxCount)
{
  maxCount = 0;
  double sum = 0.0;
  for (const auto& kv : FacetCounts(m))
  {
    maxCount = std::max(maxCount, kv.second);
    if (kv.second != 1)
      continue;
    const auto& f = kv.first;
    if (f.size() == 3)
      sum += 0.5 * (P(m, f[1]) - P(m, f[0])).cross(P(m, f[2]) - P(m, f[0])).norm();
    else
      sum += (P(m, f[1]) - P(m, f[0])).norm();
  }
  return sum;
}

double TotalMeasure(const SimplexMesh& m, double& minMeasure)
{
  double sum = 0.0;
  minMeasure = 1e300;
  for (std::size_t c = 0; c < m.NumCells(); ++c)
  {
    const double v = CellMeasure(m, c);
    sum += v;
    minMeasure = std::min(minMeasure, v);
  }
  return sum;
}

/// Longest normalized edge, recomputed with MetricEdgeLength.
double LongestEdge(const AdaptedMeshResult& r)
{
  const std::vector<std::int32_t> e = UniqueEdges(r.Mesh);
  double longest = 0.0;
  for (std::size_t i = 0; i < e.size(); i += 2)
    longest = std::max(longest,
      std::sqrt(r.MetricScale) *
        MetricEdgeLength(r.Metric.At(e[i]),
          r.Metric.At(e[i + 1]),
          r.Mesh.Point(e[i]),
          r.Mesh.Point(e[i + 1]),
          r.Mesh.AmbientDim));
  return longest;
}

double Linear(const double* x, int dim)
{
  return 1.0 + 2.0 * x[0] - 3.0 * x[1] + (dim == 3 ? 0.5 * x[2] : 0.0);
}

/// Parent weights: sum to 1, non-negative, reproduce each point and a linear field exactly.
void CheckParents(const SimplexMesh& input, const AdaptedMeshResult& r)
{
  const int d = input.AmbientDim;
  double worstPoint = 0.0, worstField = 0.0, worstSum = 0.0;
  bool nonNegative = true;
  for (std::size_t i = 0; i < r.Mesh.NumPoints(); ++i)
  {
    double x[3] = { 0, 0, 0 }, f = 0.0, sum = 0.0;
    for (int k = 0; k < 4; ++k)
    {
      const std::int32_t id = r.ParentIds[4 * i + k];
      if (id < 0)
        continue;
      const double w = r.ParentWeights[4 * i + k];
      nonNegative = nonNegative && w >= 0.0;
      sum += w;
      f += w * Linear(input.Point(id), d);
      for (int q = 0; q < d; ++q)
        x[q] += w * input.Point(id)[q];
    }
    worstSum = std::max(worstSum, std::abs(sum - 1.0));
    worstField = std::max(worstField, std::abs(f - Linear(r.Mesh.Point(i), d)));
    for (int q = 0; q < d; ++q)
      worstPoint = std::max(worstPoint, std::abs(x[q] - r.Mesh.Point(i)[q]));
  }
  AV_CHECK(nonNegative);
  AV_CHECK_NEAR(worstSum, 0.0, 1e-12);
  AV_CHECK_NEAR(worstPoint, 0.0, 1e-12);
  AV_CHECK_NEAR(worstField, 0.0, 1e-11);
}

void CheckSpd(const AdaptedMeshResult& r, bool rank2)
{
  bool ok = true;
  for (std::size_t i = 0; i < r.Metric.NumPoints(); ++i)
  {
    const Eigen::Matrix3d m = UnpackSymmetric(r.Metric.At(i));
    ok = ok && AllFinite(r.Metric.At(i), 6) &&
      (rank2 ? IsPositiveSemiDefinite(m) && EigenDecompose(m).Values[1] > 0.0
             : IsPositiveDefinite(m));
  }
  AV_CHECK(ok);
}

/// Metric of a wall layer at z = 0: size hz(z) = 0.03 + 0.3 z across, 0.15 along (stretch 5 at the
/// wall).
MetricField LayerMetric(const SimplexMesh& m)
{
  MetricField f;
  for (std::size_t i = 0; i < m.NumPoints(); ++i)
  {
    const double hz = 0.03 + 0.3 * m.Point(i)[2];
    const double h = 0.15;
    f.Values.insert(f.Values.end(), { 1.0 / (h * h), 1.0 / (h * h), 1.0 / (hz * hz), 0, 0, 0 });
  }
  return f;
}

/// The wall-layer case: a 4^3 Kuhn grid of the unit cube with LayerMetric.
SimplexMesh LayerGrid()
{
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
  return MakeKuhnTetGrid(4, 4, 4, lo, hi);
}

void TestBoundaryLayer()
{
  const SimplexMesh input = LayerGrid();
  const MetricField metric = LayerMetric(input);
  AdaptedMeshOptions o;
  o.NumberOfSites = 300;
  o.TargetLength = 0.5;
  const AdaptedMeshResult r = AdaptBackgroundMesh(input, metric, o);
  std::cout << "layer: " << r.Mesh.NumPoints() << " points, " << r.Mesh.NumCells() << " tets, "
            << r.NumSplits << " splits, " << r.NumCollapses << " collapses, max edge "
            << r.MaxEdgeLength << ", " << r.Seconds << " s\n";
  AV_CHECK(!r.HitPointLimit && r.NumSplits > 1000 && r.NumCollapses > 100);
  double minVol = 0.0;
  AV_CHECK_NEAR(TotalMeasure(r.Mesh, minVol), 1.0, 1e-12);
  AV_CHECK(minVol > 0.0);
  int maxCount = 0;
  AV_CHECK_NEAR(BoundaryMeasure(r.Mesh, maxCount), 6.0, 1e-11);
  AV_CHECK(maxCount == 2);
  // Boundary points stay on the box's faces; the corners stay.
  const std::vector<char> bnd = BoundaryVertexMask(r.Mesh);
  bool onBox = true;
  int corners = 0;
  for (std::size_t i = 0; i < r.Mesh.NumPoints(); ++i)
  {
    int atFace = 0;
    for (int q = 0; q < 3; ++q)
      atFace += r.Mesh.Point(i)[q] == 0.0 || r.Mesh.Point(i)[q] == 1.0;
    onBox = onBox && (!bnd[i] || atFace > 0);
    corners += atFace == 3;
  }
  AV_CHECK(onBox);
  AV_CHECK(corners == 8);
  // The resolution criterion, recomputed independently.
  const double longest = LongestEdge(r);
  AV_CHECK(longest <= o.TargetLength * (1 + 1e-12));
  AV_CHECK_NEAR(longest, r.MaxEdgeLength, 1e-9);
  CheckSpd(r, false);
  CheckParents(input, r);
  // Anisotropic: near the wall the edges are long along the wall, short across it.
  double maxAlong = 0.0, maxAcross = 0.0;
  const std::vector<std::int32_t> e = UniqueEdges(r.Mesh);
  for (std::size_t i = 0; i < e.size(); i += 2)
  {
    const Eigen::Vector3d a = P(r.Mesh, e[i]), b = P(r.Mesh, e[i + 1]);
    if (std::max(a[2], b[2]) > 0.02)
      continue;
    maxAcross = std::max(maxAcross, std::abs(a[2] - b[2]));
    maxAlong = std::max(maxAlong, std::hypot(a[0] - b[0], a[1] - b[1]));
  }
  AV_CHECK_MSG(maxAlong > 3.0 * maxAcross, "along " << maxAlong << " across " << maxAcross);
  // An isotropic mesh at the wall size would need ~(1/0.03)^3 / 0.5^3 ~ 300000 points.
  AV_CHECK(r.Mesh.NumPoints() < 60000u);
}

/// MeasureBackgroundResolution: the adapted mesh meets the criterion it measures (max edge, no
/// long edge), the coarse input does not; lengths scale as sites^(1/k) (8x the sites: 2x the
/// normalized lengths in 3D), and CoarserThanOutput follows the mean edge.
void TestResolution()
{
  const SimplexMesh input = LayerGrid();
  const MetricField metric = LayerMetric(input);
  AdaptedMeshOptions o;
  o.NumberOfSites = 300;
  o.TargetLength = 1.5;
  const BackgroundResolution given = MeasureBackgroundResolution(input, metric, 300, 1.5);
  AV_CHECK(given.MaxEdgeLength > 1.5 && given.LongEdgeFraction > 0.0);
  AV_CHECK(given.MeanEdgeLength > 1.0 && CoarserThanOutput(given));
  const BackgroundResolution more = MeasureBackgroundResolution(input, metric, 2400, 1.5);
  AV_CHECK_NEAR(more.MeanEdgeLength / given.MeanEdgeLength, 2.0, 1e-9);
  AV_CHECK_NEAR(more.MaxEdgeLength / given.MaxEdgeLength, 2.0, 1e-9);
  AV_CHECK(!CoarserThanOutput(MeasureBackgroundResolution(input, metric, 2, 1.5)));
  const AdaptedMeshResult r = AdaptBackgroundMesh(input, metric, o);
  const BackgroundResolution adapted = MeasureBackgroundResolution(r.Mesh, r.Metric, 300, 1.5);
  AV_CHECK_MSG(adapted.LongEdgeFraction == 0.0 && adapted.MaxEdgeLength <= 1.5 * (1 + 1e-6),
    "adapted: max edge " << adapted.MaxEdgeLength << ", long " << adapted.LongEdgeFraction);
  AV_CHECK_NEAR(adapted.MeanEdgeLength, r.MeanEdgeLength, 0.05 * r.MeanEdgeLength);
  AV_CHECK(!CoarserThanOutput(adapted));
  AV_CHECK_THROWS(MeasureBackgroundResolution(input, metric, 0, 1.5));
}

/// A fine grid and few sites: coarsening shrinks it, keeps the box and the criterion.
void TestCoarsening()
{
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 2, 1, 1 };
  const SimplexMesh input = MakeKuhnTetGrid(25, 13, 13, lo, hi);
  MetricField metric;
  for (std::size_t i = 0; i < input.NumPoints(); ++i)
    metric.Values.insert(metric.Values.end(), { 4, 1, 1, 0, 0, 0 }); // anisotropic, constant
  AdaptedMeshOptions o;
  o.NumberOfSites = 20;
  const AdaptedMeshResult r = AdaptBackgroundMesh(input, metric, o);
  std::cout << "coarsen: " << input.NumPoints() << " -> " << r.Mesh.NumPoints() << " points, "
            << r.NumCollapses << " collapses in " << r.CoarsenPasses << " passes, " << r.Seconds
            << " s\n";
  AV_CHECK(r.NumSplits == 0);
  AV_CHECK(r.Mesh.NumPoints() * 2 < input.NumPoints());
  double minVol = 0.0;
  AV_CHECK_NEAR(TotalMeasure(r.Mesh, minVol), 2.0, 1e-12);
  AV_CHECK(minVol > 0.0);
  int maxCount = 0;
  AV_CHECK_NEAR(BoundaryMeasure(r.Mesh, maxCount), 10.0, 1e-11);
  AV_CHECK(maxCount == 2);
  AV_CHECK(LongestEdge(r) <= o.TargetLength * (1 + 1e-12));
  CheckParents(input, r);
  const std::vector<char> bnd = BoundaryVertexMask(r.Mesh);
  bool onBox = true;
  for (std::size_t i = 0; i < r.Mesh.NumPoints(); ++i)
  {
    const double* x = r.Mesh.Point(i);
    const bool face = x[0] == 0 || x[0] == 2 || x[1] == 0 || x[1] == 1 || x[2] == 0 || x[2] == 1;
    onBox = onBox && (!bnd[i] || face);
  }
  AV_CHECK(onBox);
}

void Test2D()
{
  const double lo[2] = { 0, 0 }, hi[2] = { 3, 1 };
  const SimplexMesh input = MakeTriangleGrid(7, 3, lo, hi);
  MetricField metric;
  for (std::size_t i = 0; i < input.NumPoints(); ++i)
  {
    // Rotated anisotropy, varying along x.
    const double x = input.Point(i)[0];
    const double l1 = 1.0 + 30.0 * x, l2 = 1.0, c = std::cos(x), s = std::sin(x);
    metric.Values.insert(metric.Values.end(),
      { l1 * c * c + l2 * s * s, l1 * s * s + l2 * c * c, 1.0, (l1 - l2) * c * s, 0, 0 });
  }
  std::size_t previous = 0;
  for (const int sites : { 500, 4000 })
  {
    AdaptedMeshOptions o;
    o.NumberOfSites = sites;
    const AdaptedMeshResult r = AdaptBackgroundMesh(input, metric, o);
    double minArea = 0.0;
    AV_CHECK_NEAR(TotalMeasure(r.Mesh, minArea), 3.0, 1e-12);
    AV_CHECK(minArea > 0.0);
    int maxCount = 0;
    AV_CHECK_NEAR(BoundaryMeasure(r.Mesh, maxCount), 8.0, 1e-12);
    AV_CHECK(maxCount == 2);
    AV_CHECK(LongestEdge(r) <= o.TargetLength * (1 + 1e-12));
    CheckSpd(r, false);
    CheckParents(input, r);
    // The size follows the sites (8x the sites: about 8x the points).
    if (previous > 0)
      AV_CHECK_MSG(r.Mesh.NumPoints() > 4 * previous && r.Mesh.NumPoints() < 16 * previous,
        previous << " -> " << r.Mesh.NumPoints());
    previous = r.Mesh.NumPoints();
  }
}

/// A coarse sphere: new points lie on the input triangles, the surface stays closed and
/// consistently oriented, the area is kept exactly without coarsening.
void TestSurface()
{
  const SimplexMesh input = MakeIcosphere(1.0, 1);
  MetricField metric;
  for (std::size_t i = 0; i < input.NumPoints(); ++i)
  {
    // Rank 2: the projector onto the tangent plane, scaled (a curvature-like surface metric).
    const Eigen::Vector3d n = P(input, static_cast<std::int32_t>(i)).normalized();
    const Eigen::Matrix3d m = 9.0 * (Eigen::Matrix3d::Identity() - n * n.transpose());
    double v[6];
    PackSymmetric(m, v);
    metric.Values.insert(metric.Values.end(), v, v + 6);
  }
  std::set<std::vector<std::int32_t>> inputTriangles;
  for (std::size_t c = 0; c < input.NumCells(); ++c)
  {
    std::vector<std::int32_t> t(input.Cell(c), input.Cell(c) + 3);
    std::sort(t.begin(), t.end());
    inputTriangles.insert(t);
  }
  double inputArea = 0.0, unused = 0.0;
  inputArea = TotalMeasure(input, unused);
  AdaptedMeshOptions o;
  o.NumberOfSites = 2000;
  o.Coarsen = false;
  const AdaptedMeshResult r = AdaptBackgroundMesh(input, metric, o);
  AV_CHECK(r.Mesh.NumPoints() > 10 * input.NumPoints());
  double area = TotalMeasure(r.Mesh, unused);
  AV_CHECK_NEAR(area, inputArea, 1e-12 * inputArea);
  AV_CHECK(LongestEdge(r) <= o.TargetLength * (1 + 1e-12));
  CheckSpd(r, true);
  CheckParents(input, r);
  bool onInput = true;
  for (std::size_t i = 0; i < r.Mesh.NumPoints(); ++i)
  {
    std::vector<std::int32_t> ids;
    for (int k = 0; k < 4; ++k)
      if (r.ParentIds[4 * i + k] >= 0)
        ids.push_back(r.ParentIds[4 * i + k]);
    std::sort(ids.begin(), ids.end());
    bool inSome = ids.size() <= 3;
    if (ids.size() == 3)
      inSome = inputTriangles.count(ids) == 1;
    onInput = onInput && inSome;
  }
  AV_CHECK(onInput);
  // Closed and oriented: every directed edge once, its reverse once.
  std::map<std::pair<std::int32_t, std::int32_t>, int> directed;
  for (std::size_t c = 0; c < r.Mesh.NumCells(); ++c)
    for (int e = 0; e < 3; ++e)
      ++directed[{ r.Mesh.Cell(c)[e], r.Mesh.Cell(c)[(e + 1) % 3] }];
  bool oriented = true;
  for (const auto& kv : directed)
    oriented =
      oriented && kv.second == 1 && directed.count({ kv.first.second, kv.first.first }) == 1;
  AV_CHECK(oriented);
  // With coarsening the surface stays closed, oriented and the points stay on the input.
  o.Coarsen = true;
  o.NumberOfSites = 200;
  const AdaptedMeshResult c = AdaptBackgroundMesh(input, metric, o);
  int maxCount = 0;
  AV_CHECK_NEAR(BoundaryMeasure(c.Mesh, maxCount), 0.0, 0.0);
  AV_CHECK(maxCount == 2);
  CheckParents(input, c);
}

void TestBadInput()
{
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
  const SimplexMesh input = MakeKuhnTetGrid(3, 3, 3, lo, hi);
  MetricField metric;
  for (std::size_t i = 0; i < input.NumPoints(); ++i)
    metric.Values.insert(metric.Values.end(), { 1, 1, 1, 0, 0, 0 });
  AdaptedMeshOptions o;
  o.NumberOfSites = 0;
  AV_CHECK_THROWS(AdaptBackgroundMesh(input, metric, o));
  o.NumberOfSites = 100;
  o.TargetLength = -1.0;
  AV_CHECK_THROWS(AdaptBackgroundMesh(input, metric, o));
  o.TargetLength = 0.5;
  MetricField shortMetric = metric;
  shortMetric.Values.resize(6);
  AV_CHECK_THROWS(AdaptBackgroundMesh(input, shortMetric, o));
  MetricField negative = metric;
  negative.Values[6 * 3] = -1.0;
  AV_CHECK_THROWS(AdaptBackgroundMesh(input, negative, o));
  MetricField zero = metric;
  std::fill(zero.Values.begin(), zero.Values.end(), 0.0);
  AV_CHECK_THROWS(AdaptBackgroundMesh(input, zero, o));
  SimplexMesh badIds = input;
  badIds.Cells[5] = 1000;
  AV_CHECK_THROWS(AdaptBackgroundMesh(badIds, metric, o));
}
} // namespace

int TestMetricAdaptedMesh(int, char*[])
{
  TestBoundaryLayer();
  TestResolution();
  TestCoarsening();
  Test2D();
  TestSurface();
  TestBadInput();
  return AV_TEST_RESULT();
}
