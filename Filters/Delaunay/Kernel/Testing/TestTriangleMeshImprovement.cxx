// SPDX-License-Identifier: BSD-3-Clause
// Tests of the triangle operations of ImproveMesh: an edge collapse (two sites too close) and an
// edge split (a hexagon without its center) each raise the worst angle where flips and
// smoothing cannot; on a jittered 2D grid and on a latitude-longitude sphere (poles, projected
// moves) nothing inverts or flips, the 2D boundary stays (as a curve), every edge stays shared
// by two triangles (one on the 2D boundary), sphere vertices stay on the sphere, the worst
// quality never drops; the mutation hook that accepts worsening moves breaks those checks.
#include "AnisoTestChecks.h"
#include "PropertyChecks.h"
#include "MeshImprovement.h"
#include "MeshQuality.h"
#include "MeshTopology.h"
#include "StructuredMeshes.h"

#include <Eigen/Dense>

#include <algorithm>
#include <iostream>
#include <cmath>
#include <map>
#include <random>
#include <utility>
#include <vector>

using av_test::Checks;

namespace
{
const double Pi = 3.14159265358979323846;

av::MetricField IsotropicMetric(std::size_t n)
{
  av::MetricField m;
  m.Values.assign(6 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    m.Values[6 * i] = m.Values[6 * i + 1] = m.Values[6 * i + 2] = 1.0;
  return m;
}

Eigen::Vector3d At(const av::SimplexMesh& m, std::int32_t i)
{
  const double* p = m.Point(static_cast<std::size_t>(i));
  return Eigen::Vector3d(p[0], p[1], m.AmbientDim == 3 ? p[2] : 0.0);
}

// Smallest angle (degrees) of the mesh, isotropic metric; negative when a 2D triangle is
// inverted or a sphere triangle faces inwards.
double WorstAngle(const av::SimplexMesh& m)
{
  double worst = 180.0;
  for (std::size_t c = 0; c < m.NumCells(); ++c)
  {
    const std::int32_t* v = m.Cell(c);
    const Eigen::Vector3d a = At(m, v[0]), b = At(m, v[1]), d = At(m, v[2]);
    const Eigen::Vector3d n = (b - a).cross(d - a);
    const Eigen::Vector3d up =
      m.AmbientDim == 2 ? Eigen::Vector3d(Eigen::Vector3d::UnitZ()) : Eigen::Vector3d(a + b + d);
    double smallest = 180.0;
    const Eigen::Vector3d p[3] = { a, b, d };
    for (int i = 0; i < 3; ++i)
    {
      const Eigen::Vector3d u = p[(i + 1) % 3] - p[i], w = p[(i + 2) % 3] - p[i];
      smallest = std::min(smallest, std::atan2(u.cross(w).norm(), u.dot(w)) * 180.0 / Pi);
    }
    worst = std::min(worst, n.dot(up) > 0.0 ? smallest : -smallest);
  }
  return worst;
}

// Counts of how many triangles share each edge.
std::map<std::pair<std::int32_t, std::int32_t>, int> EdgeUse(const av::SimplexMesh& m)
{
  std::map<std::pair<std::int32_t, std::int32_t>, int> use;
  for (std::size_t c = 0; c < m.NumCells(); ++c)
    for (int e = 0; e < 3; ++e)
    {
      const std::int32_t a = m.Cell(c)[e], b = m.Cell(c)[(e + 1) % 3];
      ++use[{ std::min(a, b), std::max(a, b) }];
    }
  return use;
}

double Area(const av::SimplexMesh& m)
{
  double s = 0.0;
  for (std::size_t c = 0; c < m.NumCells(); ++c)
    s += av::CellMeasure(m, c);
  return s;
}

// 2D: no inverted triangle; every interior edge shared by two triangles; the boundary kept as a
// curve (each boundary edge after lies on one before, the same total length), boundary and fixed
// points stay; the area kept; the worst quality never drops.
Checks CheckPlanarRun(const av::SimplexMesh& before,
  const av::SimplexMesh& after,
  const std::vector<std::uint8_t>& fixed,
  const av::MeshImprovementResult& r)
{
  Checks c;
  for (std::size_t t = 0; t < after.NumCells(); ++t)
    c.Expect(av::CellMeasure(after, t) > 0.0, "no inverted triangle");
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> segments;
  double lengthBefore = 0.0, lengthAfter = 0.0;
  for (const auto& [e, n] : EdgeUse(before))
    if (n == 1)
    {
      segments.emplace_back(At(before, e.first), At(before, e.second));
      lengthBefore += (At(before, e.first) - At(before, e.second)).norm();
    }
  for (const auto& [e, n] : EdgeUse(after))
  {
    c.Expect(n == 1 || n == 2, "every edge shared by one (boundary) or two triangles");
    if (n != 1)
      continue;
    const Eigen::Vector3d a = At(after, e.first), b = At(after, e.second);
    lengthAfter += (a - b).norm();
    bool onOld = false;
    for (const auto& [p, q] : segments)
    {
      const double l = (q - p).norm();
      onOld = onOld ||
        ((a - p).norm() + (a - q).norm() < l + 1e-12 &&
          (b - p).norm() + (b - q).norm() < l + 1e-12);
    }
    c.Expect(onOld, "each boundary edge lies on a boundary edge of the input");
  }
  c.Expect(std::abs(lengthAfter - lengthBefore) < 1e-12, "boundary length kept");
  c.Expect(std::abs(Area(after) - Area(before)) < 1e-12, "area kept");
  const std::vector<char> boundary = av::BoundaryVertexMask(before);
  for (std::size_t i = 0; i < before.NumPoints(); ++i)
    if (boundary[i] || fixed[i])
      c.Expect(after.Points[2 * i] == before.Points[2 * i] &&
          after.Points[2 * i + 1] == before.Points[2 * i + 1],
        "boundary and fixed points stay");
  c.Expect(r.WorstAfter >= r.WorstBefore, "the worst quality never drops");
  return c;
}

// Unit sphere: the closest point, its normal and the isotropic metric of its tangent plane.
bool PlaceOnSphere(std::int32_t, const double* x, double* placed, double* normal, double* m)
{
  const Eigen::Vector3d p = Eigen::Map<const Eigen::Vector3d>(x).normalized();
  const Eigen::Matrix3d t = Eigen::Matrix3d::Identity() - p * p.transpose();
  for (int d = 0; d < 3; ++d)
    placed[d] = normal[d] = p[d];
  const double packed[6] = { t(0, 0), t(1, 1), t(2, 2), t(0, 1), t(1, 2), t(0, 2) };
  std::copy(packed, packed + 6, m);
  return true;
}

av::MetricField SphereMetric(const av::SimplexMesh& s)
{
  av::MetricField m;
  m.Values.resize(6 * s.NumPoints());
  for (std::size_t i = 0; i < s.NumPoints(); ++i)
  {
    double placed[3], normal[3];
    PlaceOnSphere(0, s.Point(i), placed, normal, m.Values.data() + 6 * i);
  }
  return m;
}

// Latitude-longitude sphere: rings of `nlon` vertices, two poles; slivers near the poles.
av::SimplexMesh LatLongSphere(int nlat, int nlon)
{
  av::SimplexMesh m;
  m.AmbientDim = 3;
  m.SimplexDim = 2;
  auto add = [&](double theta, double phi)
  {
    m.Points.insert(m.Points.end(),
      { std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta) });
  };
  add(0.0, 0.0); // north pole 0
  for (int i = 1; i < nlat; ++i)
    for (int j = 0; j < nlon; ++j)
      add(Pi * i / nlat, 2.0 * Pi * (j + 0.5 * (i % 2)) / nlon);
  add(Pi, 0.0);
  const std::int32_t south = static_cast<std::int32_t>(m.NumPoints() - 1);
  auto ring = [&](int i, int j) { return 1 + (i - 1) * nlon + ((j % nlon) + nlon) % nlon; };
  for (int j = 0; j < nlon; ++j)
  {
    m.Cells.insert(m.Cells.end(), { 0, ring(1, j), ring(1, j + 1) });
    m.Cells.insert(m.Cells.end(), { south, ring(nlat - 1, j + 1), ring(nlat - 1, j) });
    for (int i = 1; i + 1 < nlat; ++i)
    {
      m.Cells.insert(m.Cells.end(), { ring(i, j), ring(i + 1, j), ring(i + 1, j + 1) });
      m.Cells.insert(m.Cells.end(), { ring(i, j), ring(i + 1, j + 1), ring(i, j + 1) });
    }
  }
  return m;
}

// Sphere: every vertex used stays on the sphere, no triangle faces inwards or is flat, every
// edge is shared by exactly two triangles, the Euler characteristic stays 2, the worst quality
// never drops.
Checks CheckSphereRun(const av::SimplexMesh& after, const av::MeshImprovementResult& r)
{
  Checks c;
  std::vector<char> used(after.NumPoints(), 0);
  for (std::int32_t v : after.Cells)
    used[static_cast<std::size_t>(v)] = 1;
  std::size_t nv = 0;
  for (std::size_t i = 0; i < after.NumPoints(); ++i)
    if (used[i])
    {
      ++nv;
      c.Expect(std::abs(At(after, static_cast<std::int32_t>(i)).norm() - 1.0) < 1e-12,
        "vertices stay on the sphere");
    }
  c.Expect(WorstAngle(after) > 0.0, "no flipped or flat triangle");
  const auto use = EdgeUse(after);
  for (const auto& [e, n] : use)
    c.Expect(n == 2, "every edge shared by exactly two triangles");
  c.Expect(
    static_cast<long>(nv) - static_cast<long>(use.size()) + static_cast<long>(after.NumCells()) ==
      2,
    "Euler characteristic 2");
  c.Expect(r.WorstAfter >= r.WorstBefore, "the worst quality never drops");
  return c;
}

void OrientPositive(av::SimplexMesh& m)
{
  for (std::size_t c = 0; c < m.NumCells(); ++c)
    if (av::CellMeasure(m, c) < 0.0)
      std::swap(m.Cells[3 * c + 1], m.Cells[3 * c + 2]);
}

// Two interior vertices far too close in a hexagon: only removing one of them helps.
void TestCollapse()
{
  av::SimplexMesh m;
  m.AmbientDim = m.SimplexDim = 2;
  for (int i = 0; i < 6; ++i)
    m.Points.insert(m.Points.end(), { std::cos(Pi * i / 3), std::sin(Pi * i / 3) });
  m.Points.insert(m.Points.end(), { -0.05, 0.0, 0.05, 0.0 }); // 6, 7
  m.Cells = { 7, 0, 1, 7, 5, 0, 6, 2, 3, 6, 3, 4, 7, 1, 6, 6, 1, 2, 6, 4, 7, 7, 4, 5 };
  OrientPositive(m);
  const av::SimplexMesh start = m;
  av::MeshImprovementOptions o;
  o.Flips = o.Smoothing = o.Splits = false;
  const av::MeshImprovementResult r = av::ImproveMesh(m, IsotropicMetric(8), nullptr, o);
  AV_CHECK_MSG(r.NumCollapses >= 1 && WorstAngle(m) > WorstAngle(start) + 20.0,
    WorstAngle(start) << " -> " << WorstAngle(m) << ", collapses " << r.NumCollapses);
  AV_CHECK(m.NumCells() == 6);
  AV_CHECK(CheckPlanarRun(start, m, std::vector<std::uint8_t>(8, 0), r).Ok);
  // A fixed vertex is never removed: with both fixed nothing can change.
  std::vector<std::uint8_t> fixed(8, 0);
  fixed[6] = fixed[7] = 1;
  av::SimplexMesh f = start;
  const av::MeshImprovementResult fr = av::ImproveMesh(f, IsotropicMetric(8), &fixed, o);
  AV_CHECK(fr.NumCollapses == 0 && f.Cells == start.Cells);
}

// A hexagon fanned from one corner: every triangulation of its six corners has a 30 degree
// angle and no vertex is free; a split of a long diagonal, smoothed towards the center, helps.
void TestSplit()
{
  av::SimplexMesh m;
  m.AmbientDim = m.SimplexDim = 2;
  for (int i = 0; i < 6; ++i)
    m.Points.insert(m.Points.end(), { std::cos(Pi * i / 3), std::sin(Pi * i / 3) });
  m.Cells = { 0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 5 };
  const av::SimplexMesh start = m;
  av::MeshImprovementOptions o;
  o.Collapses = false;
  o.TargetAngle = 40.0;
  av::MeshImprovementOptions noSplit = o;
  noSplit.Splits = false;
  av::SimplexMesh n = start;
  av::ImproveMesh(n, IsotropicMetric(6), nullptr, noSplit);
  AV_CHECK_MSG(WorstAngle(n) < 30.0 + 1e-9, "flips and smoothing alone: " << WorstAngle(n));
  const av::MeshImprovementResult r = av::ImproveMesh(m, IsotropicMetric(6), nullptr, o);
  AV_CHECK_MSG(r.NumSplits >= 1 && WorstAngle(m) > WorstAngle(start) + 5.0,
    WorstAngle(start) << " -> " << WorstAngle(m) << ", splits " << r.NumSplits);
  AV_CHECK(m.NumPoints() == 6 + r.NumSplits);
  AV_CHECK(CheckPlanarRun(start, m, std::vector<std::uint8_t>(6, 0), r).Ok);
}

// A jittered grid in a metric stretched along x, all operations on.
av::SimplexMesh JitteredTriangles()
{
  const double lo[2] = { 0, 0 }, hi[2] = { 1, 1 };
  av::SimplexMesh t = av::MakeTriangleGrid(8, 8, lo, hi);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.04, 0.04);
  const std::vector<char> tb = av::BoundaryVertexMask(t);
  for (std::size_t i = 0; i < t.NumPoints(); ++i)
    if (!tb[i])
      for (int d = 0; d < 2; ++d)
        t.Points[2 * i + d] += u(rng);
  return t;
}

