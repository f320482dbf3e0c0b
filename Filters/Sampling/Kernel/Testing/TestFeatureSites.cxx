// SPDX-License-Identifier: BSD-3-Clause
// Feature sites: corners exactly at the cube's corners, evenly spaced sites on its 12 edges,
// a closed loop, chain continuation and bad input.
#include "FeatureSites.h"
#include "SharpFeatures.h"
#include "StructuredMeshes.h"
#include "AnisoTestChecks.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace
{

/// Points padded with zeros to Dim coordinates (an isometric embedding).
av::Embedding Padded(const av::SimplexMesh& mesh, int dim)
{
  av::Embedding e;
  e.Dim = dim;
  for (std::size_t p = 0; p < mesh.NumPoints(); ++p)
    for (int d = 0; d < dim; ++d)
      e.Coords.push_back(d < mesh.AmbientDim ? mesh.Point(p)[d] : 0.0);
  return e;
}

/// Largest gap between a site's coordinates and its barycentric position in its cell.
double BaryMismatch(const av::SimplexMesh& mesh, const av::Embedding& emb, const av::SiteSet& s)
{
  double worst = 0.0;
  for (std::size_t i = 0; i < s.NumSites(); ++i)
  {
    const std::int32_t* ids = mesh.Cell(static_cast<std::size_t>(s.CellIds[i]));
    double sum = 0.0;
    for (int j = 0; j < mesh.VerticesPerCell(); ++j)
      sum += s.Bary[4 * i + j];
    worst = std::max(worst, std::abs(sum - 1.0));
    for (int d = 0; d < emb.Dim; ++d)
    {
      double x = 0.0;
      for (int j = 0; j < mesh.VerticesPerCell(); ++j)
        x += s.Bary[4 * i + j] * emb.At(static_cast<std::size_t>(ids[j]))[d];
      worst = std::max(worst, std::abs(x - s.At(i)[d]));
    }
  }
  return worst;
}

std::int32_t CellWithEdge(const av::SimplexMesh& mesh, std::int32_t a, std::int32_t b, std::int8_t* la, std::int8_t* lb)
{
  for (std::size_t c = 0; c < mesh.NumCells(); ++c)
  {
    int ia = -1, ib = -1;
    for (int j = 0; j < mesh.VerticesPerCell(); ++j)
    {
      ia = mesh.Cell(c)[j] == a ? j : ia;
      ib = mesh.Cell(c)[j] == b ? j : ib;
    }
    if (ia >= 0 && ib >= 0)
    {
      *la = static_cast<std::int8_t>(ia);
      *lb = static_cast<std::int8_t>(ib);
      return static_cast<std::int32_t>(c);
    }
  }
  return -1;
}

} // namespace

