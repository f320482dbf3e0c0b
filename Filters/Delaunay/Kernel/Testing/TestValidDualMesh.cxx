// SPDX-License-Identifier: BSD-3-Clause
// The valid final mesh where the restricted Delaunay dual is not (ValidDualMesh.h): on a
// folded cube whose dual keeps inverted cells (repair off), the replaced mesh has every tet
// positive, every face shared by at most two tets, lies in the domain and, the metric being
// constant, is the metric's Delaunay mesh (Delaunay in the mean metric); the metric Delaunay flips
// (MetricDelaunayFlips.h) keep the mesh valid and its volume exactly, and remove most faces that
// violate the metric's Delaunay criterion; on two cubes that touch without shared points (a
// contact assembly) no tet of the replacement joins sites of the two bodies.
#include "AnisoTestChecks.h"
#include "FoldedTestCases.h"
#include "MeshQuality.h"
#include "MeshTopology.h"
#include "MeshingPipeline.h"
#include "MetricDelaunayFlips.h"
#include "StructuredMeshes.h"
#include "TetMesher.h"
#include "ValidDualMesh.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <iostream>
#include <map>
#include <random>

using namespace av_test;

namespace
{

double SignedVolume(const av::SimplexMesh& m, std::size_t c)
{
  const std::int32_t* v = m.Cell(c);
  const Eigen::Map<const Eigen::Vector3d> a(m.Point(v[0])), b(m.Point(v[1])), cc(m.Point(v[2])),
    d(m.Point(v[3]));
  return (b - a).dot((cc - a).cross(d - a)) / 6.0;
}

/// Faces by the number of tets that hold them: [1] boundary, [2] interior, [3] more.
std::array<std::size_t, 4> FaceSharing(const av::SimplexMesh& m)
{
  const std::vector<av::CellFacet> f = av::SortedCellFacets(m);
  std::array<std::size_t, 4> h{ 0, 0, 0, 0 };
  for (std::size_t i = 0; i < f.size();)
  {
    std::size_t j = i + 1;
    while (j < f.size() && f[j].Vertices == f[i].Vertices)
      ++j;
    ++h[std::min<std::size_t>(j - i, 3)];
    i = j;
  }
  return h;
}

double TotalVolume(const av::SimplexMesh& m)
{
  double v = 0.0;
  for (std::size_t c = 0; c < m.NumCells(); ++c)
    v += SignedVolume(m, c);
  return v;
}

av::SimplexMesh AsMesh(const av::RestrictedDelaunayMesh& d)
{
  av::SimplexMesh m;
  m.AmbientDim = 3;
  m.SimplexDim = 3;
  m.Points = d.Points;
  m.Cells = d.Cells;
  return m;
}

std::size_t NonDelaunayFaces(const av::SimplexMesh& m, const Eigen::Matrix3d& s);

/// `dual` without the cells of every `stride`-th site (those sites are then in no cell).
av::RestrictedDelaunayMesh WithoutCellsOfSites(const FoldedCase& c,
  const av::RestrictedDelaunayMesh& dual,
  const av::SiteSet& sites,
  std::size_t stride)
{
  av::RestrictedDelaunayMesh holed = dual;
  std::vector<std::int32_t> cells;
  for (std::size_t t = 0; t < dual.NumCells(); ++t)
  {
    const std::int32_t* v = dual.Cells.data() + 4 * t;
    if (std::none_of(v, v + 4, [&](std::int32_t s) { return s % stride == 0; }))
      cells.insert(cells.end(), v, v + 4);
  }
  holed.Cells = std::move(cells);
  av::RecountFinalDual(c.Mesh, holed, sites);
  return holed;
}

/// A dual of positive cells without non-manifold faces but with holes (sites in no cell, as a
/// domain thinner than the cells gives) is replaced when more than 1 % of its sites are left
/// out, and kept below that.
void TestHoledDualIsReplaced(const FoldedCase& c,
  const av::RestrictedDelaunayMesh& valid,
  const av::SiteSet& sites)
{
  const std::size_t numSites = valid.Points.size() / 3;
  const std::vector<std::int32_t> adjacency = av::ComputeElementAdjacency(c.Mesh);
  av::RestrictedDelaunayMesh holed = WithoutCellsOfSites(c, valid, sites, 10);
  AV_CHECK(holed.NumInverted == 0 && holed.NumNonManifoldFaces == 0);
  AV_CHECK_MSG(holed.NumUnusedSites >= numSites / 10, holed.NumUnusedSites << " unused");
  AV_CHECK(av::DualNeedsReplacement(holed));
  const std::size_t holedCells = holed.NumCells();
  const av::ValidDualResult filled = av::MakeDualValid(c.Mesh, adjacency, sites, nullptr, holed);
  AV_CHECK(filled.Replaced && filled.UnusedSites >= numSites / 10);
  AV_CHECK_MSG(holed.NumUnusedSites == 0 && holed.NumInverted == 0 &&
      holed.NumNonManifoldFaces == 0 && holed.NumCells() > holedCells,
    holed.NumUnusedSites << " unused site(s), " << holed.NumCells() << " cells");

  // One site of 150 left out (below 1 %) is not a reason to replace the dual.
  av::RestrictedDelaunayMesh one = WithoutCellsOfSites(c, valid, sites, numSites + 1);
  AV_CHECK(one.NumUnusedSites == 1 && !av::DualNeedsReplacement(one));
  const std::vector<std::int32_t> before = one.Cells;
  AV_CHECK(
    !av::MakeDualValid(c.Mesh, adjacency, sites, nullptr, one).Replaced && one.Cells == before);
}

void TestFoldedCubeGetsValidMesh()
{
  const FoldedCase c = FoldedCube(0.2, 8.0, 150, 3);
  av::MeshingPipelineOptions o;
  o.Repair = false; // keep the dual's inverted cells
  o.ImproveMesh = false;
  o.ValidDual = false;
  const av::MeshingPipelineResult plain = av::RunMeshingPipeline(c.Mesh, c.Embedding, c.Sites, o);
  AV_CHECK_MSG(plain.Repaired.Delaunay.NumInverted > 0, "the case must have an invalid dual");
  AV_CHECK(!plain.ValidDual.Replaced);

  o.ValidDual = true;
  av::MetricField metric; // anisotropic, so that the flips have work to do
  for (std::size_t i = 0; i < c.Mesh.NumPoints(); ++i)
    metric.Values.insert(metric.Values.end(), { 36.0, 1.0, 1.0, 0.0, 0.0, 0.0 });
  o.Metric = &metric;
  const av::MeshingPipelineResult r = av::RunMeshingPipeline(c.Mesh, c.Embedding, c.Sites, o);
  const av::RestrictedDelaunayMesh& d = r.Repaired.Delaunay;
  AV_CHECK(r.ValidDual.Replaced && r.ValidDual.InvalidCells == plain.Repaired.Delaunay.NumInverted);
  AV_CHECK(d.NumInverted == 0 && d.NumNonManifoldFaces == 0);
  const av::SimplexMesh m = AsMesh(d);
  std::size_t nonPositive = 0;
  for (std::size_t t = 0; t < m.NumCells(); ++t)
    nonPositive += !(SignedVolume(m, t) > 0.0);
  AV_CHECK_MSG(nonPositive == 0, nonPositive << " tet(s) not positive");
  const auto sharing = FaceSharing(m);
  AV_CHECK_MSG(sharing[3] == 0, sharing[3] << " face(s) of more than two tets");
  // Inside the unit cube (the domain is convex: the sites' hull) and most of it.
  const double vol = TotalVolume(m);
  AV_CHECK_MSG(vol <= 1.0 + 1e-12 && vol > 0.6, "volume " << vol);
  // Every site is used (random sites inside the cube are all vertices of their hull's mesh).
  AV_CHECK_MSG(d.NumUnusedSites == 0, d.NumUnusedSites << " unused site(s)");
  std::cout << "folded cube: " << plain.Repaired.Delaunay.NumInverted
            << " inverted -> valid mesh of " << m.NumCells() << " tets, volume " << vol
            << ", flips 2-3 " << r.ValidDual.Flips.NumFlips23 << " 3-2 "
            << r.ValidDual.Flips.NumFlips32 << std::endl;

  // The boundary sliver peel keeps the domain: it removes at most 0.2 % of the volume.
  std::cout << "  peeled " << r.ValidDual.BoundarySlivers << " boundary sliver(s), "
            << r.ValidDual.PeeledVolume << " of " << r.ValidDual.VolumeBeforePeel << std::endl;
  AV_CHECK(r.ValidDual.PeeledVolume <= 2e-3 * r.ValidDual.VolumeBeforePeel);
  AV_CHECK(r.ValidDual.BoundarySlivers == 0 || r.ValidDual.PeeledVolume > 0.0);
  AV_CHECK_NEAR(vol, r.ValidDual.VolumeBeforePeel - r.ValidDual.PeeledVolume, 1e-12);

  // A valid dual is left as it is.
  av::RestrictedDelaunayMesh copy = d;
  copy.NumInverted = 0;
  const av::ValidDualResult again = av::MakeDualValid(c.Mesh, {}, r.Repaired.Sites, nullptr, copy);
  AV_CHECK(!again.Replaced && copy.Cells == d.Cells);
  TestHoledDualIsReplaced(c, d, r.Repaired.Sites);
  // With a constant metric the Delaunay tetrahedralization in the mean metric is already the
  // metric's Delaunay mesh: no face violates the criterion, no flip is needed.
  Eigen::Matrix3d root = Eigen::Matrix3d::Identity();
  root(0, 0) = 6.0;
  const std::size_t nonDelaunay = NonDelaunayFaces(m, root);
  AV_CHECK_MSG(nonDelaunay == 0, nonDelaunay << " face(s) not Delaunay in the metric");
  AV_CHECK(r.ValidDual.Flips.NumFlips23 + r.ValidDual.Flips.NumFlips32 == 0);
}

/// Faces abc (apexes d, e) with e strictly in the circumsphere of abcd in the constant metric
/// S^2 (S applied to the points).
std::size_t NonDelaunayFaces(const av::SimplexMesh& m, const Eigen::Matrix3d& s)
{
  std::map<std::array<std::int32_t, 3>, std::vector<std::int32_t>> apex;
  for (const av::CellFacet& f : av::SortedCellFacets(m))
    for (int a = 0; a < 4; ++a)
    {
      const std::int32_t v = m.Cell(static_cast<std::size_t>(f.Cell))[a];
      if (std::find(f.Vertices.begin(), f.Vertices.end(), v) == f.Vertices.end())
        apex[f.Vertices].push_back(v);
    }
  std::size_t bad = 0;
  for (const auto& kv : apex)
  {
    if (kv.second.size() != 2)
      continue;
    Eigen::Vector3d q[5];
    const std::int32_t ids[5] = {
      kv.first[0], kv.first[1], kv.first[2], kv.second[0], kv.second[1]
    };
    for (int i = 0; i < 5; ++i)
      q[i] = s * Eigen::Map<const Eigen::Vector3d>(m.Point(ids[i]));
    Eigen::Matrix3d a;
    Eigen::Vector3d rhs;
    for (int i = 1; i < 4; ++i)
    {
      a.row(i - 1) = 2.0 * (q[i] - q[0]).transpose();
      rhs[i - 1] = q[i].squaredNorm() - q[0].squaredNorm();
    }
    const Eigen::Vector3d x = a.fullPivLu().solve(rhs);
    bad += (q[4] - x).squaredNorm() < (q[0] - x).squaredNorm() * (1.0 - 1e-6);
  }
  return bad;
}

void TestFlipsTowardsConstantMetric()
{
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> pts;
  for (int i = 0; i < 400; ++i)
    for (int d = 0; d < 3; ++d)
      pts.push_back(u(rng));
  av::SimplexMesh m = av::DelaunayOfPoints(pts);
  // Metric diag(36, 1, 1): unit length is 1/6 along x.
  Eigen::Matrix3d s = Eigen::Matrix3d::Identity();
  s(0, 0) = 6.0;
  av::MetricField metric;
  for (std::size_t i = 0; i < m.NumPoints(); ++i)
    metric.Values.insert(metric.Values.end(), { 36.0, 1.0, 1.0, 0.0, 0.0, 0.0 });
  const std::size_t before = NonDelaunayFaces(m, s);
  const double volBefore = TotalVolume(m);
  const auto sharingBefore = FaceSharing(m);
  const av::MetricDelaunayFlipResult r = av::FlipTowardsMetricDelaunay(m, metric);
  const std::size_t after = NonDelaunayFaces(m, s);
  std::cout << "constant metric: non-Delaunay faces " << before << " -> " << after << " (2-3 "
            << r.NumFlips23 << ", 3-2 " << r.NumFlips32 << ")" << std::endl;
  AV_CHECK(before > 100);
  AV_CHECK_MSG(after * 10 < before, "flips left " << after << " of " << before);
  AV_CHECK(!r.Capped);
  std::size_t nonPositive = 0;
  for (std::size_t t = 0; t < m.NumCells(); ++t)
    nonPositive += !(SignedVolume(m, t) > 0.0);
  AV_CHECK_MSG(nonPositive == 0, nonPositive << " tet(s) not positive");
  AV_CHECK_NEAR(TotalVolume(m), volBefore, 1e-12 * volBefore);
  const auto sharing = FaceSharing(m);
  AV_CHECK(sharing[3] == 0);
  AV_CHECK_MSG(
    sharing[1] == sharingBefore[1], "boundary faces " << sharingBefore[1] << " -> " << sharing[1]);
}

} // namespace

