// SPDX-License-Identifier: BSD-3-Clause
// SurfaceCurvatureMetric against closed forms: on a torus and on a Dupin cyclide the lines of
// curvature are the parameter lines, so the principal directions are x_u / |x_u| and
// x_v / |x_v| and the principal curvatures the normal curvatures along them, computed here by
// finite differences of the generators' closed forms (not of the mesh).
#include "AnisoTestChecks.h"
#include "SurfaceCurvatureMetric.h"
#include "SurfaceGenerators.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>

namespace
{
using PointFn = std::function<void(double, double, double*)>;

Eigen::Vector3d At(const PointFn& f, double u, double v)
{
  Eigen::Vector3d p;
  f(u, v, p.data());
  return p;
}

/// Unit tangents along u and v and the absolute normal curvatures along them at (u, v).
void Analytic(const PointFn& f,
  double u,
  double v,
  Eigen::Vector3d& tu,
  Eigen::Vector3d& tv,
  double& ku,
  double& kv)
{
  const double h = 1e-4;
  const Eigen::Vector3d p = At(f, u, v);
  const Eigen::Vector3d xu = (At(f, u + h, v) - At(f, u - h, v)) / (2 * h);
  const Eigen::Vector3d xv = (At(f, u, v + h) - At(f, u, v - h)) / (2 * h);
  const Eigen::Vector3d xuu = (At(f, u + h, v) - 2 * p + At(f, u - h, v)) / (h * h);
  const Eigen::Vector3d xvv = (At(f, u, v + h) - 2 * p + At(f, u, v - h)) / (h * h);
  const Eigen::Vector3d n = xu.cross(xv).normalized();
  ku = std::abs(xuu.dot(n)) / xu.squaredNorm();
  kv = std::abs(xvv.dot(n)) / xv.squaredNorm();
  tu = xu.normalized();
  tv = xv.normalized();
}

struct Agreement
{
  int Checked = 0;
  double WorstAngle = 0.0;     ///< degrees between v_max and the analytic direction
  double WorstKMax = 0.0;      ///< relative error of |K_max|
  double WorstKMin = 0.0;      ///< error of |K_min| relative to |K_max|
  double WorstNormalDot = 1.0; ///< smallest |n . analytic normal|
};

/// Compares the kernel's directions and curvatures with the closed form at every vertex of a
/// periodic nu x nv grid (vertex j * nu + i at u = 2 pi i / nu, v = 2 pi j / nv) where the
/// analytic curvatures differ by at least `minRatio` (elsewhere the directions are not defined
/// well enough to compare).
Agreement Compare(const av::SimplexMesh& mesh,
  const PointFn& f,
  int nu,
  int nv,
  const av::SurfaceCurvatureMetricResult& r,
  double minRatio)
{
  const double twoPi = 6.28318530717958647692;
  Agreement a;
  for (int j = 0; j < nv; ++j)
  {
    for (int i = 0; i < nu; ++i)
    {
      const std::size_t id = static_cast<std::size_t>(j) * nu + i;
      Eigen::Vector3d tu, tv;
      double ku, kv;
      Analytic(f, twoPi * i / nu, twoPi * j / nv, tu, tv, ku, kv);
      const double kmax = std::max(ku, kv), kmin = std::min(ku, kv);
      if (kmax < minRatio * kmin)
        continue;
      ++a.Checked;
      const Eigen::Vector3d expected = ku > kv ? tu : tv;
      const Eigen::Vector3d vmax(r.MaxDirection.data() + 3 * id);
      const double c = std::min(1.0, std::abs(vmax.dot(expected)));
      a.WorstAngle = std::max(a.WorstAngle, std::acos(c) * 180.0 / 3.14159265358979);
      a.WorstKMax = std::max(a.WorstKMax, std::abs(std::abs(r.MaxCurvature[id]) - kmax) / kmax);
      a.WorstKMin = std::max(a.WorstKMin, std::abs(std::abs(r.MinCurvature[id]) - kmin) / kmax);
      const Eigen::Vector3d n(r.Normals.data() + 3 * id);
      a.WorstNormalDot = std::min(a.WorstNormalDot, std::abs(n.dot(tu.cross(tv).normalized())));
      AV_CHECK(std::isfinite(r.StretchRatio[id]));
      // Orthonormal tangent frame.
      const Eigen::Vector3d vmin(r.MinDirection.data() + 3 * id);
      AV_CHECK(std::abs(vmin.dot(vmax)) < 1e-9 && std::abs(vmin.dot(n)) < 1e-9);
    }
  }
  std::cout << a.Checked << " vertices: v_max within " << a.WorstAngle << " deg, |K_max| within "
            << 100 * a.WorstKMax << " %, |K_min| within " << 100 * a.WorstKMin
            << " % of K_max, normals |cos| >= " << a.WorstNormalDot << std::endl;
  return a;
}
} // namespace