int TestFeatureSites(int, char*[])
{
  const double lo[3] = { 0.0, 0.0, 0.0 }, hi[3] = { 1.0, 1.0, 1.0 };
  const av::SimplexMesh cube = av::MakeKuhnTetGrid(5, 5, 5, lo, hi);
  const av::Embedding emb = Padded(cube, 5);
  const av::SharpFeatures f = av::DetectSharpFeatures(cube);

  // Spacing 0.3 on edges of length 1: round(1 / 0.3) - 1 = 2 sites per edge, at 1/3 and 2/3.
  {
    const av::FeatureSitePlacement p = av::PlaceFeatureSites(cube, emb, f, 0.3);
    AV_CHECK(p.NumCorners == 8);
    AV_CHECK(p.NumChains == 12);
    AV_CHECK_NEAR(p.FeatureLength, 12.0, 1e-12);
    AV_CHECK(p.Sites.NumSites() == 8 + 24);
    AV_CHECK(p.Edge.size() == p.Sites.NumSites());
    AV_CHECK(BaryMismatch(cube, emb, p.Sites) < 1e-12);
    for (std::size_t i = 0; i < p.Sites.NumSites(); ++i)
    {
      const double* x = p.Sites.At(i);
      int atBound = 0, atThird = 0;
      for (int d = 0; d < 3; ++d)
      {
        atBound += (x[d] == 0.0 || x[d] == 1.0) ? 1 : 0;
        atThird += (std::abs(x[d] - 1.0 / 3.0) < 1e-12 || std::abs(x[d] - 2.0 / 3.0) < 1e-12) ? 1 : 0;
      }
      if (i < 8)
        AV_CHECK(atBound == 3 && p.Edge[i] == -1);
      else
        AV_CHECK(atBound == 2 && atThird == 1 && p.Edge[i] >= 0);
      AV_CHECK(x[3] == 0.0 && x[4] == 0.0);
    }
    // Spacing longer than the edges: corners only.
    AV_CHECK(av::PlaceFeatureSites(cube, emb, f, 5.0).Sites.NumSites() == 8);
  }

  // Chain continuation: along an edge of the cube the next feature edge is collinear; at a
  // corner there is none.
  {
    for (std::size_t e = 0; e < f.NumEdges(); ++e)
      for (int s = 0; s < 2; ++s)
      {
        const std::int32_t p = f.Edges[2 * e + s];
        const std::int32_t next = av::NextFeatureEdge(f, static_cast<std::int32_t>(e), p);
        AV_CHECK((next < 0) == (f.IsCorner[static_cast<std::size_t>(p)] != 0));
        if (next >= 0)
        {
          AV_CHECK(next != static_cast<std::int32_t>(e));
          AV_CHECK(f.Edges[2 * next] == p || f.Edges[2 * next + 1] == p);
        }
      }
  }

  // A closed loop without corners: the boundary of a square grid declared as one feature loop.
  {
    const double lo2[2] = { 0.0, 0.0 }, hi2[2] = { 1.0, 1.0 };
    const av::SimplexMesh square = av::MakeTriangleGrid(3, 3, lo2, hi2);
    const av::Embedding e2 = Padded(square, 3);
    av::SharpFeatures loop;
    // Grid points are row-major: id = i + 3 j; the boundary cycle 0-1-2-5-8-7-6-3-0.
    const std::int32_t cyc[9] = { 0, 1, 2, 5, 8, 7, 6, 3, 0 };
    for (int k = 0; k < 8; ++k)
    {
      const std::int32_t a = std::min(cyc[k], cyc[k + 1]), b = std::max(cyc[k], cyc[k + 1]);
      std::int8_t la = 0, lb = 0;
      loop.Edges.push_back(a);
      loop.Edges.push_back(b);
      loop.EdgeCells.push_back(CellWithEdge(square, a, b, &la, &lb));
      loop.EdgeLocal.push_back(la);
      loop.EdgeLocal.push_back(lb);
    }
    loop.IsCorner.assign(square.NumPoints(), 0);
    loop.PointEdgeOffsets.assign(square.NumPoints() + 1, 0);
    std::vector<std::vector<std::int32_t>> byPoint(square.NumPoints());
    for (std::int32_t e = 0; e < 8; ++e)
      for (int s = 0; s < 2; ++s)
        byPoint[static_cast<std::size_t>(loop.Edges[2 * e + s])].push_back(e);
    for (std::size_t p = 0; p < square.NumPoints(); ++p)
    {
      loop.PointEdgeOffsets[p + 1] = loop.PointEdgeOffsets[p] + static_cast<std::int32_t>(byPoint[p].size());
      loop.PointEdges.insert(loop.PointEdges.end(), byPoint[p].begin(), byPoint[p].end());
    }
    // Perimeter 4, spacing 0.5: 8 sites, 0.5 apart along the loop (every grid point of it).
    const av::FeatureSitePlacement p = av::PlaceFeatureSites(square, e2, loop, 0.5);
    AV_CHECK(p.NumCorners == 0 && p.NumChains == 1);
    AV_CHECK(p.Sites.NumSites() == 8);
    AV_CHECK(BaryMismatch(square, e2, p.Sites) < 1e-12);
    // Spacing 0.4: 10 sites, consecutive ones 0.4 apart along the perimeter.
    const av::FeatureSitePlacement q = av::PlaceFeatureSites(square, e2, loop, 0.4);
    AV_CHECK(q.Sites.NumSites() == 10);
    AV_CHECK(BaryMismatch(square, e2, q.Sites) < 1e-12);
    for (std::size_t i = 0; i < q.Sites.NumSites(); ++i)
    {
      const double* x = q.Sites.At(i);
      const bool onBoundary = x[0] < 1e-12 || x[0] > 1 - 1e-12 || x[1] < 1e-12 || x[1] > 1 - 1e-12;
      AV_CHECK(onBoundary);
    }
  }

  // Bad input.
  AV_CHECK_THROWS(av::PlaceFeatureSites(cube, emb, f, 0.0));
  AV_CHECK_THROWS(av::PlaceFeatureSites(cube, emb, f, std::nan("")));
  {
    av::Embedding shortEmb = emb;
    shortEmb.Coords.resize(shortEmb.Coords.size() - 5);
    AV_CHECK_THROWS(av::PlaceFeatureSites(cube, shortEmb, f, 0.3));
  }
  return AV_TEST_RESULT();
}
