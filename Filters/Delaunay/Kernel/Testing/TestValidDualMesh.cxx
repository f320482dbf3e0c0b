// SPDX-License-Identifier: BSD-3-Clause
// The valid final mesh where the restricted Delaunay dual is not (ValidDualMesh.h): on a
// folded cube whose dual keeps inverted cells (repair off), the replaced mesh has every tet
// positive, every face shared by at most two tets, lies in the domain and, the metric being
// constant, is nearly the metric's Delaunay mesh away from the dual's kept cells; the metric
// Delaunay flips (MetricDelaunayFlips.h) keep the mesh valid and its volume exactly, and remove
// most faces that violate the metric's Delaunay criterion; on two cubes that touch without shared
// points (a contact assembly) no tet of the replacement joins sites of the two bodies. The
// replacement keeps the dual's valid cells: TetGen's constrained Delaunay tetrahedralization holds
// every tet whose faces it is given, and the flips never remove a target tet and create new ones.
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

std::size_t NonDelaunayFaces(const av::SimplexMesh& m,
  const Eigen::Matrix3d& s,
  const std::vector<std::array<std::int32_t, 4>>* skip = nullptr,
  std::size_t* numInterior = nullptr);
std::vector<std::array<std::int32_t, 4>> SortedTets(const av::SimplexMesh& m);

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
  // The dual's valid cells away from its bad ones are all kept.
  AV_CHECK_MSG(r.ValidDual.TargetCells > 0 && r.ValidDual.KeptCells == r.ValidDual.TargetCells &&
      r.ValidDual.Constrained,
    r.ValidDual.KeptCells << " of " << r.ValidDual.TargetCells << " valid cells kept");
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
  // With a constant metric the constrained Delaunay tetrahedralization in the mean metric is
  // nearly the metric's away from the kept cells: TetGen without Steiner points (-S0) leaves a
  // few faces between two tets that are not cells of the dual (not constrained) that fail the
  // criterion and that no 2-3 / 3-2 flip can change (48 of 1116 here); at most 10 %.
  Eigen::Matrix3d root = Eigen::Matrix3d::Identity();
  root(0, 0) = 6.0;
  const auto dualCells = SortedTets(AsMesh(plain.Repaired.Delaunay));
  std::size_t free = 0;
  const std::size_t nonDelaunay = NonDelaunayFaces(m, root, &dualCells, &free);
  std::cout << "  " << nonDelaunay << " of " << free << " unconstrained interior faces not Delaunay"
            << std::endl;
  AV_CHECK_MSG(free > 500 && nonDelaunay * 10 <= free,
    nonDelaunay << " of " << free << " face(s) not Delaunay in the metric");
}

/// Faces abc (apexes d, e) with e strictly in the circumsphere of abcd in the constant metric
/// S^2 (S applied to the points); with `skip` (sorted quadruples), not faces of those tets.
std::size_t NonDelaunayFaces(const av::SimplexMesh& m,
  const Eigen::Matrix3d& s,
  const std::vector<std::array<std::int32_t, 4>>* skip,
  std::size_t* numInterior)
{
  std::size_t interior = 0;
  std::map<std::array<std::int32_t, 3>, std::vector<std::int32_t>> apex;
  std::vector<std::array<std::int32_t, 3>> skipped;
  for (const av::CellFacet& f : av::SortedCellFacets(m))
  {
    const std::int32_t* cell = m.Cell(static_cast<std::size_t>(f.Cell));
    std::array<std::int32_t, 4> q{ cell[0], cell[1], cell[2], cell[3] };
    std::sort(q.begin(), q.end());
    if (skip && std::binary_search(skip->begin(), skip->end(), q))
      skipped.push_back(f.Vertices);
    for (int a = 0; a < 4; ++a)
    {
      const std::int32_t v = cell[a];
      if (std::find(f.Vertices.begin(), f.Vertices.end(), v) == f.Vertices.end())
        apex[f.Vertices].push_back(v);
    }
  }
  for (const auto& f : skipped)
    apex.erase(f);
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
    ++interior;
  }
  if (numInterior)
    *numInterior = interior;
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

