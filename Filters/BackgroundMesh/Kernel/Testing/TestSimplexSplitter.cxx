// SPDX-License-Identifier: BSD-3-Clause
// SimplexSplitter: exact volume, conformity (every interior face shared by exactly two tets,
// boundary area exact) on hex blocks with randomly permuted point ids, mixed
// hex/wedge/pyramid columns, voxels/pixels, quadratic cells, interpolation weights, errors.
#include "AnisoTestChecks.h"
#include "SimplexSplitter.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <map>
#include <numeric>
#include <random>
#include <vector>

namespace
{
struct Cells
{
  std::vector<std::uint8_t> Types;
  std::vector<std::int64_t> Offsets{ 0 };
  std::vector<std::int64_t> Conn;
  void Add(int type, std::initializer_list<std::int64_t> ids)
  {
    this->Types.push_back(static_cast<std::uint8_t>(type));
    this->Conn.insert(this->Conn.end(), ids);
    this->Offsets.push_back(static_cast<std::int64_t>(this->Conn.size()));
  }
  void Add(int type, const std::vector<std::int64_t>& ids)
  {
    this->Types.push_back(static_cast<std::uint8_t>(type));
    this->Conn.insert(this->Conn.end(), ids.begin(), ids.end());
    this->Offsets.push_back(static_cast<std::int64_t>(this->Conn.size()));
  }
};

av::SimplexSplitResult Split(const std::vector<double>& pts, const Cells& c, int outDim = 3)
{
  return av::SplitIntoSimplices(pts.data(),
    pts.size() / 3,
    c.Types.data(),
    c.Offsets.data(),
    c.Conn.data(),
    c.Types.size(),
    outDim);
}

/// Volume, boundary area; checks orientation and that no face has more than two tets.
double CheckTets(const av::SimplexMesh& m, double& boundaryArea, int& overShared)
{
  double volume = 0.0, minVol = 1e300;
  std::map<std::array<std::int32_t, 3>, int> faces;
  for (std::size_t c = 0; c < m.NumCells(); ++c)
  {
    const std::int32_t* t = m.Cell(c);
    const Eigen::Map<const Eigen::Vector3d> a(m.Point(t[0])), b(m.Point(t[1])), d(m.Point(t[2])),
      e(m.Point(t[3]));
    const double v = (b - a).dot((d - a).cross(e - a)) / 6.0;
    volume += v;
    minVol = std::min(minVol, v);
    for (int k = 0; k < 4; ++k)
    {
      std::array<std::int32_t, 3> f = { t[(k + 1) % 4], t[(k + 2) % 4], t[(k + 3) % 4] };
      std::sort(f.begin(), f.end());
      ++faces[f];
    }
  }
  AV_CHECK_MSG(minVol > 0.0, "smallest tet volume " << minVol);
  boundaryArea = 0.0;
  overShared = 0;
  for (const auto& f : faces)
  {
    overShared += f.second > 2;
    if (f.second == 1)
    {
      const Eigen::Map<const Eigen::Vector3d> a(m.Point(f.first[0])), b(m.Point(f.first[1])),
        d(m.Point(f.first[2]));
      boundaryArea += 0.5 * (b - a).cross(d - a).norm();
    }
  }
  return volume;
}

/// Interpolating the input coordinates with the parent weights must give the output points.
void CheckParents(const av::SimplexSplitResult& r, const std::vector<double>& pts)
{
  const av::SimplexMesh& m = r.Mesh;
  AV_CHECK(r.PointParentOffsets.size() == m.NumPoints() + 1);
  AV_CHECK(r.CellParent.size() == m.NumCells());
  double worst = 0.0;
  for (std::size_t i = 0; i < m.NumPoints(); ++i)
  {
    double x[3] = { 0, 0, 0 }, wsum = 0.0;
    for (auto k = r.PointParentOffsets[i]; k < r.PointParentOffsets[i + 1]; ++k)
    {
      const auto p = static_cast<std::size_t>(r.PointParents[static_cast<std::size_t>(k)]);
      const double w = r.PointWeights[static_cast<std::size_t>(k)];
      wsum += w;
      for (int d = 0; d < 3; ++d)
      {
        x[d] += w * pts[3 * p + d];
      }
    }
    worst = std::max(worst, std::abs(wsum - 1.0));
    for (int d = 0; d < m.AmbientDim; ++d)
    {
      worst = std::max(worst, std::abs(x[d] - m.Point(i)[d]));
    }
  }
  AV_CHECK_MSG(worst < 1e-12, "parent interpolation off by " << worst);
}
// 1. Block of 4 x 3 x 2 hexahedra, point ids randomly permuted (so the face diagonals point
//   every way), in every VTK hex corner rotation.
void CheckHexBlock(std::mt19937& rng)
{
  const int nx = 4, ny = 3, nz = 2;
  const int np = (nx + 1) * (ny + 1) * (nz + 1);
  std::vector<std::int64_t> perm(np);
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), rng);
  std::vector<double> pts(3 * np);
  auto lid = [&](int i, int j, int k) { return perm[i + (nx + 1) * (j + (ny + 1) * k)]; };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
      {
        const auto id = static_cast<std::size_t>(lid(i, j, k));
        pts[3 * id] = 0.5 * i;
        pts[3 * id + 1] = 0.25 * j;
        pts[3 * id + 2] = 1.0 * k;
      }
  Cells c;
  int rot = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
      {
        std::array<std::int64_t, 4> bottom = {
          lid(i, j, k), lid(i + 1, j, k), lid(i + 1, j + 1, k), lid(i, j + 1, k)
        };
        std::array<std::int64_t, 4> top = {
          lid(i, j, k + 1), lid(i + 1, j, k + 1), lid(i + 1, j + 1, k + 1), lid(i, j + 1, k + 1)
        };
        std::rotate(bottom.begin(), bottom.begin() + rot % 4, bottom.end());
        std::rotate(top.begin(), top.begin() + rot % 4, top.end());
        ++rot;
        c.Add(12, { bottom[0], bottom[1], bottom[2], bottom[3], top[0], top[1], top[2], top[3] });
      }
  const av::SimplexSplitResult r = Split(pts, c);
  AV_CHECK(r.Mesh.SimplexDim == 3 && r.Mesh.NumCells() == 12u * nx * ny * nz);
  AV_CHECK(r.NumAddedPoints == static_cast<std::size_t>(nx * ny * nz));
  AV_CHECK(r.InputPointsKept);
  double area = 0.0;
  int over = 0;
  const double lx = 0.5 * nx, ly = 0.25 * ny, lz = 1.0 * nz;
  AV_CHECK_NEAR(CheckTets(r.Mesh, area, over), lx * ly * lz, 1e-12);
  AV_CHECK_MSG(over == 0, over << " faces in more than two tets");
  // A non-conforming split leaves interior faces used once: extra "boundary" area.
  AV_CHECK_NEAR(area, 2 * (lx * ly + ly * lz + lx * lz), 1e-12);
  CheckParents(r, pts);
  for (std::size_t t = 0; t < r.Mesh.NumCells(); ++t)
  {
    AV_CHECK(r.CellParent[t] == static_cast<std::int32_t>(t / 12));
  }
}