/// Two 5 x 5 x 5 grids, [0,1]^3 and [0,1]^2 x [1,2], the second with its own copy of z = 1, and
/// a site at the centroid of every third tet: a joint tetrahedralization of the sites fills the
/// gap between the bodies' sites with tets whose centroid is in one of them.
void TestBodiesMeshedApart()
{
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 }, lo2[3] = { 0, 0, 1 }, hi2[3] = { 1, 1, 2 };
  av::SimplexMesh mesh = av::MakeKuhnTetGrid(5, 5, 5, lo, hi);
  const av::SimplexMesh upper = av::MakeKuhnTetGrid(5, 5, 5, lo2, hi2);
  const std::int32_t offset = static_cast<std::int32_t>(mesh.NumPoints());
  mesh.Points.insert(mesh.Points.end(), upper.Points.begin(), upper.Points.end());
  for (std::int32_t id : upper.Cells)
    mesh.Cells.push_back(id + offset);
  std::vector<std::int32_t> body;
  AV_CHECK(av::LabelBodies(mesh, body) == 2u);
  av::SiteSet sites;
  sites.Dim = 3;
  av::RestrictedDelaunayMesh rdt;
  for (std::size_t c = 0; c < mesh.NumCells(); c += 3)
  {
    sites.CellIds.push_back(static_cast<std::int32_t>(c));
    for (int d = 0; d < 3; ++d)
    {
      double x = 0.0;
      for (int a = 0; a < 4; ++a)
        x += 0.25 * mesh.Point(static_cast<std::size_t>(mesh.Cell(c)[a]))[d];
      sites.Coords.push_back(x);
      rdt.Points.push_back(x);
    }
    sites.Bary.insert(sites.Bary.end(), { 0.25, 0.25, 0.25, 0.25 });
  }
  rdt.NumUnusedSites = sites.NumSites(); // no cell: replaced
  const av::ValidDualResult r =
    av::MakeDualValid(mesh, av::ComputeElementAdjacency(mesh), sites, nullptr, rdt);
  AV_CHECK(r.Replaced && rdt.NumCells() > 0 && rdt.NumInverted == 0);
  std::size_t across = 0;
  for (std::size_t c = 0; c < rdt.NumCells(); ++c)
  {
    auto bodyOf = [&](int a)
    { return body[static_cast<std::size_t>(mesh.Cell(sites.CellIds[rdt.Cells[4 * c + a]])[0])]; };
    across += bodyOf(1) != bodyOf(0) || bodyOf(2) != bodyOf(0) || bodyOf(3) != bodyOf(0);
  }
  AV_CHECK_MSG(across == 0, across << " tet(s) join the two bodies");
}

int TestValidDualMesh(int, char*[])
{
  TestBodiesMeshedApart();
  TestFoldedCubeGetsValidMesh();
  TestFlipsTowardsConstantMetric();
  return AV_TEST_RESULT();
}