av::MetricField StretchedMetric2(std::size_t n)
{
  av::MetricField m;
  m.Values.assign(6 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
  {
    m.Values[6 * i] = 9.0;
    m.Values[6 * i + 1] = 1.0;
    m.Values[6 * i + 3] = 0.5;
  }
  return m;
}

void TestPlanarGrid()
{
  const av::SimplexMesh start = JitteredTriangles();
  std::vector<std::uint8_t> fixed(start.NumPoints(), 0);
  fixed[start.NumPoints() / 2] = 1;
  const av::MetricField metric = StretchedMetric2(start.NumPoints());
  av::SimplexMesh m = start;
  av::MeshImprovementOptions o;
  o.TargetAngle = 45.0;
  const av::MeshImprovementResult r = av::ImproveMesh(m, metric, &fixed, o);
  std::cerr << "grid: worst " << r.WorstBefore << " -> " << r.WorstAfter << ", flips "
            << r.NumFlips22 << ", moves " << r.NumSmoothed << ", splits " << r.NumSplits
            << ", collapses " << r.NumCollapses << std::endl;
  AV_CHECK(CheckPlanarRun(start, m, fixed, r).Ok);
  AV_CHECK_MSG(r.WorstAfter > r.WorstBefore + 1.0, r.WorstBefore << " -> " << r.WorstAfter);
  AV_CHECK(r.NumSplits + r.NumCollapses > 0);

  av::MeshImprovementOptions worsening = o;
  worsening.AcceptWorsening = true;
  worsening.TargetAngle = 80.0;
  av::SimplexMesh w = start;
  const av::MeshImprovementResult wr = av::ImproveMesh(w, metric, &fixed, worsening);
  std::cerr << "(expected) worsening grid run: " << wr.WorstBefore << " -> " << wr.WorstAfter
            << std::endl;
  AV_CHECK_MSG(!CheckPlanarRun(start, w, fixed, wr).Ok, "the checks miss a worsening run");
}

// The mean-quality sweeps on the jittered grid: the mean G (the Quality kernel's evaluator)
// rises, the worst triangle stays where the worst-first passes left it or at the target, the
// grid stays valid; without the floor (the AcceptWorsening hook, no passes) the worst falls.
void TestMeanSmoothing()
{
  const av::SimplexMesh start = JitteredTriangles();
  std::vector<std::uint8_t> fixed(start.NumPoints(), 0);
  fixed[start.NumPoints() / 2] = 1;
  av::MeshImprovementOptions o;
  o.Splits = o.Collapses = false; // same points, so that one metric field evaluates both
  av::MeshImprovementOptions passesOnly = o;
  passesOnly.MeanSmoothingSweeps = 0;
  const av::MetricField metric = StretchedMetric2(start.NumPoints());
  av::SimplexMesh m0 = start, m2 = start;
  const av::MeshImprovementResult r0 = av::ImproveMesh(m0, metric, &fixed, passesOnly);
  const av::MeshImprovementResult r2 = av::ImproveMesh(m2, metric, &fixed, o);
  AV_CHECK(CheckPlanarRun(start, m2, fixed, r2).Ok);
  const av::MeshQualitySummary q0 = av::EvaluateMeshQuality(m0, metric).Summary;
  const av::MeshQualitySummary q2 = av::EvaluateMeshQuality(m2, metric).Summary;
  std::cerr << "mean smoothing (triangles): G_avg " << q0.GAvg << " -> " << q2.GAvg
            << ", theta_min " << q0.ThetaMin << " -> " << q2.ThetaMin << ", "
            << r2.NumMeanSmoothed << " moves" << std::endl;
  AV_CHECK(r0.NumMeanSmoothed == 0 && r2.NumMeanSmoothed > 0);
  AV_CHECK_MSG(q2.GAvg > q0.GAvg + 0.005, q0.GAvg << " -> " << q2.GAvg);
  AV_CHECK_MSG(r2.WorstAfter >= std::min(r0.WorstAfter, o.TargetAngle) - 1e-9,
    r0.WorstAfter << " -> " << r2.WorstAfter);
  av::MeshImprovementOptions noFloor = o;
  noFloor.MaxPasses = 0;
  noFloor.AcceptWorsening = true;
  av::SimplexMesh b = start;
  const av::MeshImprovementResult rb = av::ImproveMesh(b, metric, &fixed, noFloor);
  std::cerr << "(expected) sweeps without the floor: worst " << rb.WorstBefore << " -> "
            << rb.WorstAfter << std::endl;
  AV_CHECK_MSG(rb.WorstAfter < rb.WorstBefore, "the floor check misses a worsening sweep");
}

void TestSphere()
{
  const av::SimplexMesh start = LatLongSphere(10, 14);
  av::MeshImprovementOptions o;
  o.PlacePoint = PlaceOnSphere;
  o.SurfaceFlipMaxDihedral = 40.0; // a coarse sphere: neighbors meet at about 25 degrees
  o.SurfaceCollapseMaxDeviation = 0.3;
  av::SimplexMesh m = start;
  const av::MeshImprovementResult r = av::ImproveMesh(m, SphereMetric(start), nullptr, o);
  std::cerr << "sphere: worst " << r.WorstBefore << " -> " << r.WorstAfter << ", flips "
            << r.NumFlips22 << ", moves " << r.NumSmoothed << ", splits " << r.NumSplits
            << ", collapses " << r.NumCollapses << std::endl;
  AV_CHECK(r.Supported);
  AV_CHECK(CheckSphereRun(m, r).Ok);
  AV_CHECK_MSG(
    WorstAngle(m) > WorstAngle(start) + 5.0, WorstAngle(start) << " -> " << WorstAngle(m));
  AV_CHECK(r.NumSmoothed > 0);

  // Without the surface, surface triangles are left alone.
  av::SimplexMesh u = start;
  const av::MeshImprovementResult ur = av::ImproveMesh(u, SphereMetric(start), nullptr);
  AV_CHECK(!ur.Supported && u.Points == start.Points && u.Cells == start.Cells);

  av::MeshImprovementOptions worsening = o;
  worsening.AcceptWorsening = true;
  worsening.TargetAngle = 80.0;
  av::SimplexMesh w = start;
  const av::MeshImprovementResult wr = av::ImproveMesh(w, SphereMetric(start), nullptr, worsening);
  std::cerr << "(expected) worsening sphere run: " << wr.WorstBefore << " -> " << wr.WorstAfter
            << std::endl;
  AV_CHECK_MSG(!CheckSphereRun(w, wr).Ok, "the checks miss a worsening run");
}
// The roof z = 1 - |y| (a 90-degree ridge along y = 0): the closest point of the side of x,
// its normal and the isotropic metric of that plane.
bool PlaceOnRoof(std::int32_t, const double* x, double* placed, double* normal, double* m)
{
  const double side = x[1] >= 0.0 ? 1.0 : -1.0;
  const Eigen::Vector3d n = Eigen::Vector3d(0.0, side, 1.0).normalized();
  const Eigen::Vector3d p = Eigen::Map<const Eigen::Vector3d>(x);
  const Eigen::Vector3d q = p - n * (p - Eigen::Vector3d(0.0, 0.0, 1.0)).dot(n);
  for (int d = 0; d < 3; ++d)
  {
    placed[d] = q[d];
    normal[d] = n[d];
  }
  const double packed[6] = { 1, 1, 1, 0, 0, 0 };
  std::copy(packed, packed + 6, m);
  return true;
}

// A ridge vertex placed badly along the ridge (x = 0.3 between 0 and 2): with
// ProjectToFeatureLine it slides along the ridge, staying exactly on it, the worst angle rises
// and every ridge edge stays; without it, it stays where it is.
void TestCreaseSlide()
{
  const double ridge[5] = { 0.0, 0.3, 2.0, 3.0, 4.0 };
  av::SimplexMesh m;
  m.AmbientDim = 3;
  m.SimplexDim = 2;
  for (double x : ridge)
    m.Points.insert(m.Points.end(), { x, 0.0, 1.0 }); // 0..4
  for (int side = 0; side < 2; ++side)
    for (int i = 0; i <= 4; ++i)
      m.Points.insert(m.Points.end(), { double(i), side == 0 ? 1.0 : -1.0, 0.0 }); // 5..9, 10..14
  // Zip the ridge with each row, by x; each triangle oriented with an upward normal.
  auto add = [&](std::int32_t a, std::int32_t b, std::int32_t c)
  {
    const Eigen::Vector3d n = (At(m, b) - At(m, a)).cross(At(m, c) - At(m, a));
    if (n.z() > 0.0)
      m.Cells.insert(m.Cells.end(), { a, b, c });
    else
      m.Cells.insert(m.Cells.end(), { a, c, b });
  };
  for (int side = 0; side < 2; ++side)
  {
    const std::int32_t row = side == 0 ? 5 : 10;
    int i = 0, j = 0;
    while (i < 4 || j < 4)
    {
      const bool ridgeNext = j == 4 || (i < 4 && ridge[i + 1] <= double(j + 1));
      if (ridgeNext)
      {
        add(i, i + 1, row + j);
        ++i;
      }
      else
      {
        add(i, row + j, row + j + 1);
        ++j;
      }
    }
  }
  std::vector<std::uint8_t> fixed(m.NumPoints(), 0);
  fixed[0] = fixed[4] = 1; // the ridge's ends (corners)
  fixed[1] = fixed[2] = fixed[3] = av::FeatureLinePoint;
  av::MeshImprovementOptions o;
  o.PlacePoint = PlaceOnRoof;
  o.ProjectToFeatureLine = [](std::int32_t, const double* x, double* placed, double* tangent)
  {
    placed[0] = std::min(4.0, std::max(0.0, x[0]));
    placed[1] = 0.0;
    placed[2] = 1.0;
    tangent[0] = 1.0;
    tangent[1] = tangent[2] = 0.0;
    return true;
  };
  av::SimplexMesh slid = m;
  const av::MeshImprovementResult r = av::ImproveMesh(slid, IsotropicMetric(m.NumPoints()), &fixed, o);
  std::cerr << "crease slide: worst " << r.WorstBefore << " -> " << r.WorstAfter << ", ridge x "
            << slid.Point(1)[0] << " " << slid.Point(2)[0] << " " << slid.Point(3)[0] << std::endl;
  AV_CHECK(slid.Point(1)[0] > 0.5 && slid.Point(1)[0] < slid.Point(2)[0]);
  bool onRidge = true;
  for (int v = 0; v < 5; ++v)
    onRidge = onRidge && slid.Point(v)[1] == 0.0 && slid.Point(v)[2] == 1.0;
  AV_CHECK(onRidge);
  AV_CHECK(r.WorstAfter > r.WorstBefore + 5.0);
  const auto edges = EdgeUse(slid);
  for (std::int32_t v = 0; v < 4; ++v)
    AV_CHECK_MSG(edges.count({ v, v + 1 }) && edges.at({ v, v + 1 }) == 2, "ridge edge " << v);
  AV_CHECK(slid.Point(0)[0] == 0.0 && slid.Point(4)[0] == 4.0);

  av::MeshImprovementOptions still = o;
  still.ProjectToFeatureLine = nullptr;
  av::SimplexMesh kept = m;
  av::ImproveMesh(kept, IsotropicMetric(m.NumPoints()), &fixed, still);
  AV_CHECK(std::equal(kept.Points.begin(), kept.Points.begin() + 15, m.Points.begin()));
}
} // namespace

int TestTriangleMeshImprovement(int, char*[])
{
  TestCreaseSlide();
  TestCollapse();
  TestSplit();
  TestPlanarGrid();
  TestMeanSmoothing();
  TestSphere();
  return AV_TEST_RESULT();
}