// 2. Mixed column: hexahedron, two wedges (quad faces shared with the hex and the pyramids),
//   three pyramids, a tetra on a pyramid face, with random ids; volume and conformity.
void CheckMixedColumn(std::mt19937& rng)
{
  for (int trial = 0; trial < 20; ++trial)
  {
    // Lattice points of a 1 x 1 x 3 column plus an apex above it.
    std::vector<std::int64_t> perm(17);
    std::iota(perm.begin(), perm.end(), 0);
    std::shuffle(perm.begin(), perm.end(), rng);
    std::vector<double> pts(3 * 17);
    auto id = [&](int i, int j, int k) { return perm[i + 2 * (j + 2 * k)]; };
    for (int k = 0; k < 4; ++k)
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i)
        {
          const auto p = static_cast<std::size_t>(id(i, j, k));
          pts[3 * p] = i;
          pts[3 * p + 1] = j;
          pts[3 * p + 2] = k;
        }
    const auto apex = static_cast<std::size_t>(perm[16]);
    pts[3 * apex] = 0.8;
    pts[3 * apex + 1] = 0.6;
    pts[3 * apex + 2] = 3.7;
    Cells c;
    c.Add(12,
      { id(0, 0, 0),
        id(1, 0, 0),
        id(1, 1, 0),
        id(0, 1, 0),
        id(0, 0, 1),
        id(1, 0, 1),
        id(1, 1, 1),
        id(0, 1, 1) });
    // Cube 2 (z in [1,2]) cut by the plane through its x-edges (y=0,z=1) and (y=1,z=2): two
    // wedges along x; the bottom quad belongs to wedge A, the top quad to wedge B.
    c.Add(13, { id(0, 0, 1), id(0, 1, 1), id(0, 1, 2), id(1, 0, 1), id(1, 1, 1), id(1, 1, 2) });
    c.Add(13, { id(0, 0, 1), id(0, 1, 2), id(0, 0, 2), id(1, 0, 1), id(1, 1, 2), id(1, 0, 2) });
    // Cube 3 (z in [2,3]): three pyramids with apex at its corner (0,0,3), bases the far faces.
    const std::int64_t a = id(0, 0, 3);
    c.Add(14, { id(0, 0, 2), id(1, 0, 2), id(1, 1, 2), id(0, 1, 2), a }); // z = 2
    c.Add(14, { id(1, 0, 2), id(1, 1, 2), id(1, 1, 3), id(1, 0, 3), a }); // x = 1
    c.Add(14, { id(0, 1, 2), id(0, 1, 3), id(1, 1, 3), id(1, 1, 2), a }); // y = 1
    // A tetra on the top triangle (a, (1,0,3), (1,1,3)) made by the pyramids.
    c.Add(10, { a, id(1, 0, 3), id(1, 1, 3), static_cast<std::int64_t>(apex) });
    const av::SimplexSplitResult r = Split(pts, c);
    double area = 0.0;
    int over = 0;
    const Eigen::Vector3d ap(0.8, 0.6, 3.7), t0(0, 0, 3), t1(1, 0, 3), t2(1, 1, 3);
    const double tetVolume = std::abs((t1 - t0).dot((t2 - t0).cross(ap - t0))) / 6.0;
    AV_CHECK_NEAR(CheckTets(r.Mesh, area, over), 3.0 + tetVolume, 1e-12);
    AV_CHECK(over == 0);
    // Column boundary 14, minus the triangle covered by the tet, plus the tet's 3 other faces.
    auto tri = [](const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& w)
    { return 0.5 * (q - p).cross(w - p).norm(); };
    AV_CHECK_NEAR(
      area, 14.0 - tri(t0, t1, t2) + tri(t0, t1, ap) + tri(t1, t2, ap) + tri(t2, t0, ap), 1e-12);
    AV_CHECK(r.Mesh.NumCells() == 12 + 3 + 3 + 3 * 2 + 1);
    CheckParents(r, pts);
  }
}

