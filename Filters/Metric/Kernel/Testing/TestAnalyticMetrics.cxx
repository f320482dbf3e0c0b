// SPDX-License-Identifier: BSD-3-Clause
// Analytic presets: values at sample points against the paper's formulas (independently
// re-typed here), the Gaussian metric against finite differences of its height field, stretch
// ranges, name lookup and dimension checks.
#include "AnalyticMetrics.h"
#include "MetricAlgebra.h"
#include "StructuredMeshes.h"
#include "AnisoTestChecks.h"

#include <algorithm>
#include <cmath>

namespace
{
double MaxDiff(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b)
{
  return (a - b).cwiseAbs().maxCoeff();
}
Eigen::Matrix3d Stretched(double s, Eigen::Vector3d u)
{
  u.normalize();
  return Eigen::Matrix3d::Identity() + (s * s - 1.0) * u * u.transpose();
}
}

int TestAnalyticMetrics(int, char*[])
{
  using namespace av;
  // Cube1: S = 1 + 9x along x.
  {
    const double p[3] = { 0.5, 0.3, 0.9 };
    Eigen::Matrix3d want = Eigen::Matrix3d::Identity();
    want(0, 0) = 5.5 * 5.5;
    AV_CHECK(MaxDiff(AnalyticMetricAt(AnalyticPreset::Cube1, p), want) < 1e-12);
  }
  // Cube2: peak 0.2 * 0.0025^-0.8 at x = 0.5, and a value away from it.
  {
    const double p[3] = { 0.5, 0.1, 0.1 }, q[3] = { 0.1, 0.7, 0.2 };
    const double s0 = 0.2 * std::pow(0.0025, -0.8);
    const double s1 = 0.2 * std::pow(0.0025 + 0.2 * (1.0 - std::exp(-0.4)), -0.8);
    AV_CHECK_NEAR(AnalyticMetricAt(AnalyticPreset::Cube2, p)(0, 0), s0 * s0, 1e-9);
    AV_CHECK_NEAR(AnalyticMetricAt(AnalyticPreset::Cube2, q)(0, 0), s1 * s1, 1e-9);
    AV_CHECK_NEAR(AnalyticMetricAt(AnalyticPreset::Cube2, q)(1, 1), 1.0, 1e-12);
  }
  // Cube3: S = 20 on the cylinder r = 7, radial direction.
  {
    const double p[3] = { 7.0, 0.0, 3.0 }, q[3] = { 3.0, 4.0, 5.0 };
    AV_CHECK(MaxDiff(AnalyticMetricAt(AnalyticPreset::Cube3, p), Stretched(20.0, { 1, 0, 0 })) < 1e-9);
    const double s = 2.0 / (0.1 + 2.0 * (1.0 - std::exp(-0.01 * 24.0)));
    AV_CHECK(MaxDiff(AnalyticMetricAt(AnalyticPreset::Cube3, q), Stretched(s, { 3, 4, 0 })) < 1e-9);
  }
  // Sphere, cylindrical: S = 1 + 4r along (x, y, 0) / r.
  {
    const double p[3] = { 0.3, 0.4, -0.5 }, axis[3] = { 0.0, 0.0, 0.7 };
    AV_CHECK(MaxDiff(AnalyticMetricAt(AnalyticPreset::SphereCylindrical, p), Stretched(3.0, { 3, 4, 0 })) < 1e-12);
    AV_CHECK(MaxDiff(AnalyticMetricAt(AnalyticPreset::SphereCylindrical, axis), Eigen::Matrix3d::Identity()) < 1e-12);
  }
  // Sphere, cosine: 10 along (2cos4x, 1, 0), 1 along (1, -2cos4x, 0) and z.
  {
    const double p[3] = { 0.2, -0.3, 0.1 };
    const double c = 2.0 * std::cos(0.8);
    const Eigen::Matrix3d m = AnalyticMetricAt(AnalyticPreset::SphereCosine, p);
    const Eigen::Vector3d a(c, 1.0, 0.0), b(1.0, -c, 0.0);
    AV_CHECK((m * a - 100.0 * a).norm() < 1e-10);
    AV_CHECK((m * b - b).norm() < 1e-12);
    AV_CHECK((m * Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitZ()).norm() < 1e-12);
  }
  // Gaussian: M = I + grad h grad h^T (finite differences), stretch range [1, 3.85].
  {
    const double x = 0.21, y = -0.13, e = 1e-6;
    const double gx = (GaussianHeight(x + e, y) - GaussianHeight(x - e, y)) / (2 * e);
    const double gy = (GaussianHeight(x, y + e) - GaussianHeight(x, y - e)) / (2 * e);
    const double p[2] = { x, y };
    const Eigen::Matrix3d m = AnalyticMetricAt(AnalyticPreset::Gaussian2D, p);
    AV_CHECK_NEAR(m(0, 0), 1 + gx * gx, 1e-6);
    AV_CHECK_NEAR(m(1, 1), 1 + gy * gy, 1e-6);
    AV_CHECK_NEAR(m(0, 1), gx * gy, 1e-6);
    AV_CHECK(m(2, 2) == 0.0);
    const AnalyticDomain d = RecommendedDomain(AnalyticPreset::Gaussian2D);
    const SimplexMesh mesh = MakeTriangleGrid(201, 201, d.Lo, d.Hi);
    const MetricField f = EvaluateAnalyticMetric(AnalyticPreset::Gaussian2D, mesh);
    double smin = 1e300, smax = 0;
    for (std::size_t i = 0; i < f.NumPoints(); ++i)
    {
      const double s = StretchRatio(UnpackSymmetric2(f.At(i)));
      smin = std::min(smin, s);
      smax = std::max(smax, s);
    }
    AV_CHECK_NEAR(smin, 1.0, 1e-6);
    AV_CHECK_NEAR(smax, 3.85, 0.01);
    AV_CHECK_THROWS(EvaluateAnalyticMetric(AnalyticPreset::Cube1, mesh));
  }
  // Stretch range of Cube2 on its recommended grid: [1.491, 24.14].
  {
    const AnalyticDomain d = RecommendedDomain(AnalyticPreset::Cube2);
    const SimplexMesh mesh = MakeKuhnTetGrid(d.GridVertices[0], 3, 3, d.Lo, d.Hi);
    AV_CHECK(mesh.NumPoints() == 101u * 9);
    const MetricField f = EvaluateAnalyticMetric(AnalyticPreset::Cube2, mesh);
    double smin = 1e300, smax = 0;
    for (std::size_t i = 0; i < f.NumPoints(); ++i)
    {
      const double s = StretchRatio(UnpackSymmetric(f.At(i)));
      smin = std::min(smin, s);
      smax = std::max(smax, s);
    }
    AV_CHECK_NEAR(smin, 1.49077, 1e-4);
    AV_CHECK_NEAR(smax, 24.1367, 1e-3);
    AV_CHECK_THROWS(EvaluateAnalyticMetric(AnalyticPreset::Gaussian2D, mesh));
  }
  for (AnalyticPreset p : AllAnalyticPresets())
  {
    AV_CHECK(AnalyticPresetFromName(AnalyticPresetName(p)) == p);
  }
  AV_CHECK_THROWS(AnalyticPresetFromName("cube9"));
  return AV_TEST_RESULT();
}