int TestSurfaceCurvatureDirections(int, char*[])
{
  // Torus R = 3, r = 1: |K| = 1 along the tube (v), |cos v| / (3 + cos v) <= 0.25 along u.
  {
    const int nu = 160, nv = 64;
    const av::SimplexMesh torus = av::MakeTorusSurface(3.0, 1.0, nu, nv);
    AV_CHECK(torus.NumPoints() == static_cast<std::size_t>(nu * nv));
    av::SurfaceCurvatureMetricOptions o;
    const auto r = av::SurfaceCurvatureMetric(torus, o);
    const PointFn f = [](double u, double v, double* p) { av::TorusPoint(3.0, 1.0, u, v, p); };
    const Agreement a = Compare(torus, f, nu, nv, r, 1.5);
    AV_CHECK(a.Checked == nu * nv); // the tube direction dominates everywhere
    AV_CHECK_MSG(
      a.WorstAngle < 1.0, "torus: v_max off the tube direction by " << a.WorstAngle << " deg");
    AV_CHECK_MSG(a.WorstKMax < 0.03, "torus: |K_max| off by " << 100 * a.WorstKMax << " %");
    AV_CHECK_MSG(
      a.WorstKMin < 0.03, "torus: |K_min| off by " << 100 * a.WorstKMin << " % of K_max");
    AV_CHECK_MSG(a.WorstNormalDot > 0.9999, "torus: normals off, |cos| " << a.WorstNormalDot);
    // Outward orientation of the generator: the normal at (u, v) = (0, 0) is +x.
    AV_CHECK(r.Normals[0] > 0.999);
  }

  // Cyclide1 of Tab. 3 (a = 2, c = 1, mu = 1.5), a finer grid than the benchmark's.
  {
    const int nu = 160, nv = 120;
    const av::SimplexMesh cyclide = av::MakeDupinCyclideSurface(2.0, 1.0, 1.5, nu, nv);
    av::SurfaceCurvatureMetricOptions o;
    const auto r = av::SurfaceCurvatureMetric(cyclide, o);
    const PointFn f = [](double u, double v, double* p)
    { av::DupinCyclidePoint(2.0, 1.0, 1.5, u, v, p); };
    const Agreement a = Compare(cyclide, f, nu, nv, r, 1.5);
    AV_CHECK_MSG(a.Checked > nu * nv / 2, "cyclide: only " << a.Checked << " anisotropic vertices");
    AV_CHECK_MSG(
      a.WorstAngle < 2.0, "cyclide: v_max off the curvature line by " << a.WorstAngle << " deg");
    AV_CHECK_MSG(a.WorstKMax < 0.05, "cyclide: |K_max| off by " << 100 * a.WorstKMax << " %");
    AV_CHECK_MSG(
      a.WorstKMin < 0.05, "cyclide: |K_min| off by " << 100 * a.WorstKMin << " % of K_max");
    AV_CHECK_MSG(a.WorstNormalDot > 0.9999, "cyclide: normals off, |cos| " << a.WorstNormalDot);
    // The closed form has umbilic lines (|K_u| = |K_v|, ratio 1) and lines where one curvature
    // vanishes (ratio from the floor 0.1 / diagonal, about 10.5): after smoothing the range is
    // about [1, 9], under the default cap of 10.
    const auto [lo, hi] = std::minmax_element(r.StretchRatio.begin(), r.StretchRatio.end());
    AV_CHECK_MSG(*lo >= 1.0 && *lo < 1.1 && *hi > 8.0 && *hi <= 10.0 + 1e-12,
      "cyclide stretch range [" << *lo << ", " << *hi << "]");
  }
  return AV_TEST_RESULT();
}