// 3. Voxels and pixels (lexicographic corner order), quadratic cells reduced to corners.
void CheckVoxelsPixelsQuadratic()
{
  std::vector<double> pts;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i)
        pts.insert(pts.end(), { 1.0 * i, 2.0 * j, 3.0 * k });
  auto id = [](int i, int j, int k) { return static_cast<std::int64_t>(i + 3 * (j + 2 * k)); };
  Cells c;
  for (int i = 0; i < 2; ++i)
  {
    c.Add(11,
      { id(i, 0, 0),
        id(i + 1, 0, 0),
        id(i, 1, 0),
        id(i + 1, 1, 0),
        id(i, 0, 1),
        id(i + 1, 0, 1),
        id(i, 1, 1),
        id(i + 1, 1, 1) });
  }
  const auto r = Split(pts, c);
  double area = 0.0;
  int over = 0;
  AV_CHECK_NEAR(CheckTets(r.Mesh, area, over), 12.0, 1e-12);
  AV_CHECK(over == 0);
  AV_CHECK_NEAR(area, 2 * (2 * 2 + 2 * 3 + 2 * 3), 1e-12);

  // Pixels + quads + a triangle in 2D, output in R^2, counter-clockwise.
  Cells q;
  q.Add(8, { id(0, 0, 0), id(1, 0, 0), id(0, 1, 0), id(1, 1, 0) });
  q.Add(9, { id(1, 0, 0), id(1, 1, 0), id(2, 1, 0), id(2, 0, 0) }); // clockwise quad
  const auto t = Split(pts, q, 2);
  AV_CHECK(t.Mesh.AmbientDim == 2 && t.Mesh.SimplexDim == 2 && t.Mesh.NumCells() == 4);
  double total = 0.0, minArea = 1e300;
  std::map<std::pair<int, int>, int> edges;
  for (std::size_t e = 0; e < t.Mesh.NumCells(); ++e)
  {
    const std::int32_t* v = t.Mesh.Cell(e);
    const double* p0 = t.Mesh.Point(v[0]);
    const double* p1 = t.Mesh.Point(v[1]);
    const double* p2 = t.Mesh.Point(v[2]);
    const double a2 = (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p1[1] - p0[1]) * (p2[0] - p0[0]);
    total += a2 / 2;
    minArea = std::min(minArea, a2 / 2);
    for (int k = 0; k < 3; ++k)
    {
      ++edges[{ std::min(v[k], v[(k + 1) % 3]), std::max(v[k], v[(k + 1) % 3]) }];
    }
  }
  AV_CHECK_NEAR(total, 4.0, 1e-12);
  AV_CHECK(minArea > 0.0);
  AV_CHECK((edges[{ static_cast<int>(id(1, 0, 0)), static_cast<int>(id(1, 1, 0)) }] == 2));
  AV_CHECK(!t.InputPointsKept); // the z = 3 layer is unused and dropped
  AV_CHECK(t.Mesh.NumPoints() == 6);
  CheckParents(t, pts);

  // Quadratic tetra: mid-edge nodes dropped, output points map back to their input ids.
  std::vector<double> qp = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  const int edgesOfTet[6][2] = { { 0, 1 }, { 1, 2 }, { 2, 0 }, { 0, 3 }, { 1, 3 }, { 2, 3 } };
  for (const auto& e : edgesOfTet)
  {
    for (int d = 0; d < 3; ++d)
    {
      qp.push_back(0.5 * (qp[3 * e[0] + d] + qp[3 * e[1] + d]) + 0.01); // curved a bit
    }
  }
  Cells qt;
  qt.Add(24, { 0, 1, 2, 3, 4, 5, 6, 7, 8, 9 });
  const auto rq = Split(qp, qt);
  AV_CHECK(rq.Mesh.NumPoints() == 4 && rq.Mesh.NumCells() == 1 && !rq.InputPointsKept);
  CheckParents(rq, qp);
}

