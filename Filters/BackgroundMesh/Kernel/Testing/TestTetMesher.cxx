// SPDX-License-Identifier: BSD-3-Clause
// TetMesher: validity (orientation, volume, closed boundary), target counts, error handling.
#include "SurfaceGenerators.h"
#include "TetMesher.h"
#include "AnisoTestChecks.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

namespace
{
double SignedVolume(const av::SimplexMesh& m, std::size_t c)
{
  const std::int32_t* t = m.Cell(c);
  const Eigen::Map<const Eigen::Vector3d> a(m.Point(t[0])), b(m.Point(t[1])), d(m.Point(t[2])),
    e(m.Point(t[3]));
  return (b - a).dot((d - a).cross(e - a)) / 6.0;
}

/// Checks orientation and conformity; returns the total volume. Every face must be shared by
/// two tets (interior) or be a boundary face; boundary faces must form a closed surface.
double CheckTetMesh(const av::SimplexMesh& m, double* boundaryArea)
{
  AV_CHECK(m.AmbientDim == 3 && m.SimplexDim == 3);
  double volume = 0.0, minVolume = 1e300;
  std::map<std::array<std::int32_t, 3>, int> faces;
  std::vector<char> used(m.NumPoints(), 0);
  for (std::size_t c = 0; c < m.NumCells(); ++c)
  {
    const double v = SignedVolume(m, c);
    volume += v;
    minVolume = std::min(minVolume, v);
    const std::int32_t* t = m.Cell(c);
    for (int k = 0; k < 4; ++k)
    {
      used[static_cast<std::size_t>(t[k])] = 1;
      std::array<std::int32_t, 3> f = { t[(k + 1) % 4], t[(k + 2) % 4], t[(k + 3) % 4] };
      std::sort(f.begin(), f.end());
      ++faces[f];
    }
  }
  AV_CHECK_MSG(minVolume > 0.0, "min tet volume " << minVolume);
  AV_CHECK(std::all_of(used.begin(), used.end(), [](char u) { return u != 0; }));
  int bad = 0;
  double area = 0.0;
  for (const auto& f : faces)
  {
    bad += f.second > 2;
    if (f.second == 1)
    {
      const Eigen::Map<const Eigen::Vector3d> a(m.Point(f.first[0])), b(m.Point(f.first[1])),
        d(m.Point(f.first[2]));
      area += 0.5 * (b - a).cross(d - a).norm();
    }
  }
  AV_CHECK_MSG(bad == 0, bad << " faces shared by more than two tets");
  *boundaryArea = area;
  return volume;
}
} // namespace

