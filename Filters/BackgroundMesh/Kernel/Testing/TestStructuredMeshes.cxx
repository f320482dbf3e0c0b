// SPDX-License-Identifier: BSD-3-Clause
// Kuhn tet grid / triangle grid: positive orientation, exact volume partition, conformity
// (every interior face shared by two cells), edge and boundary counts; two grids that touch
// along a face with separate points (a contact assembly) are two bodies, merged points one;
// joined along an edge only, they are one body with pinched boundary edges.
#include "MeshTopology.h"
#include "StructuredMeshes.h"
#include "AnisoTestChecks.h"

#include <cmath>

int TestStructuredMeshes(int, char*[])
{
  using namespace av;
  {
    const double lo[3] = { -1.0, 0.5, 2.0 }, hi[3] = { 2.0, 1.5, 4.5 };
    const int nx = 5, ny = 4, nz = 3;
    const SimplexMesh m = MakeKuhnTetGrid(nx, ny, nz, lo, hi);
    AV_CHECK(m.NumPoints() == 60u);
    AV_CHECK(m.NumCells() == 6u * 4 * 3 * 2);
    double vol = 0.0, minVol = 1e300;
    for (std::size_t c = 0; c < m.NumCells(); ++c)
    {
      const double v = CellMeasure(m, c);
      vol += v;
      minVol = std::min(minVol, v);
    }
    AV_CHECK_NEAR(vol, 3.0 * 1.0 * 2.5, 1e-12);
    // All 6 tets of a cube have the same volume (cube volume / 6).
    AV_CHECK_NEAR(minVol, 3.0 / 4 * 1.0 / 3 * 2.5 / 2 / 6.0, 1e-12);
    // Euler characteristic of a ball: V - E + F - T = 1 (checks conformity of the split).
    const std::size_t ne = UniqueEdges(m).size() / 2;
    // Faces: 4T = 2F_int + F_bnd, F_bnd = 2 triangles per boundary square.
    const std::size_t fb = 2 * 2 * ((nx - 1) * (ny - 1) + (ny - 1) * (nz - 1) + (nx - 1) * (nz - 1));
    const std::size_t nf = (4 * m.NumCells() + fb) / 2;
    AV_CHECK(static_cast<long>(m.NumPoints()) - static_cast<long>(ne) + static_cast<long>(nf) -
        static_cast<long>(m.NumCells()) ==
      1);
    const std::vector<char> bnd = BoundaryVertexMask(m);
    int nb = 0;
    for (char b : bnd)
    {
      nb += b;
    }
    AV_CHECK(nb == 60 - (nx - 2) * (ny - 2) * (nz - 2));
    AV_CHECK(m.Point(59)[0] == hi[0] && m.Point(59)[1] == hi[1] && m.Point(59)[2] == hi[2]);
  }
  {
    const double lo[2] = { 0.0, 0.0 }, hi[2] = { 2.0, 1.0 };
    const SimplexMesh m = MakeTriangleGrid(4, 3, lo, hi);
    AV_CHECK(m.AmbientDim == 2 && m.SimplexDim == 2);
    AV_CHECK(m.NumCells() == 12u);
    double area = 0.0;
    bool allPositive = true;
    for (std::size_t c = 0; c < m.NumCells(); ++c)
    {
      area += CellMeasure(m, c);
      allPositive = allPositive && CellMeasure(m, c) > 0.0;
    }
    AV_CHECK(allPositive);
    AV_CHECK_NEAR(area, 2.0, 1e-12);
    // V - E + F = 1 for a disk.
    AV_CHECK(12 - static_cast<long>(UniqueEdges(m).size() / 2) + 12 == 1);
    const std::vector<char> bnd = BoundaryVertexMask(m);
    AV_CHECK(bnd[5] == 0 && bnd[6] == 0 && bnd[0] == 1 && bnd[4] == 1);
  }
  const double z3[3] = { 0, 0, 0 }, o3[3] = { 1, 1, 1 };
  {
    // Two unit cubes stacked along z: copies of the points on z = 1 (two bodies), then the
    // upper cube's cells pointed at the lower cube's points there (one body).
    const double lo2[3] = { 0, 0, 1 }, hi2[3] = { 1, 1, 2 };
    const SimplexMesh a = MakeKuhnTetGrid(3, 3, 3, z3, o3), b = MakeKuhnTetGrid(3, 3, 3, lo2, hi2);
    SimplexMesh both = a;
    const std::int32_t offset = static_cast<std::int32_t>(a.NumPoints());
    both.Points.insert(both.Points.end(), b.Points.begin(), b.Points.end());
    for (std::int32_t id : b.Cells)
      both.Cells.push_back(id + offset);
    std::vector<std::int32_t> body;
    AV_CHECK(LabelBodies(a, body) == 1u && body.size() == a.NumPoints());
    AV_CHECK(LabelBodies(both, body) == 2u);
    AV_CHECK(body[0] == 0 && body[26] == 0 && body[27] == 1 && body[53] == 1);
    SimplexMesh merged = both;
    for (std::int32_t& id : merged.Cells)
      if (id >= offset && id - offset < 9) // b's z = 1 layer: ids 0..8, a's ids 18..26
        id = id - offset + 18;
    AV_CHECK(LabelBodies(merged, body) == 1u);
    AV_CHECK(CountPinchedBoundaryEdges(a) == 0 && CountPinchedBoundaryEdges(merged) == 0);
    // The upper cube shifted by +1 in x and joined to the lower one along the edge x = 1,
    // z = 1 only (its points (0, j, 0) become the lower cube's (2, j, 2)): 2 pinched edges.
    SimplexMesh edgeJoined = both;
    for (std::size_t p = static_cast<std::size_t>(offset); p < edgeJoined.NumPoints(); ++p)
      edgeJoined.Points[3 * p] += 1.0;
    for (std::size_t k = a.Cells.size(); k < edgeJoined.Cells.size(); ++k)
    {
      const std::int32_t id = edgeJoined.Cells[k] - offset; // i + 3 (j + 3 k) in the upper grid
      if (id % 3 == 0 && id < 9)
        edgeJoined.Cells[k] = 2 + 3 * (id / 3) + 18;
    }
    AV_CHECK_MSG(CountPinchedBoundaryEdges(edgeJoined) == 2u,
      CountPinchedBoundaryEdges(edgeJoined) << " pinched edges");
    std::vector<std::int32_t> edgeBody;
    AV_CHECK(LabelBodies(edgeJoined, edgeBody) == 1u);
    AV_CHECK(body[27] == -1 && body[35] == -1 && body[36] == 0); // b's z = 1 copies: unused
    SimplexMesh bad = a;
    bad.Cells[5] = 999;
    AV_CHECK_THROWS(LabelBodies(bad, body));
  }
  AV_CHECK_THROWS(MakeKuhnTetGrid(1, 3, 3, z3, o3));
  AV_CHECK_THROWS(MakeKuhnTetGrid(3, 3, 3, o3, z3));
  return AV_TEST_RESULT();
}
