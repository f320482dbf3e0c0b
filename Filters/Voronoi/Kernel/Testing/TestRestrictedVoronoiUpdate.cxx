// SPDX-License-Identifier: BSD-3-Clause
// Incremental restricted Voronoi diagram: UpdateRestrictedVoronoi after inserting / moving a few
// sites must equal ComputeRestrictedVoronoi of the new sites field by field (bit-identical),
// while clipping only a small part of the mesh; and the Delaunay repair, which uses it for its
// later rounds, must end with the diagram / dual of its final sites.
#include "RestrictedDelaunayRefinement.h"
#include "RestrictedVoronoi.h"
#include "AnisoTestChecks.h"
#include "VoronoiDiagramCompare.h"
#include "VoronoiTestMeshes.h"

#include <cmath>
#include <iostream>
#include <random>
#include <string>

using namespace av_test;

namespace
{

// Identity padded to 5D, plus a smooth bump and a wave in the extra coordinates (not flat).
av::Embedding Bumpy(const av::SimplexMesh& m)
{
  const int k = m.SimplexDim;
  return MakeEmbedding(m, 5, [=](const double* x, int col) {
    const double z = k == 3 ? x[2] : 0.5;
    const double r2 = (x[0] - 0.5) * (x[0] - 0.5) + (x[1] - 0.4) * (x[1] - 0.4) + (z - 0.5) * (z - 0.5);
    switch (col)
    {
      case 3: return 0.4 * std::exp(-r2 / 0.08);
      default: return 0.15 * std::sin(5.0 * x[0] + 3.0 * x[1] + 2.0 * z);
    }
  });
}

// A random position inside the mesh, as a site (random element and weights).
void AddRandomSite(av::SiteSet& s, const av::SimplexMesh& m, const av::Embedding& e, std::mt19937& rng)
{
  const av::SiteSet one = RandomSites(m, e, 1, static_cast<unsigned>(rng()));
  s.Coords.insert(s.Coords.end(), one.Coords.begin(), one.Coords.end());
  s.CellIds.insert(s.CellIds.end(), one.CellIds.begin(), one.CellIds.end());
  s.Bary.insert(s.Bary.end(), one.Bary.begin(), one.Bary.end());
}

// Moves site i to a random point of an element near its own cell (a small move, as ODT does).
void MoveSite(av::SiteSet& s, std::size_t i, const av::SimplexMesh& m, const av::Embedding& e,
  std::mt19937& rng)
{
  const int nv = m.SimplexDim + 1;
  std::int32_t c = s.CellIds[i];
  // A few steps to neighboring elements through shared vertices (brute force: small meshes).
  for (int step = 0; step < 3; ++step)
  {
    const std::int32_t v = m.Cell(c)[rng() % nv];
    std::vector<std::int32_t> around;
    for (std::size_t q = 0; q < m.NumCells(); ++q)
      for (int a = 0; a < nv; ++a)
        if (m.Cell(q)[a] == v)
          around.push_back(static_cast<std::int32_t>(q));
    c = around[rng() % around.size()];
  }
  av::SiteSet one = RandomSites(m, e, 1, static_cast<unsigned>(rng()));
  // Same weights in element c.
  double b[4];
  for (int a = 0; a < 4; ++a)
    b[a] = one.Bary[a];
  s.CellIds[i] = c;
  for (int a = 0; a < 4; ++a)
    s.Bary[4 * i + a] = b[a];
  for (int d = 0; d < e.Dim; ++d)
  {
    double x = 0.0;
    for (int a = 0; a < nv; ++a)
      x += b[a] * e.At(m.Cell(c)[a])[d];
    s.Coords[i * e.Dim + d] = x;
  }
}

void RunCase(const av::SimplexMesh& m, const av::Embedding& e, int numSites, int k,
  double maxFraction, const char* name)
{
  av::RestrictedVoronoiOptions o;
  o.ComputeGeometry = false;
  std::mt19937 rng(7);
  av::SiteSet s0 = RandomSites(m, e, numSites, 3);
  const av::RestrictedVoronoiDiagram d0 = av::ComputeRestrictedVoronoi(m, e, s0, o);
  const std::size_t nc = m.NumCells();
  AV_CHECK(d0.NumRecomputedElements == nc);
  AV_CHECK(d0.ElementPieceOffsets.size() == nc + 1);

  // Nothing changed: nothing clipped.
  {
    const av::RestrictedVoronoiDiagram u = av::UpdateRestrictedVoronoi(m, e, s0, d0, s0, o);
    AV_CHECK(u.NumRecomputedElements == 0);
    AV_CHECK_MSG(SameDiagram(u, d0, std::string(name) + " unchanged"), name);
  }

  // k sites inserted at random positions.
  av::SiteSet s1 = s0;
  for (int i = 0; i < k; ++i)
    AddRandomSite(s1, m, e, rng);
  const av::RestrictedVoronoiDiagram u1 = av::UpdateRestrictedVoronoi(m, e, s1, d0, s0, o);
  const av::RestrictedVoronoiDiagram f1 = av::ComputeRestrictedVoronoi(m, e, s1, o);
  AV_CHECK_MSG(SameDiagram(u1, f1, std::string(name) + " insert"), name);
  AV_CHECK_MSG(u1.NumRecomputedElements > 0 && u1.NumRecomputedElements < maxFraction * nc,
    name << " insert: " << u1.NumRecomputedElements << " of " << nc << " elements clipped");
  std::cout << name << ": insert " << k << ": " << u1.NumRecomputedElements << " of " << nc
            << " elements clipped\n";

  // k sites inserted at Voronoi vertices (what the repair does: near-ties with k+1 sites).
  av::SiteSet s2 = s1;
  for (int i = 0; i < k && i < static_cast<int>(f1.VoronoiVertexElement.size()); ++i)
  {
    const std::size_t r = (static_cast<std::size_t>(i) * 7919) % f1.VoronoiVertexElement.size();
    double b[4], r2;
    if (av::ComputeDualVoronoiVertex(m, e, s1, f1.VoronoiVertexSites.data() + r * (m.SimplexDim + 1),
          f1.VoronoiVertexElement[r], b, r2))
      AddSite(s2, m, e, f1.VoronoiVertexElement[r], b);
  }
  AV_CHECK(s2.NumSites() > s1.NumSites());
  const av::RestrictedVoronoiDiagram u2 = av::UpdateRestrictedVoronoi(m, e, s2, u1, s1, o);
  const av::RestrictedVoronoiDiagram f2 = av::ComputeRestrictedVoronoi(m, e, s2, o);
  AV_CHECK_MSG(SameDiagram(u2, f2, std::string(name) + " insert at Voronoi vertices"), name);
  AV_CHECK(u2.NumRecomputedElements > 0 && u2.NumRecomputedElements < maxFraction * nc);
  std::cout << name << ": insert at Voronoi vertices: " << u2.NumRecomputedElements << " of "
            << nc << " elements clipped\n";

  // k sites moved (old and new positions matter), chained on the updated diagram.
  av::SiteSet s3 = s2;
  for (int i = 0; i < k; ++i)
    MoveSite(s3, (static_cast<std::size_t>(i) * 37 + 5) % s3.NumSites(), m, e, rng);
  const av::RestrictedVoronoiDiagram u3 = av::UpdateRestrictedVoronoi(m, e, s3, u2, s2, o);
  const av::RestrictedVoronoiDiagram f3 = av::ComputeRestrictedVoronoi(m, e, s3, o);
  AV_CHECK_MSG(SameDiagram(u3, f3, std::string(name) + " move"), name);
  AV_CHECK(u3.NumRecomputedElements > 0 && u3.NumRecomputedElements < maxFraction * nc);
  std::cout << name << ": move " << k << ": " << u3.NumRecomputedElements << " of " << nc
            << " elements clipped\n";

  // Moved and inserted at once.
  av::SiteSet s4 = s3;
  MoveSite(s4, 1, m, e, rng);
  AddRandomSite(s4, m, e, rng);
  const av::RestrictedVoronoiDiagram u4 = av::UpdateRestrictedVoronoi(m, e, s4, u3, s3, o);
  AV_CHECK_MSG(SameDiagram(u4, av::ComputeRestrictedVoronoi(m, e, s4, o), std::string(name) + " both"), name);

  // Geometry / MergeBySite: the full computation (still equal).
  av::RestrictedVoronoiOptions g;
  const av::RestrictedVoronoiDiagram ug = av::UpdateRestrictedVoronoi(m, e, s1, d0, s0, g);
  AV_CHECK(ug.NumRecomputedElements == nc);
  AV_CHECK_MSG(SameDiagram(ug, av::ComputeRestrictedVoronoi(m, e, s1, g), std::string(name) + " geometry"), name);

  // Inconsistent inputs.
  AV_CHECK_THROWS(av::UpdateRestrictedVoronoi(m, e, s1, d0, s2, o)); // diagram of other sites
  AV_CHECK_THROWS(av::UpdateRestrictedVoronoi(m, e, s0, u1, s1, o)); // sites removed
}

// The repair uses the update after its first round: its final diagram and dual must be those
// of its final sites.
void TestRepair()
{
  const av::SimplexMesh m = TriGrid(33, 33, 0, 0, 1, 1);
  const av::Embedding e = MakeEmbedding(m, 8, [](const double* x, int col) {
    switch (col % 3)
    {
      case 0: return 0.2 * std::sin(12.0 * x[0] + 0.3 * col);
      case 1: return 0.2 * std::cos(12.0 * x[1]);
      default: return 0.2 * std::sin(12.0 * (x[0] + x[1]));
    }
  });
  const av::SiteSet s = RandomSites(m, e, 60, 1);
  const av::DelaunayRepairResult r = av::RepairRestrictedDelaunay(m, e, s);
  AV_CHECK(r.Rounds >= 2); // so that at least one round used the update
  AV_CHECK(r.Voronoi.NumRecomputedElements < m.NumCells());
  const av::DelaunayRepairOptions opt;
  const av::RestrictedVoronoiDiagram full = av::ComputeRestrictedVoronoi(m, e, r.Sites, opt.Voronoi);
  AV_CHECK_MSG(SameDiagram(r.Voronoi, full, "repair"), "repair");
  const av::RestrictedDelaunayMesh dual = av::ComputeRestrictedDelaunay(m, e, r.Sites, full);
  AV_CHECK(r.Delaunay.Cells == dual.Cells);
  AV_CHECK(r.Delaunay.NumInverted == dual.NumInverted);
  std::cout << "repair: " << r.Rounds << " rounds, " << r.NumInserted << " sites inserted, last "
            << r.Voronoi.NumRecomputedElements << " of " << m.NumCells() << " elements clipped\n";
}

} // namespace

int TestRestrictedVoronoiUpdate(int, char*[])
{
  {
    const av::SimplexMesh m = TriGrid(61, 61, 0, 0, 1, 1);
    RunCase(m, Bumpy(m), 300, 4, 0.2, "triangles");
  }
  {
    const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
    const av::SimplexMesh m = KuhnGrid(15, 15, 15, lo, hi);
    RunCase(m, Bumpy(m), 400, 4, 0.2, "tets");
  }
  // Coarse meshes (several pieces per element): most candidates of an element cut none of its
  // pieces, which the per-piece test (last cut, security radius) must recognize exactly.
  {
    const av::SimplexMesh m = TriGrid(16, 16, 0, 0, 1, 1);
    RunCase(m, Bumpy(m), 700, 6, 0.6, "coarse triangles");
  }
  {
    const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
    const av::SimplexMesh m = KuhnGrid(7, 7, 7, lo, hi);
    RunCase(m, Bumpy(m), 1500, 6, 0.6, "coarse tets");
  }
  TestRepair();
  return AV_TEST_RESULT();
}
