// SPDX-License-Identifier: BSD-3-Clause
#include "SurfaceGenerators.h"

#include <Eigen/Core>
#include <Eigen/Geometry> // cross products

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>

namespace av
{
namespace
{
/// Flips every triangle whose normal points against `outward(centroid)`.
template <class Outward>
void OrientOutward(SimplexMesh& mesh, Outward outward)
{
  for (std::size_t c = 0; c < mesh.NumCells(); ++c)
  {
    std::int32_t* t = mesh.Cells.data() + 3 * c;
    const Eigen::Map<const Eigen::Vector3d> a(mesh.Point(t[0])), b(mesh.Point(t[1])),
      d(mesh.Point(t[2]));
    const Eigen::Vector3d n = (b - a).cross(d - a);
    const Eigen::Vector3d centroid = (a + b + d) / 3.0;
    if (n.dot(outward(centroid)) < 0.0)
    {
      std::swap(t[1], t[2]);
    }
  }
}

/// A structured triangle grid over a (u, v) parameter rectangle: `nu` x `nv` intervals,
/// periodic directions wrap (no duplicated seam vertices), open ones get one more vertex
/// column / row. Each quad is split along its shorter diagonal; every triangle keeps the
/// orientation of (u, v), so the normal is along x_u x x_v.
template <class PointFn>
SimplexMesh ParametricGrid(PointFn point, int nu, int nv, bool periodicU, bool periodicV,
  double uSpan, double vSpan)
{
  SimplexMesh mesh;
  mesh.AmbientDim = 3;
  mesh.SimplexDim = 2;
  const int cu = periodicU ? nu : nu + 1;
  const int cv = periodicV ? nv : nv + 1;
  mesh.Points.resize(3 * static_cast<std::size_t>(cu) * cv);
  for (int j = 0; j < cv; ++j)
  {
    for (int i = 0; i < cu; ++i)
    {
      point(uSpan * i / nu, vSpan * j / nv, mesh.Points.data() + 3 * (j * cu + i));
    }
  }
  auto id = [&](int i, int j) { return static_cast<std::int32_t>((j % cv) * cu + (i % cu)); };
  auto distance2 = [&](std::int32_t p, std::int32_t q) {
    return (Eigen::Map<const Eigen::Vector3d>(mesh.Point(p)) -
      Eigen::Map<const Eigen::Vector3d>(mesh.Point(q)))
      .squaredNorm();
  };
  mesh.Cells.reserve(6 * static_cast<std::size_t>(nu) * nv);
  for (int j = 0; j < nv; ++j)
  {
    for (int i = 0; i < nu; ++i)
    {
      const std::int32_t p00 = id(i, j), p10 = id(i + 1, j), p11 = id(i + 1, j + 1),
                         p01 = id(i, j + 1);
      if (distance2(p00, p11) <= distance2(p10, p01))
      {
        mesh.Cells.insert(mesh.Cells.end(), { p00, p10, p11, p00, p11, p01 });
      }
      else
      {
        mesh.Cells.insert(mesh.Cells.end(), { p00, p10, p01, p10, p11, p01 });
      }
    }
  }
  return mesh;
}

/// Signed volume enclosed by a closed, consistently oriented triangle surface.
double EnclosedVolume(const SimplexMesh& mesh)
{
  double six = 0.0;
  for (std::size_t c = 0; c < mesh.NumCells(); ++c)
  {
    const std::int32_t* t = mesh.Cell(c);
    const Eigen::Map<const Eigen::Vector3d> a(mesh.Point(t[0])), b(mesh.Point(t[1])),
      d(mesh.Point(t[2]));
    six += a.dot(b.cross(d));
  }
  return six / 6.0;
}

void ReverseAll(SimplexMesh& mesh)
{
  for (std::size_t c = 0; c < mesh.NumCells(); ++c)
  {
    std::swap(mesh.Cells[3 * c + 1], mesh.Cells[3 * c + 2]);
  }
}

constexpr double kTwoPi = 6.28318530717958647692;
} // namespace

SimplexMesh MakeGeodesicSphere(double radius, int frequency)
{
  if (!(radius > 0.0) || !std::isfinite(radius))
  {
    throw InputError("MakeGeodesicSphere: radius must be positive and finite");
  }
  if (frequency < 1 || frequency > 4096)
  {
    throw InputError("MakeGeodesicSphere: frequency must be in [1, 4096], got " +
      std::to_string(frequency));
  }
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  const double iv[12][3] = { { -1, t, 0 }, { 1, t, 0 }, { -1, -t, 0 }, { 1, -t, 0 },
    { 0, -1, t }, { 0, 1, t }, { 0, -1, -t }, { 0, 1, -t }, { t, 0, -1 }, { t, 0, 1 },
    { -t, 0, -1 }, { -t, 0, 1 } };
  const int faces[20][3] = { { 0, 11, 5 }, { 0, 5, 1 }, { 0, 1, 7 }, { 0, 7, 10 },
    { 0, 10, 11 }, { 1, 5, 9 }, { 5, 11, 4 }, { 11, 10, 2 }, { 10, 7, 6 }, { 7, 1, 8 },
    { 3, 9, 4 }, { 3, 4, 2 }, { 3, 2, 6 }, { 3, 6, 8 }, { 3, 8, 9 }, { 4, 9, 5 }, { 2, 4, 11 },
    { 6, 2, 10 }, { 8, 6, 7 }, { 9, 8, 1 } };

  const int n = frequency;
  SimplexMesh mesh;
  mesh.AmbientDim = 3;
  mesh.SimplexDim = 2;
  const std::size_t nv = 10 * static_cast<std::size_t>(n) * n + 2;
  mesh.Points.reserve(3 * nv);
  mesh.Cells.reserve(60 * static_cast<std::size_t>(n) * n);
  // A lattice point is identified by its (icosahedron vertex, integer weight) pairs, which
  // are the same from every face that contains it.
  std::unordered_map<std::uint64_t, std::int32_t> ids;
  ids.reserve(nv);
  std::vector<std::int32_t> local;
  for (const auto& f : faces)
  {
    local.assign(static_cast<std::size_t>(n + 1) * (n + 1), -1);
    for (int i = 0; i <= n; ++i)
    {
      for (int j = 0; i + j <= n; ++j)
      {
        std::array<std::pair<int, int>, 3> vw = { { { f[0], n - i - j }, { f[1], i },
          { f[2], j } } };
        for (auto& p : vw)
        {
          if (p.second == 0)
          {
            p.first = -1; // zero weights sort first and pack as 0: same key from every face
          }
        }
        std::sort(vw.begin(), vw.end());
        std::uint64_t key = 0;
        for (const auto& p : vw)
        {
          const int w = p.second;
          key = (key << 20) | (w == 0 ? 0u : (static_cast<std::uint64_t>(p.first) << 16 | w));
        }
        auto it = ids.find(key);
        std::int32_t id;
        if (it == ids.end())
        {
          id = static_cast<std::int32_t>(mesh.Points.size() / 3);
          ids.emplace(key, id);
          Eigen::Vector3d x = Eigen::Vector3d::Zero();
          for (const auto& p : vw)
          {
            if (p.second > 0)
            {
              x += p.second * Eigen::Vector3d(iv[p.first]);
            }
          }
          x *= radius / x.norm();
          mesh.Points.insert(mesh.Points.end(), { x[0], x[1], x[2] });
        }
        else
        {
          id = it->second;
        }
        local[static_cast<std::size_t>(i) * (n + 1) + j] = id;
      }
    }
    auto L = [&](int i, int j) { return local[static_cast<std::size_t>(i) * (n + 1) + j]; };
    for (int i = 0; i < n; ++i)
    {
      for (int j = 0; i + j < n; ++j)
      {
        mesh.Cells.insert(mesh.Cells.end(), { L(i, j), L(i + 1, j), L(i, j + 1) });
        if (i + j + 2 <= n)
        {
          mesh.Cells.insert(mesh.Cells.end(), { L(i + 1, j), L(i + 1, j + 1), L(i, j + 1) });
        }
      }
    }
  }
  OrientOutward(mesh, [](const Eigen::Vector3d& c) { return c; });
  return mesh;
}

SimplexMesh MakeIcosphere(double radius, int subdivisions)
{
  if (subdivisions < 0 || subdivisions > 9)
  {
    throw InputError("MakeIcosphere: subdivisions must be in [0, 9], got " +
      std::to_string(subdivisions));
  }
  return MakeGeodesicSphere(radius, 1 << subdivisions);
}

SimplexMesh MakeBoxSurface(const double lo[3], const double hi[3], const int n[3])
{
  for (int d = 0; d < 3; ++d)
  {
    if (!std::isfinite(lo[d]) || !std::isfinite(hi[d]) || !(hi[d] > lo[d]))
    {
      throw InputError("MakeBoxSurface: need finite lo < hi on every axis");
    }
    if (n[d] < 1 || n[d] > 100000)
    {
      throw InputError("MakeBoxSurface: intervals per axis must be in [1, 100000]");
    }
  }
  SimplexMesh mesh;
  mesh.AmbientDim = 3;
  mesh.SimplexDim = 2;
  std::unordered_map<std::uint64_t, std::int32_t> ids;
  auto idOf = [&](const int ijk[3]) {
    const std::uint64_t key = (static_cast<std::uint64_t>(ijk[0]) * (n[1] + 1) + ijk[1]) *
        static_cast<std::uint64_t>(n[2] + 1) +
      ijk[2];
    auto it = ids.find(key);
    if (it != ids.end())
    {
      return it->second;
    }
    const auto id = static_cast<std::int32_t>(mesh.Points.size() / 3);
    ids.emplace(key, id);
    for (int d = 0; d < 3; ++d)
    {
      // Exact end values on the box faces.
      mesh.Points.push_back(ijk[d] == n[d] ? hi[d] : lo[d] + (hi[d] - lo[d]) * ijk[d] / n[d]);
    }
    return id;
  };
  for (int d = 0; d < 3; ++d)
  {
    const int u = (d + 1) % 3, v = (d + 2) % 3;
    for (int side = 0; side < 2; ++side)
    {
      for (int a = 0; a < n[u]; ++a)
      {
        for (int b = 0; b < n[v]; ++b)
        {
          std::int32_t q[4];
          const int corners[4][2] = { { a, b }, { a + 1, b }, { a + 1, b + 1 }, { a, b + 1 } };
          for (int k = 0; k < 4; ++k)
          {
            int ijk[3];
            ijk[d] = side * n[d];
            ijk[u] = corners[k][0];
            ijk[v] = corners[k][1];
            q[k] = idOf(ijk);
          }
          mesh.Cells.insert(mesh.Cells.end(), { q[0], q[1], q[2], q[0], q[2], q[3] });
        }
      }
    }
  }
  const Eigen::Vector3d center(
    (lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2);
  const Eigen::Vector3d half(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  OrientOutward(mesh, [&](const Eigen::Vector3d& c) {
    // The face's own axis: the coordinate closest to a box face (scaled by the box size).
    const Eigen::Vector3d r = (c - center).cwiseQuotient(half);
    int axis = 0;
    r.cwiseAbs().maxCoeff(&axis);
    Eigen::Vector3d o = Eigen::Vector3d::Zero();
    o[axis] = r[axis];
    return o;
  });
  return mesh;
}

SimplexMesh MakeCylinderSurface(double radius, double height, int around, int along)
{
  if (!(radius > 0.0) || !(height > 0.0) || !std::isfinite(radius) || !std::isfinite(height))
  {
    throw InputError("MakeCylinderSurface: radius and height must be positive and finite");
  }
  if (around < 3 || along < 1)
  {
    throw InputError("MakeCylinderSurface: need around >= 3 and along >= 1");
  }
  SimplexMesh mesh;
  mesh.AmbientDim = 3;
  mesh.SimplexDim = 2;
  const double pi = 3.14159265358979323846;
  for (int k = 0; k <= along; ++k)
  {
    for (int i = 0; i < around; ++i)
    {
      const double a = 2.0 * pi * (i + 0.5 * (k % 2)) / around;
      mesh.Points.insert(
        mesh.Points.end(), { radius * std::cos(a), radius * std::sin(a), height * k / along });
    }
  }
  auto id = [&](int k, int i) { return static_cast<std::int32_t>(k * around + (i % around)); };
  for (int k = 0; k < along; ++k)
  {
    for (int i = 0; i < around; ++i)
    {
      if (k % 2 == 0)
      {
        mesh.Cells.insert(mesh.Cells.end(), { id(k, i), id(k, i + 1), id(k + 1, i) });
        mesh.Cells.insert(mesh.Cells.end(), { id(k, i + 1), id(k + 1, i + 1), id(k + 1, i) });
      }
      else
      {
        mesh.Cells.insert(mesh.Cells.end(), { id(k, i), id(k + 1, i + 1), id(k + 1, i) });
        mesh.Cells.insert(mesh.Cells.end(), { id(k, i), id(k, i + 1), id(k + 1, i + 1) });
      }
    }
  }
  OrientOutward(mesh, [](const Eigen::Vector3d& c) { return Eigen::Vector3d(c[0], c[1], 0); });
  return mesh;
}

void TorusPoint(double majorRadius, double minorRadius, double u, double v, double xyz[3])
{
  const double ring = majorRadius + minorRadius * std::cos(v);
  xyz[0] = ring * std::cos(u);
  xyz[1] = ring * std::sin(u);
  xyz[2] = minorRadius * std::sin(v);
}

SimplexMesh MakeTorusSurface(double majorRadius, double minorRadius, int around, int tube,
  double uFraction, double vFraction)
{
  if (!(minorRadius > 0.0) || !(majorRadius > minorRadius) || !std::isfinite(majorRadius))
  {
    throw InputError("MakeTorusSurface: need finite radii with R > r > 0");
  }
  if (around < 3 || tube < 3 || around > 100000 || tube > 100000)
  {
    throw InputError("MakeTorusSurface: around and tube must be in [3, 100000]");
  }
  if (!(uFraction > 0.0 && uFraction <= 1.0) || !(vFraction > 0.0 && vFraction <= 1.0))
  {
    throw InputError("MakeTorusSurface: uFraction and vFraction must be in (0, 1]");
  }
  // x_u x x_v points outward for this parameterization (at u = v = 0 it is +x), so the grid's
  // (u, v) orientation is already the outward one.
  return ParametricGrid(
    [&](double u, double v, double* p) { TorusPoint(majorRadius, minorRadius, u, v, p); },
    around, tube, uFraction == 1.0, vFraction == 1.0, kTwoPi * uFraction, kTwoPi * vFraction);
}

void DupinCyclidePoint(double a, double c, double mu, double u, double v, double xyz[3])
{
  const double b2 = a * a - c * c;
  const double b = std::sqrt(b2);
  const double cu = std::cos(u), su = std::sin(u), cv = std::cos(v), sv = std::sin(v);
  const double d = a - c * cu * cv;
  xyz[0] = (mu * (c - a * cu * cv) + b2 * cu) / d;
  xyz[1] = b * su * (a - mu * cv) / d;
  xyz[2] = b * sv * (c * cu - mu) / d;
}

SimplexMesh MakeDupinCyclideSurface(double a, double c, double mu, int nu, int nv)
{
  if (!std::isfinite(a) || !std::isfinite(c) || !std::isfinite(mu) || !(c >= 0.0) ||
    !(mu > c) || !(a > mu))
  {
    throw InputError("MakeDupinCyclideSurface: a ring cyclide needs 0 <= c < mu < a");
  }
  if (nu < 3 || nv < 3 || nu > 100000 || nv > 100000)
  {
    throw InputError("MakeDupinCyclideSurface: nu and nv must be in [3, 100000]");
  }
  SimplexMesh mesh = ParametricGrid(
    [&](double u, double v, double* p) { DupinCyclidePoint(a, c, mu, u, v, p); }, nu, nv, true,
    true, kTwoPi, kTwoPi);
  if (EnclosedVolume(mesh) < 0.0)
  {
    ReverseAll(mesh);
  }
  return mesh;
}

} // namespace av
