// SPDX-License-Identifier: BSD-3-Clause
// The RVD's whole-element fast path (RestrictedVoronoiOptions::WholeElementFastPath): on meshes
// where many elements lie inside one cell and many do not, with and without geometry, and with
// exact ties at mesh vertices, the output must equal the full clipping's field by field, every
// element must be partitioned by its pieces, and a one-piece element's vertices must all be
// nearest (brute force) to its site. Also: the same output on 1 and on all threads.
#include "AnisoTestChecks.h"
#include "RestrictedVoronoi.h"
#include "VoronoiDiagramCompare.h"
#include "VoronoiTestMeshes.h"

#include <tbb/global_control.h>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

using namespace av_test;

namespace
{


double Dist2(const double* a, const double* b, int dim)
{
  double s = 0.0;
  for (int d = 0; d < dim; ++d)
    s += (a[d] - b[d]) * (a[d] - b[d]);
  return s;
}

// Sites nearest to embedded point x (brute force; all within a relative 1e-12 of the minimum).
std::vector<std::int32_t> NearestSites(const av::SiteSet& s, const double* x, int dim)
{
  double best = 1e300;
  for (std::size_t q = 0; q < s.NumSites(); ++q)
    best = std::min(best, Dist2(x, s.At(q), dim));
  std::vector<std::int32_t> out;
  for (std::size_t q = 0; q < s.NumSites(); ++q)
    if (Dist2(x, s.At(q), dim) <= best * (1.0 + 1e-12))
      out.push_back(static_cast<std::int32_t>(q));
  return out;
}

// Fast path on against off (the full clipping), for one mesh / embedding / site set.
// Returns the number of elements the fast path emitted whole.
std::size_t CheckAgainstFullClipping(const av::SimplexMesh& m,
  const av::Embedding& e,
  const av::SiteSet& s,
  const std::string& name)
{
  std::size_t whole = 0;
  for (int geom = 0; geom < 2; ++geom)
  {
    av::RestrictedVoronoiOptions full, fast;
    full.ComputeGeometry = fast.ComputeGeometry = geom != 0;
    full.WholeElementFastPath = false;
    fast.WholeElementFastPath = true;
    const auto a = av::ComputeRestrictedVoronoi(m, e, s, full);
    const auto b = av::ComputeRestrictedVoronoi(m, e, s, fast);
    const std::string what = name + (geom ? " geometry" : " lean");
    AV_CHECK_MSG(a.NumWholeElements == 0, what << ": whole elements without the fast path");
    AV_CHECK_MSG(SameDiagram(b, a, what), what << ": fast path differs from the full clipping");
    whole = b.NumWholeElements;

    // Independent of the bitwise comparison: same pieces, measures to 1e-12, and every
    // element partitioned by its pieces.
    AV_CHECK(a.NumPieces() == b.NumPieces());
    std::size_t badMeasure = 0, badPartition = 0, badWhole = 0, single = 0;
    for (std::size_t p = 0; p < std::min(a.NumPieces(), b.NumPieces()); ++p)
      if (a.PieceSite[p] != b.PieceSite[p] || a.PieceElement[p] != b.PieceElement[p] ||
        std::abs(a.PieceMeasure[p] - b.PieceMeasure[p]) > 1e-12 * std::abs(a.PieceMeasure[p]))
        ++badMeasure;
    const std::size_t nc = m.NumCells();
    for (std::size_t c = 0; c < nc && b.ElementPieceOffsets.size() == nc + 1; ++c)
    {
      const std::int64_t p0 = b.ElementPieceOffsets[c], p1 = b.ElementPieceOffsets[c + 1];
      double sum = 0.0;
      for (std::int64_t p = p0; p < p1; ++p)
        sum += b.PieceMeasure[p];
      const double ref = GramCellMeasure(m, m.Points.data(), m.AmbientDim, c);
      if (std::abs(sum - ref) > 1e-12 * ref)
        ++badPartition;
      if (p1 - p0 != 1)
        continue;
      // One piece: the whole element, so every vertex is nearest to its site.
      ++single;
      const std::int32_t site = b.PieceSite[p0];
      for (int a0 = 0; a0 <= m.SimplexDim; ++a0)
      {
        const std::vector<std::int32_t> near = NearestSites(s, e.At(m.Cell(c)[a0]), e.Dim);
        if (std::find(near.begin(), near.end(), site) == near.end())
          ++badWhole;
      }
    }
    AV_CHECK_MSG(badMeasure == 0, what << ": " << badMeasure << " pieces differ");
    AV_CHECK_MSG(badPartition == 0, what << ": " << badPartition << " elements not partitioned");
    AV_CHECK_MSG(badWhole == 0,
      what << ": " << badWhole << " vertices of one-piece elements "
           << "not nearest to the piece's site");
    AV_CHECK_MSG(b.NumWholeElements <= single,
      what << ": " << b.NumWholeElements << " whole elements, " << single << " one-piece ones");
  }
  return whole;
}

// Tets in 8D: cells about 3 elements across, so a mix of whole and cut elements.
void TestTets()
{
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
  const av::SimplexMesh m = KuhnGrid(13, 13, 13, lo, hi);
  const av::Embedding e = MakeEmbedding(m, 8, SmoothExtra3);
  const av::SiteSet s = RandomSites(m, e, 25, 3);
  const std::size_t whole = CheckAgainstFullClipping(m, e, s, "tets 8D");
  const std::size_t nc = m.NumCells();
  std::cout << "tets 8D: " << whole << " of " << nc << " elements whole" << std::endl;
  AV_CHECK_MSG(whole > nc / 4 && whole < 9 * nc / 10, "tets 8D: " << whole << " whole elements");
}

// Triangles of a height field in 5D.
void TestTriangles()
{
  av::SimplexMesh m = TriGrid(31, 31, 0.0, 0.0, 1.0, 1.0);
  const av::Embedding e = MakeEmbedding(m, 5, SmoothExtra);
  const av::SiteSet s = RandomSites(m, e, 30, 5);
  const std::size_t whole = CheckAgainstFullClipping(m, e, s, "triangles 5D");
  const std::size_t nc = m.NumCells();
  std::cout << "triangles 5D: " << whole << " of " << nc << " elements whole" << std::endl;
  AV_CHECK_MSG(whole > nc / 4 && whole < 9 * nc / 10, "triangles 5D: " << whole);
}

// Exact ties at mesh vertices: sites mirrored about the grid planes x = 0.5 and y = 0.5 (flat
// identity embedding, so the vertices on those planes are exactly equidistant from a pair).
// The tie-break (lowest id) must be the full clipping's: no whole element across a tie.
void TestTies()
{
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
  const av::SimplexMesh m = KuhnGrid(9, 9, 5, lo, hi);
  const av::Embedding e = MakeEmbedding(m, 3, nullptr);
  av::SiteSet s;
  s.Dim = 3;
  const double pts[4][3] = {
    { 0.3, 0.3, 0.41 }, { 0.7, 0.3, 0.41 }, { 0.3, 0.7, 0.41 }, { 0.7, 0.7, 0.41 }
  };
  for (const auto& p : pts)
    AV_CHECK(SiteAt(s, m, e, p));
  const std::size_t whole = CheckAgainstFullClipping(m, e, s, "ties");
  AV_CHECK_MSG(whole > 0, "ties: no whole element");
}

// The same output whatever the number of threads (the fast path's per-vertex sites included).
void TestThreads()
{
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
  const av::SimplexMesh m = KuhnGrid(13, 13, 13, lo, hi);
  const av::Embedding e = MakeEmbedding(m, 8, SmoothExtra3);
  const av::SiteSet s = RandomSites(m, e, 25, 3);
  const auto all = av::ComputeRestrictedVoronoi(m, e, s);
  av::RestrictedVoronoiDiagram one;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = av::ComputeRestrictedVoronoi(m, e, s);
  }
  AV_CHECK(SameDiagram(one, all, "threads"));
  AV_CHECK(one.NumWholeElements == all.NumWholeElements);
}

} // namespace

int TestRestrictedVoronoiFastPath(int, char*[])
{
  TestTets();
  TestTriangles();
  TestTies();
  TestThreads();
  return AV_TEST_RESULT();
}
