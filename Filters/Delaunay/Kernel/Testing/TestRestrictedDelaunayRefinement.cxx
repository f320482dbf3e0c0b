// SPDX-License-Identifier: BSD-3-Clause
// Repair of the restricted Delaunay mesh by Voronoi-vertex insertion: a wavy 8D embedding with
// few sites has inverted dual elements; the repair must remove all of them (checked in input
// space, independently of the kernel's flags), keep the input sites first and unchanged, insert
// only at Voronoi vertices of inverted cells, and leave a valid complex whose Voronoi diagram
// still partitions the domain.
#include "RestrictedDelaunayRefinement.h"
#include "AnisoTestChecks.h"
#include "FoldedTestCases.h"
#include "VoronoiTestMeshes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <map>
#include <set>

using namespace av_test;

namespace
{
using Key = std::array<int, 4>;

// Euler characteristic of the complex (V - E + F [- T]), counting only used vertices, and the
// largest number of cells sharing a facet.
void Topology(const av::RestrictedDelaunayMesh& d, long& euler, int& maxFacetShare)
{
  const int nv = d.SimplexDim + 1;
  std::set<Key> simplices[4];
  std::map<Key, int> facetCount;
  for (std::size_t c = 0; c < d.NumCells(); ++c)
  {
    int ids[4];
    for (int a = 0; a < nv; ++a)
      ids[a] = d.Cells[c * nv + a];
    std::sort(ids, ids + nv);
    // Every sub-simplex, by bit mask.
    for (int mask = 1; mask < (1 << nv); ++mask)
    {
      Key key = { -1, -1, -1, -1 };
      int n = 0;
      for (int a = 0; a < nv; ++a)
        if (mask & (1 << a))
          key[n++] = ids[a];
      simplices[n - 1].insert(key);
      if (n == nv - 1)
        ++facetCount[key];
    }
  }
  euler = 0;
  for (int q = 0; q < nv; ++q)
    euler += (q % 2 ? -1L : 1L) * static_cast<long>(simplices[q].size());
  maxFacetShare = 0;
  for (const auto& f : facetCount)
    maxFacetShare = std::max(maxFacetShare, f.second);
}

double Dist2(const av::SiteSet& s, std::size_t i, const double* p)
{
  double d2 = 0.0;
  for (int d = 0; d < s.Dim; ++d)
    d2 += (s.At(i)[d] - p[d]) * (s.At(i)[d] - p[d]);
  return d2;
}

// Properties every repaired result must have.
void CheckRepaired(const av::SimplexMesh& m, const av::Embedding& e, const av::SiteSet& s,
  const av::DelaunayRepairResult& r, const char* what)
{
  const std::size_t n = s.NumSites(), nt = r.Sites.NumSites();
  const int nv = m.SimplexDim + 1;
  std::cout << what << ": inverted " << r.InitialInverted << " -> " << r.Delaunay.NumInverted
            << ", non-manifold faces " << r.InitialNonManifoldFaces << " -> "
            << r.Delaunay.NumNonManifoldFaces << ", inserted " << r.NumInserted << " in "
            << r.Rounds << " round(s), skipped " << r.NumSkipped << std::endl;
  AV_CHECK(r.InitialInverted > 0); // the case must exercise the repair
  AV_CHECK(r.Converged);
  AV_CHECK(r.Delaunay.NumInverted == 0);
  AV_CHECK_MSG(NegativeCells(r.Delaunay) == 0, what);
  AV_CHECK(r.NumInserted > 0 && r.Rounds > 0);
  AV_CHECK(r.NumInputSites == n && nt == n + r.NumInserted);
  std::size_t sum = 0;
  for (std::size_t v : r.InsertedPerRound)
    sum += v;
  AV_CHECK(sum == r.NumInserted && r.InsertedPerRound.size() == std::size_t(r.Rounds));
  AV_CHECK(r.InvertedPerRound.size() == std::size_t(r.Rounds) + 1 &&
    r.InvertedPerRound.front() == r.InitialInverted && r.InvertedPerRound.back() == 0);
  // Input sites first and bit-identical.
  AV_CHECK(std::equal(s.Coords.begin(), s.Coords.end(), r.Sites.Coords.begin()));
  AV_CHECK(std::equal(s.CellIds.begin(), s.CellIds.end(), r.Sites.CellIds.begin()));
  AV_CHECK(std::equal(s.Bary.begin(), s.Bary.end(), r.Sites.Bary.begin()));
  // Inserted sites lie on the mesh: valid barycentric coordinates, embedded = combination.
  for (std::size_t i = n; i < nt; ++i)
  {
    const std::int32_t c = r.Sites.CellIds[i];
    AV_CHECK(c >= 0 && std::size_t(c) < m.NumCells());
    double bsum = 0.0;
    for (int a = 0; a < 4; ++a)
    {
      AV_CHECK(r.Sites.Bary[4 * i + a] >= 0.0);
      bsum += r.Sites.Bary[4 * i + a];
    }
    AV_CHECK_NEAR(bsum, 1.0, 1e-12);
    for (int d = 0; d < e.Dim; ++d)
    {
      double x = 0.0;
      for (int a = 0; a < nv; ++a)
        x += r.Sites.Bary[4 * i + a] * e.At(m.Cell(c)[a])[d];
      AV_CHECK_NEAR(r.Sites.At(i)[d], x, 1e-12);
    }
    // Points of the dual are the sites in input space.
    for (int d = 0; d < m.AmbientDim; ++d)
      AV_CHECK(r.Delaunay.Points[i * m.AmbientDim + d] == r.Sites.At(i)[d]);
  }
  // The Voronoi diagram of the final sites still partitions the unit square / cube.
  double total = 0.0;
  for (double v : r.Voronoi.PieceMeasure)
    total += v;
  AV_CHECK_NEAR(total, 1.0, 1e-9);
  AV_CHECK(r.Voronoi.NumSites == nt && r.Voronoi.SiteMeasure.size() == nt);
  for (std::size_t i = 0; i < nt; ++i)
    AV_CHECK(r.Voronoi.SiteMeasure[i] > 0.0);
}

void TestVoronoiVertex()
{
  // Identity embedding: the dual Voronoi vertex is the circumcenter.
  const av::SimplexMesh m = TriGrid(9, 9, 0, 0, 1, 1);
  const av::Embedding e = MakeEmbedding(m, 2, nullptr);
  av::SiteSet s;
  s.Dim = 2;
  const double x[4][2] = { { 0.2, 0.2 }, { 0.6, 0.2 }, { 0.2, 0.6 }, { 0.4, 0.4 } };
  for (const auto& p : x)
    AV_CHECK(SiteAt(s, m, e, p));
  const std::int32_t ids[3] = { 0, 1, 2 };
  double b[4], r2 = -1.0;
  AV_CHECK(av::ComputeDualVoronoiVertex(m, e, s, ids, s.CellIds[3], b, r2));
  AV_CHECK_NEAR(r2, 0.08, 1e-12);
  for (int a = 0; a < 4; ++a)
    AV_CHECK_NEAR(b[a], s.Bary[12 + a], 1e-12);
  // An element that does not hold the circumcenter is refused.
  AV_CHECK(!av::ComputeDualVoronoiVertex(m, e, s, ids, s.CellIds[0], b, r2));
  // Collinear sites: no circumcenter.
  av::SiteSet c;
  c.Dim = 2;
  const double y[3][2] = { { 0.1, 0.1 }, { 0.3, 0.3 }, { 0.5, 0.5 } };
  for (const auto& p : y)
    AV_CHECK(SiteAt(c, m, e, p));
  AV_CHECK(!av::ComputeDualVoronoiVertex(m, e, c, ids, c.CellIds[1], b, r2));
}

void TestRepair2D()
{
  const auto& [m, e, s] = FoldedSquare(0.2, 12.0, 60, 1);

  // One round only: every inserted site is a Voronoi vertex of the input sites (k+1 of them
  // at the same, smallest, embedding distance) of a cell that was inverted.
  av::DelaunayRepairOptions one;
  one.MaxRounds = 1;
  const av::DelaunayRepairResult r1 = av::RepairRestrictedDelaunay(m, e, s, one);
  AV_CHECK(r1.Rounds == 1 && r1.NumInserted > 0 && r1.NumInserted <= r1.InitialInverted);
  av::DelaunayRepairOptions none;
  none.MaxRounds = 0;
  const av::DelaunayRepairResult r0 = av::RepairRestrictedDelaunay(m, e, s, none);
  AV_CHECK(r0.NumInserted == 0 && r0.Rounds == 0 && !r0.Converged);
  AV_CHECK(r0.Sites.Coords == s.Coords && r0.Delaunay.NumInverted == r0.InitialInverted);
  std::set<Key> inverted;
  for (std::size_t c = 0; c < r0.Delaunay.NumCells(); ++c)
    if (r0.Delaunay.Inverted[c])
    {
      Key key = { -1, -1, -1, -1 };
      for (int a = 0; a < 3; ++a)
        key[a] = r0.Delaunay.Cells[3 * c + a];
      std::sort(key.begin(), key.begin() + 3);
      inverted.insert(key);
    }
  for (std::size_t i = s.NumSites(); i < r1.Sites.NumSites(); ++i)
  {
    std::vector<std::pair<double, int>> d;
    for (std::size_t q = 0; q < s.NumSites(); ++q)
      d.push_back({ Dist2(s, q, r1.Sites.At(i)), int(q) });
    std::sort(d.begin(), d.end());
    AV_CHECK_NEAR(d[2].first / d[0].first, 1.0, 1e-9);
    AV_CHECK(d[3].first > d[2].first * (1 + 1e-9));
    Key key = { d[0].second, d[1].second, d[2].second, -1 };
    std::sort(key.begin(), key.begin() + 3);
    AV_CHECK(inverted.count(key) == 1);
  }

  // Inverted elements only.
  av::DelaunayRepairOptions invertedOnly;
  invertedOnly.RepairNonManifold = false;
  const av::DelaunayRepairResult r = av::RepairRestrictedDelaunay(m, e, s, invertedOnly);
  CheckRepaired(m, e, s, r, "2D inverted");
  // Deterministic, and the same when starting from the caller's round-0 diagram and dual.
  const av::DelaunayRepairResult again = av::RepairRestrictedDelaunay(m, e, s, invertedOnly);
  AV_CHECK(again.Sites.Coords == r.Sites.Coords && again.Delaunay.Cells == r.Delaunay.Cells);
  auto rvd0 = av::ComputeRestrictedVoronoi(m, e, s, invertedOnly.Voronoi);
  auto rdt0 = av::ComputeRestrictedDelaunay(m, e, s, rvd0);
  const av::DelaunayRepairResult given =
    av::RepairRestrictedDelaunay(m, e, s, rvd0, rdt0, invertedOnly);
  AV_CHECK(given.Sites.Coords == r.Sites.Coords && given.Delaunay.Cells == r.Delaunay.Cells);
  AV_CHECK(given.InitialInverted == r.InitialInverted && given.Rounds == r.Rounds);
  AV_CHECK_THROWS(av::RepairRestrictedDelaunay(m, e, r1.Sites, rvd0, rdt0)); // other sites

  // Inverted and non-manifold: a disc (Euler characteristic 1) whose facets are shared by at
  // most two triangles, no open interior facet, every site used.
  av::DelaunayRepairOptions nm;
  nm.RepairNonManifold = true;
  const av::DelaunayRepairResult rn = av::RepairRestrictedDelaunay(m, e, s, nm);
  CheckRepaired(m, e, s, rn, "2D inverted + non-manifold");
  AV_CHECK(rn.InitialNonManifoldFaces > 0);
  AV_CHECK(rn.Delaunay.NumNonManifoldFaces == 0 && rn.Delaunay.NumOpenInteriorFaces == 0);
  AV_CHECK(rn.Delaunay.NumUnusedSites == 0);
  long euler = 0;
  int share = 0;
  Topology(rn.Delaunay, euler, share);
  AV_CHECK_MSG(euler == 1, "Euler characteristic " << euler);
  AV_CHECK(share == 2);
}

void TestRepair3D()
{
  const auto& [m, e, s] = FoldedCube(0.2, 8.0, 150, 3);
  av::DelaunayRepairOptions invertedOnly;
  invertedOnly.RepairNonManifold = false;
  const av::DelaunayRepairResult r = av::RepairRestrictedDelaunay(m, e, s, invertedOnly);
  CheckRepaired(m, e, s, r, "3D inverted");
  AV_CHECK(r.Delaunay.NumNonManifoldFaces > 0); // left: the case below has work to do

  // The defaults also repair non-manifold faces, but only once no cell is inverted and never
  // at the price of inverted cells: here the non-manifold insertions invert cells again and
  // the repair stalls; it returns a state without inverted cells and with fewer non-manifold
  // faces than the inverted repair alone left.
  const av::DelaunayRepairResult rn = av::RepairRestrictedDelaunay(m, e, s);
  std::cout << "3D defaults: inverted " << rn.InitialInverted << " -> " << rn.Delaunay.NumInverted
            << ", non-manifold faces " << rn.InitialNonManifoldFaces << " -> "
            << rn.Delaunay.NumNonManifoldFaces << (rn.Stalled ? " (stalled)" : "") << std::endl;
  AV_CHECK(rn.Delaunay.NumInverted == 0 && NegativeCells(rn.Delaunay) == 0);
  AV_CHECK(rn.Delaunay.NumNonManifoldFaces <= r.Delaunay.NumNonManifoldFaces);
  AV_CHECK(rn.Converged == (rn.Delaunay.NumNonManifoldFaces == 0));
  long euler = 0;
  int share = 0;
  Topology(r.Delaunay, euler, share);
  std::cout << "3D: Euler characteristic " << euler << ", largest facet share " << share
            << std::endl;
}

// A strongly folded embedding: every insertion round makes more inverted elements than it
// removes (183 -> 322 -> 651 here). The repair must stop after StallRounds rounds without
// progress and return its best state (the input, untouched), not run away.
void TestRepairStalls()
{
  const auto& [m, e, s] = FoldedCube(0.3, 12.0, 60, 3);
  const av::DelaunayRepairResult r = av::RepairRestrictedDelaunay(m, e, s);
  std::cout << "stalled repair: bad per round";
  for (std::size_t v : r.InvertedPerRound)
    std::cout << " " << v;
  std::cout << ", kept " << r.Delaunay.NumInverted << std::endl;
  AV_CHECK(r.Stalled && !r.Converged);
  AV_CHECK(r.InvertedPerRound.size() == 3); // round 0 and StallRounds (2) worse rounds
  const std::size_t best = *std::min_element(r.InvertedPerRound.begin(), r.InvertedPerRound.end());
  AV_CHECK(best == r.InvertedPerRound[0] && best > 0);
  AV_CHECK(r.Delaunay.NumInverted == best);
  AV_CHECK(r.NumInserted == 0 && r.Rounds == 0 && r.InsertedPerRound.empty());
  AV_CHECK(r.Sites.Coords == s.Coords && r.Sites.CellIds == s.CellIds);
  // The returned diagram and dual are those of the returned sites.
  const av::RestrictedVoronoiDiagram v =
    av::ComputeRestrictedVoronoi(m, e, r.Sites, av::DelaunayRepairOptions().Voronoi);
  AV_CHECK(v.PieceMeasure == r.Voronoi.PieceMeasure);
  AV_CHECK(av::ComputeRestrictedDelaunay(m, e, r.Sites, v).Cells == r.Delaunay.Cells);
  // One round without progress is enough to stop with StallRounds = 1.
  av::DelaunayRepairOptions o;
  o.StallRounds = 1;
  const av::DelaunayRepairResult r1 = av::RepairRestrictedDelaunay(m, e, s, o);
  AV_CHECK(r1.Stalled && r1.InvertedPerRound.size() == 2 && r1.Delaunay.NumInverted == best);
}

void TestNothingToRepair()
{
  // Identity embedding: Delaunay, never inverted; nothing inserted.
  const av::SimplexMesh m = TriGrid(17, 17, 0, 0, 1, 1);
  const av::Embedding e = MakeEmbedding(m, 8, nullptr);
  const av::SiteSet s = RandomSites(m, e, 40, 5);
  const av::DelaunayRepairResult r = av::RepairRestrictedDelaunay(m, e, s);
  AV_CHECK(r.Converged && r.Rounds == 0 && r.NumInserted == 0 && r.InitialInverted == 0);
  AV_CHECK(r.Sites.Coords == s.Coords && r.Sites.CellIds == s.CellIds);
  AV_CHECK(r.Delaunay.NumCells() > 0);
}

void TestBadOptions()
{
  const av::SimplexMesh m = TriGrid(6, 6, 0, 0, 1, 1);
  const av::Embedding e = MakeEmbedding(m, 3, SmoothExtra);
  const av::SiteSet s = RandomSites(m, e, 12, 24);
  av::DelaunayRepairOptions o;
  o.MaxRounds = -1;
  AV_CHECK_THROWS(av::RepairRestrictedDelaunay(m, e, s, o));
  o = av::DelaunayRepairOptions();
  o.MinDistanceFraction = 1.5;
  AV_CHECK_THROWS(av::RepairRestrictedDelaunay(m, e, s, o));
  o = av::DelaunayRepairOptions();
  o.StallRounds = 0;
  AV_CHECK_THROWS(av::RepairRestrictedDelaunay(m, e, s, o));
  o = av::DelaunayRepairOptions();
  o.Voronoi.ElementEnd = 3;
  AV_CHECK_THROWS(av::RepairRestrictedDelaunay(m, e, s, o));
  av::SiteSet none;
  none.Dim = 3;
  AV_CHECK_THROWS(av::RepairRestrictedDelaunay(m, e, none));
}

} // namespace

int TestRestrictedDelaunayRefinement(int, char*[])
{
  TestVoronoiVertex();
  TestRepair2D();
  TestRepair3D();
  TestRepairStalls();
  TestNothingToRepair();
  TestBadOptions();
  return AV_TEST_RESULT();
}