/// Tets of `m` as sorted quadruples, sorted.
std::vector<std::array<std::int32_t, 4>> SortedTets(const av::SimplexMesh& m)
{
  std::vector<std::array<std::int32_t, 4>> out;
  for (std::size_t c = 0; c < m.NumCells(); ++c)
  {
    std::array<std::int32_t, 4> q{ m.Cell(c)[0], m.Cell(c)[1], m.Cell(c)[2], m.Cell(c)[3] };
    std::sort(q.begin(), q.end());
    out.push_back(q);
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::size_t CountIn(const std::vector<std::array<std::int32_t, 4>>& tets,
  const std::vector<std::array<std::int32_t, 4>>& sortedSet)
{
  std::size_t n = 0;
  for (const auto& t : tets)
    n += std::binary_search(sortedSet.begin(), sortedSet.end(), t);
  return n;
}

/// 300 random points; targets: the middle slab's tets of their Delaunay tetrahedralization in
/// the metric diag(36, 1, 1) (another valid mesh of the same hull: a linear map keeps it).
struct TargetCase
{
  std::vector<double> Points;
  std::vector<std::array<std::int32_t, 4>> Targets;
};

TargetCase MakeTargetCase()
{
  TargetCase c;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 300; ++i)
    for (int d = 0; d < 3; ++d)
      c.Points.push_back(u(rng));
  std::vector<double> mapped = c.Points;
  for (std::size_t i = 0; i < mapped.size(); i += 3)
    mapped[i] *= 6.0;
  av::SimplexMesh other = av::DelaunayOfPoints(mapped);
  other.Points = c.Points;
  av::SimplexMesh slab = other;
  slab.Cells.clear();
  for (std::size_t t = 0; t < other.NumCells(); ++t)
  {
    double x = 0.0;
    for (int a = 0; a < 4; ++a)
      x += 0.25 * other.Point(other.Cell(t)[a])[0];
    if (x > 0.3 && x < 0.7)
      slab.Cells.insert(slab.Cells.end(), other.Cell(t), other.Cell(t) + 4);
  }
  c.Targets = SortedTets(slab);
  return c;
}

/// Constrained by the targets' faces, TetGen's tetrahedralization holds every target tet (the
/// plain Delaunay one holds few of them), fills the same hull and stays valid.
void TestConstrainedDelaunayKeepsTargets()
{
  const TargetCase c = MakeTargetCase();
  std::vector<std::int32_t> faces;
  for (const auto& q : c.Targets)
    for (int skip = 0; skip < 4; ++skip)
      for (int a = 0; a < 4; ++a)
        if (a != skip)
          faces.push_back(q[a]);
  const av::SimplexMesh plain = av::DelaunayOfPoints(c.Points);
  const av::SimplexMesh kept = av::ConstrainedDelaunayOfPoints(c.Points, faces);
  const std::size_t inPlain = CountIn(c.Targets, SortedTets(plain));
  const std::size_t inKept = CountIn(c.Targets, SortedTets(kept));
  std::cout << "constrained Delaunay: " << inKept << " of " << c.Targets.size()
            << " target tets (plain Delaunay: " << inPlain << ")" << std::endl;
  AV_CHECK(c.Targets.size() > 200);
  AV_CHECK_MSG(inPlain < c.Targets.size() * 8 / 10, "the targets must differ from Delaunay");
  AV_CHECK(inKept == c.Targets.size());
  std::size_t nonPositive = 0;
  for (std::size_t t = 0; t < kept.NumCells(); ++t)
    nonPositive += !(SignedVolume(kept, t) > 0.0);
  AV_CHECK(nonPositive == 0 && FaceSharing(kept)[3] == 0);
  AV_CHECK_NEAR(TotalVolume(kept), TotalVolume(plain), 1e-12);
  // Bad input: a face id out of range.
  bool threw = false;
  try
  {
    av::ConstrainedDelaunayOfPoints(c.Points, { 0, 1, 300 });
  }
  catch (const av::InputError&)
  {
    threw = true;
  }
  AV_CHECK(threw);
  // Faces that cross (TetGen fails on them, and TetGen 1.5 may crash rather than report it; it
  // runs in a child process): an InputError, and the caller goes on. Then the same call works.
  std::vector<double> pts = c.Points;
  const std::vector<double> flat = { 0.3, 0.3, 0.5, 0.6, 0.3, 0.5, 0.45, 0.6, 0.5 };
  const std::vector<double> piercing = { 0.45, 0.45, 0.2, 0.45, 0.45, 0.8, 0.48, 0.46, 0.8 };
  pts.insert(pts.end(), flat.begin(), flat.end());
  pts.insert(pts.end(), piercing.begin(), piercing.end());
  const std::int32_t b = static_cast<std::int32_t>(c.Points.size() / 3);
  threw = false;
  try
  {
    av::ConstrainedDelaunayOfPoints(pts, { b, b + 1, b + 2, b + 3, b + 4, b + 5 });
  }
  catch (const av::InputError& e)
  {
    threw = true;
    std::cout << "crossing faces: " << e.what() << std::endl;
  }
  AV_CHECK(threw);
  AV_CHECK(av::ConstrainedDelaunayOfPoints(c.Points, faces).NumCells() == kept.NumCells());
}

/// With targets, flips in an isotropic metric (whose Delaunay mesh the start already is, so
/// without targets nothing flips) create target tets, remove none, keep the mesh valid and
/// its volume.
void TestFlipsTowardsTargets()
{
  const TargetCase c = MakeTargetCase();
  av::SimplexMesh m = av::DelaunayOfPoints(c.Points);
  av::MetricField metric;
  for (std::size_t i = 0; i < m.NumPoints(); ++i)
    metric.Values.insert(metric.Values.end(), { 1.0, 1.0, 1.0, 0.0, 0.0, 0.0 });
  av::SimplexMesh untouched = m;
  const av::MetricDelaunayFlipResult none = av::FlipTowardsMetricDelaunay(untouched, metric);
  AV_CHECK(none.NumFlips23 + none.NumFlips32 == 0 && untouched.Cells == m.Cells);
  const auto before = SortedTets(m);
  std::vector<std::array<std::int32_t, 4>> present;
  for (const auto& t : c.Targets)
    if (std::binary_search(before.begin(), before.end(), t))
      present.push_back(t);
  const double volume = TotalVolume(m);
  const av::MetricDelaunayFlipResult r = av::FlipTowardsMetricDelaunay(m, metric, c.Targets);
  const auto after = SortedTets(m);
  const std::size_t inAfter = CountIn(c.Targets, after);
  std::cout << "flips towards targets: " << present.size() << " -> " << inAfter << " of "
            << c.Targets.size() << " (" << r.NumTargetFlips << " target flips)" << std::endl;
  AV_CHECK(r.NumTargetFlips > 0 && inAfter > present.size() + 10);
  AV_CHECK_MSG(CountIn(present, after) == present.size(), "a target tet was flipped away");
  std::size_t nonPositive = 0;
  for (std::size_t t = 0; t < m.NumCells(); ++t)
    nonPositive += !(SignedVolume(m, t) > 0.0);
  AV_CHECK(nonPositive == 0 && FaceSharing(m)[3] == 0);
  AV_CHECK_NEAR(TotalVolume(m), volume, 1e-12 * volume);
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
  TestConstrainedDelaunayKeepsTargets();
  TestFlipsTowardsTargets();
  return AV_TEST_RESULT();
}