// 4. Degenerate (collapsed) hexahedron: zero-volume pieces dropped, the rest exact.
void CheckCollapsedHexahedron()
{
  // Hex with its top face collapsed onto an edge: a wedge-shaped cell.
  std::vector<double> pts = { 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1 };
  Cells c;
  c.Add(12, { 0, 1, 2, 3, 4, 5, 5, 4 });
  const auto r = Split(pts, c);
  double area = 0.0;
  int over = 0;
  AV_CHECK_NEAR(CheckTets(r.Mesh, area, over), 0.5, 1e-12);
  AV_CHECK(r.NumDroppedSimplices > 0);
}

// 5. Errors.
void CheckErrors()
{
  std::vector<double> pts = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 0 };
  Cells polygon;
  polygon.Add(7, { 0, 1, 4, 2 });
  AV_CHECK_THROWS(Split(pts, polygon));
  Cells mixed;
  mixed.Add(10, { 0, 1, 2, 3 });
  mixed.Add(5, { 0, 1, 2 });
  AV_CHECK_THROWS(Split(pts, mixed));
  Cells wrongCount;
  wrongCount.Add(10, { 0, 1, 2 });
  AV_CHECK_THROWS(Split(pts, wrongCount));
  Cells outOfRange;
  outOfRange.Add(10, { 0, 1, 2, 9 });
  AV_CHECK_THROWS(Split(pts, outOfRange));
  Cells empty;
  AV_CHECK_THROWS(Split(pts, empty));
  Cells flat;
  flat.Add(10, { 0, 1, 2, 4 }); // all in z = 0
  AV_CHECK_THROWS(Split(pts, flat));
  std::vector<double> nan = pts;
  nan[4] = std::nan("");
  Cells tet;
  tet.Add(10, { 0, 1, 2, 3 });
  AV_CHECK_THROWS(Split(nan, tet));
  AV_CHECK(av::VtkCellTypeName(7) == "VTK_POLYGON");
}
} // namespace

int TestSimplexSplitter(int, char*[])
{
  std::mt19937 rng(42); // one stream for both randomised cases, in this order
  CheckHexBlock(rng);
  CheckMixedColumn(rng);
  CheckVoxelsPixelsQuadratic();
  CheckCollapsedHexahedron();
  CheckErrors();
  return AV_TEST_RESULT();
}
