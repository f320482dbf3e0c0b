// SPDX-License-Identifier: BSD-3-Clause
// Restricted Voronoi diagram with coincident sites (exact copies, and sites put on one mesh
// vertex from different elements, as the sampler did on the OpenFOAM mixer): the lowest id of
// each group owns the cell, the others own nothing, and the pieces still partition every
// element. Without the candidate filter the pieces of the copies overlap (mixer: 859 elements).
#include "RestrictedVoronoi.h"
#include "AnisoTestChecks.h"
#include "VoronoiTestMeshes.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <random>
#include <vector>

using namespace av_test;

namespace
{

double ElementMeasure(const av::SimplexMesh& m, std::size_t c)
{
  const std::int32_t* v = m.Cell(c);
  const double* p0 = m.Point(v[0]);
  if (m.SimplexDim == 2)
  {
    const double* p1 = m.Point(v[1]);
    const double* p2 = m.Point(v[2]);
    return 0.5 * std::abs((p1[0] - p0[0]) * (p2[1] - p0[1]) - (p1[1] - p0[1]) * (p2[0] - p0[0]));
  }
  double M[3][3];
  for (int a = 0; a < 3; ++a)
    for (int d = 0; d < 3; ++d)
      M[a][d] = m.Point(v[a + 1])[d] - p0[d];
  return std::abs(Det3(M)) / 6.0;
}

// Adds, after the random sites, exact copies of some of them and pairs of sites on one mesh
// vertex reached from two different elements; returns the groups of coincident ids.
std::vector<std::vector<std::int32_t>> AddCoincidentSites(
  av::SiteSet& s, const av::SimplexMesh& m, const av::Embedding& e, unsigned seed)
{
  std::mt19937 rng(seed);
  std::vector<std::vector<std::int32_t>> groups;
  const auto n0 = static_cast<std::int32_t>(s.NumSites());
  for (int t = 0; t < 12; ++t)
  {
    const std::int32_t orig = static_cast<std::int32_t>(rng() % n0);
    const double* b = s.Bary.data() + 4 * orig;
    const double bb[4] = { b[0], b[1], b[2], b[3] };
    AddSite(s, m, e, s.CellIds[orig], bb);
    groups.push_back({ orig, static_cast<std::int32_t>(s.NumSites() - 1) });
  }
  // Vertex sites: the same point as corner a of cell c and corner a' of another cell c'.
  const int nv = m.SimplexDim + 1;
  for (int t = 0; t < 12; ++t)
  {
    const auto c = static_cast<std::int32_t>(rng() % m.NumCells());
    const std::int32_t vert = m.Cell(c)[t % nv];
    std::int32_t c2 = -1;
    int a2 = -1;
    for (std::size_t q = 0; q < m.NumCells() && c2 < 0; ++q)
      for (int a = 0; a < nv; ++a)
        if (m.Cell(q)[a] == vert && static_cast<std::int32_t>(q) != c)
        {
          c2 = static_cast<std::int32_t>(q);
          a2 = a;
        }
    if (c2 < 0)
      continue;
    double b1[4] = { 0, 0, 0, 0 }, b2[4] = { 0, 0, 0, 0 };
    b1[t % nv] = 1.0;
    b2[a2] = 1.0;
    AddSite(s, m, e, c, b1);
    AddSite(s, m, e, c2, b2);
    const auto id = static_cast<std::int32_t>(s.NumSites());
    groups.push_back({ id - 2, id - 1 });
  }
  return groups;
}

void CheckCase(const char* name, const av::SimplexMesh& m, const av::Embedding& e, unsigned seed)
{
  av::SiteSet s = RandomSites(m, e, 120, seed);
  const auto groups = AddCoincidentSites(s, m, e, seed + 1);
  // Every group really is coincident (the test would prove nothing otherwise).
  for (const auto& g : groups)
    AV_CHECK_MSG(std::equal(s.At(g[0]), s.At(g[0]) + s.Dim, s.At(g[1])),
      name << ": sites " << g[0] << " and " << g[1] << " differ");
  av::RestrictedVoronoiOptions o;
  o.ComputeGeometry = false;
  const av::RestrictedVoronoiDiagram r = av::ComputeRestrictedVoronoi(m, e, s, o);

  std::size_t bad = 0;
  double worst = 0.0, total = 0.0, domain = 0.0;
  for (std::size_t c = 0; c < m.NumCells(); ++c)
  {
    double sum = 0.0;
    for (std::int64_t p = r.ElementPieceOffsets[c]; p < r.ElementPieceOffsets[c + 1]; ++p)
      sum += r.PieceMeasure[p];
    const double vol = ElementMeasure(m, c);
    const double rel = std::abs(sum - vol) / vol;
    worst = std::max(worst, rel);
    bad += !(rel < 1e-9);
    total += sum;
    domain += vol;
  }
  AV_CHECK_MSG(bad == 0,
    name << ": " << bad << " element(s) not partitioned by their pieces (worst " << worst << ")");
  AV_CHECK_MSG(std::abs(total - domain) < 1e-9 * domain, name << ": measure " << total << " vs " << domain);
  for (const auto& g : groups)
  {
    const std::int32_t lo = std::min(g[0], g[1]), hi = std::max(g[0], g[1]);
    AV_CHECK_MSG(r.SiteMeasure[hi] == 0.0,
      name << ": site " << hi << " (a copy of " << lo << ") owns " << r.SiteMeasure[hi]);
    AV_CHECK_MSG(r.SiteMeasure[lo] > 0.0, name << ": site " << lo << " owns nothing");
  }
  std::cout << name << ": " << s.NumSites() << " sites (" << groups.size()
            << " coincident pairs), worst element gap " << worst << std::endl;
}

} // namespace

int TestRestrictedVoronoiCoincidentSites(int, char*[])
{
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
  const av::SimplexMesh tets = KuhnGrid(6, 6, 6, lo, hi);
  // Strongly curved 8D embedding: large elements for their pieces, as on the mixer.
  const av::Embedding e3 =
    MakeEmbedding(tets, 8, [](const double* x, int col) { return 4.0 * SmoothExtra3(x, col); });
  CheckCase("tets 8D", tets, e3, 3);
  const av::SimplexMesh tris = TriGrid(12, 12, 0, 0, 1, 1);
  const av::Embedding e2 =
    MakeEmbedding(tris, 5, [](const double* x, int col) { return 4.0 * SmoothExtra(x, col); });
  CheckCase("triangles 5D", tris, e2, 5);
  return AV_TEST_RESULT();
}
