// SPDX-License-Identifier: BSD-3-Clause
// Feature lines and corners: the cube's 12 edges and 8 corners, a square's 4 corners, a folded
// sheet's crease, none on a ball, and bad input.
#include "SharpFeatures.h"
#include "StructuredMeshes.h"
#include "AnisoTestChecks.h"
#include "TetMesher.h"
#include "VoronoiTestMeshes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

namespace
{

int AtBound(const av::SimplexMesh& mesh, std::int32_t p, double lo, double hi)
{
  int n = 0;
  for (int d = 0; d < mesh.AmbientDim; ++d)
  {
    const double x = mesh.Point(static_cast<std::size_t>(p))[d];
    n += (std::abs(x - lo) < 1e-12 || std::abs(x - hi) < 1e-12) ? 1 : 0;
  }
  return n;
}

/// Every feature edge's cell holds its two points at the recorded local indices.
bool EdgeCellsConsistent(const av::SimplexMesh& mesh, const av::SharpFeatures& f)
{
  for (std::size_t e = 0; e < f.NumEdges(); ++e)
  {
    const std::int32_t* ids = mesh.Cell(static_cast<std::size_t>(f.EdgeCells[e]));
    if (ids[f.EdgeLocal[2 * e]] != f.Edges[2 * e] || ids[f.EdgeLocal[2 * e + 1]] != f.Edges[2 * e + 1])
      return false;
  }
  for (std::size_t c = 0; c < f.Corners.size(); ++c)
    if (mesh.Cell(static_cast<std::size_t>(f.CornerCells[c]))[f.CornerLocal[c]] != f.Corners[c])
      return false;
  return true;
}

} // namespace