int TestTetMesher(int, char*[])
{
  const double pi = 3.14159265358979323846;

  // Surface generators: closed, outward (divergence theorem volume > 0), right counts.
  {
    const av::SimplexMesh s = av::MakeIcosphere(2.0, 3);
    AV_CHECK(s.NumPoints() == 642 && s.NumCells() == 1280);
    double vol = 0.0;
    for (std::size_t c = 0; c < s.NumCells(); ++c)
    {
      const std::int32_t* t = s.Cell(c);
      const Eigen::Map<const Eigen::Vector3d> a(s.Point(t[0])), b(s.Point(t[1])),
        d(s.Point(t[2]));
      vol += a.dot(b.cross(d)) / 6.0;
    }
    AV_CHECK_NEAR(vol, 4.0 / 3.0 * pi * 8.0, 0.02 * 4.0 / 3.0 * pi * 8.0);
    AV_CHECK(vol < 4.0 / 3.0 * pi * 8.0); // inscribed polyhedron
    for (std::size_t i = 0; i < s.NumPoints(); ++i)
    {
      AV_CHECK_NEAR(Eigen::Map<const Eigen::Vector3d>(s.Point(i)).norm(), 2.0, 1e-12);
    }
  }

  // Ball with a target count: accurate count, valid mesh, volume close to the ball's.
  for (std::size_t target : { 500u, 5000u, 30000u })
  {
    const av::SimplexMesh m = av::TetrahedralizeSphere(1.5, target);
    const double rel = std::abs(static_cast<double>(m.NumPoints()) / target - 1.0);
    AV_CHECK_MSG(rel < 0.15, "target " << target << " got " << m.NumPoints());
    double area = 0.0;
    const double vol = CheckTetMesh(m, &area);
    const double exact = 4.0 / 3.0 * pi * 1.5 * 1.5 * 1.5;
    AV_CHECK_MSG(vol < exact && vol > 0.95 * exact, "ball volume " << vol);
    AV_CHECK_NEAR(area, 4.0 * pi * 1.5 * 1.5, 0.05 * 4.0 * pi * 1.5 * 1.5);
    for (std::size_t i = 0; i < m.NumPoints(); ++i)
    {
      AV_CHECK(Eigen::Map<const Eigen::Vector3d>(m.Point(i)).norm() <= 1.5 + 1e-9);
    }
  }

  // Box: exact volume and boundary area (the box is a polyhedron).
  {
    const double lo[3] = { -1, 0, 2 }, hi[3] = { 1, 0.5, 3 };
    const av::SimplexMesh m = av::TetrahedralizeBox(lo, hi, 3000);
    AV_CHECK(std::abs(m.NumPoints() / 3000.0 - 1.0) < 0.15);
    double area = 0.0;
    AV_CHECK_NEAR(CheckTetMesh(m, &area), 1.0, 1e-12);
    AV_CHECK_NEAR(area, 2 * (2 * 0.5 + 2 * 1 + 0.5 * 1), 1e-12);
  }

  // Closed-surface options: MaxVolume is honoured (TetGen's bound is loose by a few %),
  // PreserveSurface keeps the input points first and the boundary unsplit.
  for (double maxVolume : { 0.002, 0.0005 })
  {
    const av::SimplexMesh s = av::MakeIcosphere(1.0, 2);
    av::TetMeshOptions o;
    o.MaxVolume = maxVolume;
    const av::SimplexMesh m = av::TetrahedralizeClosedSurface(s, o);
    double maxVol = 0.0, area = 0.0;
    for (std::size_t c = 0; c < m.NumCells(); ++c)
    {
      maxVol = std::max(maxVol, SignedVolume(m, c));
    }
    AV_CHECK_MSG(maxVol <= 1.2 * maxVolume, "max tet volume " << maxVol);
    AV_CHECK(m.NumCells() * maxVolume > 0.9 * CheckTetMesh(m, &area));
    o.PreserveSurface = true;
    const av::SimplexMesh y = av::TetrahedralizeClosedSurface(s, o);
    for (std::size_t i = 0; i < s.Points.size(); ++i)
    {
      AV_CHECK(y.Points[i] == s.Points[i]);
    }
    double surfaceArea = 0.0;
    for (std::size_t c = 0; c < s.NumCells(); ++c)
    {
      const std::int32_t* t = s.Cell(c);
      const Eigen::Map<const Eigen::Vector3d> a(s.Point(t[0])), b(s.Point(t[1])),
        d(s.Point(t[2]));
      surfaceArea += 0.5 * (b - a).cross(d - a).norm();
    }
    CheckTetMesh(y, &area);
    AV_CHECK_NEAR(area, surfaceArea, 1e-10);
  }

  // Bad input is reported, not crashed on.
  {
    av::SimplexMesh s = av::MakeIcosphere(1.0, 1);
    av::SimplexMesh open = s;
    open.Cells.resize(open.Cells.size() - 3); // drop a triangle: 3 boundary edges
    AV_CHECK_THROWS(av::TetrahedralizeClosedSurface(open, av::TetMeshOptions()));
    av::SimplexMesh nan = s;
    nan.Points[4] = std::nan("");
    AV_CHECK_THROWS(av::TetrahedralizeClosedSurface(nan, av::TetMeshOptions()));
    av::SimplexMesh outOfRange = s;
    outOfRange.Cells[7] = 100000;
    AV_CHECK_THROWS(av::TetrahedralizeClosedSurface(outOfRange, av::TetMeshOptions()));
    av::SimplexMesh degenerate = s;
    degenerate.Cells[1] = degenerate.Cells[0];
    AV_CHECK_THROWS(av::TetrahedralizeClosedSurface(degenerate, av::TetMeshOptions()));
    // Two spheres sharing space: self-intersecting surface, TetGen's error becomes InputError.
    av::SimplexMesh twice = s;
    const std::size_t np = s.NumPoints();
    for (std::size_t i = 0; i < np; ++i)
    {
      twice.Points.insert(twice.Points.end(),
        { s.Points[3 * i] + 0.5, s.Points[3 * i + 1] + 0.01, s.Points[3 * i + 2] + 0.02 });
    }
    for (std::size_t i = 0; i < s.Cells.size(); ++i)
    {
      twice.Cells.push_back(s.Cells[i] + static_cast<std::int32_t>(np));
    }
    AV_CHECK_THROWS(av::TetrahedralizeClosedSurface(twice, av::TetMeshOptions()));
    av::SimplexMesh empty;
    empty.SimplexDim = 2;
    AV_CHECK_THROWS(av::TetrahedralizeClosedSurface(empty, av::TetMeshOptions()));
    AV_CHECK_THROWS(av::TetrahedralizeSphere(-1.0, 1000));
    AV_CHECK_THROWS(av::TetrahedralizeSphere(1.0, 3));
  }
  return AV_TEST_RESULT();
}