int TestSharpFeatures(int, char*[])
{
  const double lo[3] = { 0.0, 0.0, 0.0 }, hi[3] = { 1.0, 1.0, 1.0 };
  const int n = 5;
  const av::SimplexMesh cube = av::MakeKuhnTetGrid(n, n, n, lo, hi);

  // Cube: the 12 edges of (n - 1) segments each and the 8 corners, nothing else.
  {
    const av::SharpFeatures f = av::DetectSharpFeatures(cube);
    AV_CHECK(f.NumEdges() == 12 * (n - 1));
    AV_CHECK(f.Corners.size() == 8);
    for (std::int32_t c : f.Corners)
      AV_CHECK(AtBound(cube, c, 0.0, 1.0) == 3);
    for (std::size_t e = 0; e < f.NumEdges(); ++e)
    {
      AV_CHECK(f.Edges[2 * e] < f.Edges[2 * e + 1]);
      AV_CHECK(AtBound(cube, f.Edges[2 * e], 0.0, 1.0) >= 2);
      AV_CHECK(AtBound(cube, f.Edges[2 * e + 1], 0.0, 1.0) >= 2);
    }
    AV_CHECK(EdgeCellsConsistent(cube, f));
    // Point -> edges: corners have 3, other edge points 2, the rest none.
    for (std::size_t p = 0; p < cube.NumPoints(); ++p)
    {
      const int deg = f.PointEdgeOffsets[p + 1] - f.PointEdgeOffsets[p];
      const int b = AtBound(cube, static_cast<std::int32_t>(p), 0.0, 1.0);
      AV_CHECK(deg == (b == 3 ? 3 : (b == 2 ? 2 : 0)));
      AV_CHECK((f.IsCorner[p] != 0) == (b == 3));
    }
    // A feature angle above the cube's 90 degrees: no features.
    const av::SharpFeatures none = av::DetectSharpFeatures(cube, 100.0);
    AV_CHECK(none.NumEdges() == 0 && none.Corners.empty());
    const av::SharpFeatures off = av::DetectSharpFeatures(cube, 180.0);
    AV_CHECK(off.NumEdges() == 0 && off.Corners.empty());
  }

  // The cube's boundary as a closed surface: the same 12 creases and 8 corners.
  {
    const av::SimplexMesh surface = av_test::BoundaryTriangles(cube);
    const av::SharpFeatures f = av::DetectSharpFeatures(surface);
    AV_CHECK(f.NumEdges() == 12 * (n - 1));
    AV_CHECK(f.Corners.size() == 8);
    AV_CHECK(EdgeCellsConsistent(surface, f));
  }

  // 2D square: four corners, no feature lines.
  {
    const double lo2[2] = { 0.0, 0.0 }, hi2[2] = { 2.0, 1.0 };
    const av::SimplexMesh square = av::MakeTriangleGrid(7, 4, lo2, hi2);
    const av::SharpFeatures f = av::DetectSharpFeatures(square);
    AV_CHECK(f.NumEdges() == 0);
    AV_CHECK(f.Corners.size() == 4);
    for (std::int32_t c : f.Corners)
    {
      const double* p = square.Point(static_cast<std::size_t>(c));
      AV_CHECK((p[0] == 0.0 || p[0] == 2.0) && (p[1] == 0.0 || p[1] == 1.0));
    }
  }

  // Folded sheet z = |x - 1| over [0, 2] x [0, 1]: a crease along x = 1 (90 degrees), whose two
  // ends meet the boundary (corners), plus the sheet's 4 corners.
  {
    const double lo2[2] = { 0.0, 0.0 }, hi2[2] = { 2.0, 1.0 };
    const av::SimplexMesh flat = av::MakeTriangleGrid(9, 5, lo2, hi2);
    av::SimplexMesh sheet;
    sheet.AmbientDim = 3;
    sheet.SimplexDim = 2;
    sheet.Cells = flat.Cells;
    for (std::size_t p = 0; p < flat.NumPoints(); ++p)
    {
      const double x = flat.Point(p)[0], y = flat.Point(p)[1];
      sheet.Points.insert(sheet.Points.end(), { x, y, std::abs(x - 1.0) });
    }
    const av::SharpFeatures f = av::DetectSharpFeatures(sheet);
    AV_CHECK(f.NumEdges() == 4); // 5 points along the crease
    for (std::int32_t id : f.Edges)
      AV_CHECK(std::abs(sheet.Point(static_cast<std::size_t>(id))[0] - 1.0) < 1e-12);
    AV_CHECK(f.Corners.size() == 6);
    AV_CHECK(EdgeCellsConsistent(sheet, f));
    // Flipping one triangle's orientation must not create a crease.
    av::SimplexMesh flipped = sheet;
    std::swap(flipped.Cells[0], flipped.Cells[1]);
    const av::SharpFeatures g = av::DetectSharpFeatures(flipped);
    AV_CHECK(g.NumEdges() == 4 && g.Corners.size() == 6);
    // A gentle fold (z = 0.2 |x - 1|, 22.6 degrees) is no feature at 30 degrees.
    av::SimplexMesh gentle = sheet;
    for (std::size_t p = 0; p < gentle.NumPoints(); ++p)
      gentle.Points[3 * p + 2] *= 0.2;
    AV_CHECK(av::DetectSharpFeatures(gentle).NumEdges() == 0);
    AV_CHECK(av::DetectSharpFeatures(gentle).Corners.size() == 4);

    // Given by patch ids: the gentle sheet (no angle feature) in two patches, x < 1 and x > 1
    // (every triangle lies on one side): the line x = 1 again, the same 6 corners; a corner
    // flag adds one in the middle of the line. Rebuilt from its edges and corners, the same.
    std::vector<std::int32_t> patch(gentle.NumCells());
    for (std::size_t c = 0; c < gentle.NumCells(); ++c)
    {
      double x = 0.0;
      for (int j = 0; j < 3; ++j)
        x += gentle.Point(static_cast<std::size_t>(gentle.Cell(c)[j]))[0] / 3.0;
      patch[c] = x < 1.0 ? 7 : 9;
    }
    const av::SharpFeatures p = av::SharpFeaturesFromPatches(gentle, patch);
    AV_CHECK(p.NumEdges() == 4 && p.Corners.size() == 6 && EdgeCellsConsistent(gentle, p));
    for (std::int32_t id : p.Edges)
      AV_CHECK(std::abs(gentle.Point(static_cast<std::size_t>(id))[0] - 1.0) < 1e-12);
    AV_CHECK(p.Edges == f.Edges && p.Corners == f.Corners);
    std::vector<std::uint8_t> flags(gentle.NumPoints(), 0);
    std::int32_t middle = -1;
    for (std::size_t q = 0; q < gentle.NumPoints(); ++q)
      if (std::abs(gentle.Point(q)[0] - 1.0) < 1e-12 && std::abs(gentle.Point(q)[1] - 0.5) < 1e-12)
        middle = static_cast<std::int32_t>(q);
    AV_CHECK(middle >= 0);
    flags[static_cast<std::size_t>(middle)] = 1;
    const av::SharpFeatures pc = av::SharpFeaturesFromPatches(gentle, patch, &flags);
    AV_CHECK(pc.Corners.size() == 7 && pc.IsCorner[static_cast<std::size_t>(middle)] == 1);
    const av::SharpFeatures r = av::SharpFeaturesFromEdges(gentle, pc.Edges, pc.Corners);
    AV_CHECK(r.Edges == pc.Edges && r.Corners == pc.Corners && r.IsCorner == pc.IsCorner &&
      r.PointEdgeOffsets == pc.PointEdgeOffsets && r.PointEdges == pc.PointEdges);
    AV_CHECK(EdgeCellsConsistent(gentle, r));
    // One patch: no line, only the sheet's 4 corners (its boundary turns).
    const av::SharpFeatures one =
      av::SharpFeaturesFromPatches(gentle, std::vector<std::int32_t>(gentle.NumCells(), 3));
    AV_CHECK(one.NumEdges() == 0 && one.Corners.size() == 4);
    // Bad input: ids not one per triangle, flags not one per point, a tet mesh, an edge that
    // is not a mesh edge, an id out of range, an odd edge list.
    AV_CHECK_THROWS(av::SharpFeaturesFromPatches(gentle, std::vector<std::int32_t>(3, 0)));
    std::vector<std::uint8_t> shortFlags(2, 0);
    AV_CHECK_THROWS(av::SharpFeaturesFromPatches(gentle, patch, &shortFlags));
    AV_CHECK_THROWS(
      av::SharpFeaturesFromPatches(cube, std::vector<std::int32_t>(cube.NumCells(), 0)));
    AV_CHECK_THROWS(av::SharpFeaturesFromEdges(
      gentle, { 0, static_cast<std::int32_t>(gentle.NumPoints() - 1) }, {}));
    AV_CHECK_THROWS(av::SharpFeaturesFromEdges(gentle, { 0, 1 }, { -1 }));
    AV_CHECK_THROWS(av::SharpFeaturesFromEdges(gentle, { 0, 1, 2 }, {}));
  }

  // A ball: a smooth boundary has no features.
  {
    const av::SimplexMesh ball = av::TetrahedralizeSphere(1.0, 3000);
    const av::SharpFeatures f = av::DetectSharpFeatures(ball);
    AV_CHECK(f.NumEdges() == 0 && f.Corners.empty());
  }

  // Bad input.
  AV_CHECK_THROWS(av::DetectSharpFeatures(cube, 0.0));
  AV_CHECK_THROWS(av::DetectSharpFeatures(cube, std::nan("")));
  AV_CHECK_THROWS(av::DetectSharpFeatures(av::SimplexMesh()));
  {
    av::SimplexMesh bad = cube;
    bad.Cells[5] = static_cast<std::int32_t>(bad.NumPoints());
    AV_CHECK_THROWS(av::DetectSharpFeatures(bad));
  }
  return AV_TEST_RESULT();
}
