// SPDX-License-Identifier: BSD-3-Clause
// Reference embeddings: the pull-back of the map (central differences at sample points) equals
// the analytic metric for every supported preset; Cube1's height matches its closed form;
// Cube3's height across the cusp matches an independent fine quadrature; the piecewise-linear
// embedding of a grid has a small paper §5.1 edge error; bad input throws.
#include "AnalyticMetrics.h"
#include "EdgeLengthError.h"
#include "ReferenceEmbedding.h"
#include "StructuredMeshes.h"
#include "AnisoTestChecks.h"

#include <Eigen/Dense>

#include <cmath>
#include <vector>

namespace
{
using namespace av;

/// Pull-back J^T J of the reference embedding at p (central differences, step eps).
Eigen::Matrix3d PullBack(AnalyticPreset preset, const double* p, int m, double eps)
{
  SimplexMesh pts;
  pts.AmbientDim = m;
  pts.SimplexDim = m;
  for (int k = 0; k < m; ++k)
  {
    for (int sign = -1; sign <= 1; sign += 2)
    {
      for (int d = 0; d < m; ++d)
      {
        pts.Points.push_back(p[d] + (d == k ? sign * eps : 0.0));
      }
    }
  }
  const Embedding e = ComputeReferenceEmbedding(preset, pts, 8);
  Eigen::MatrixXd jac(8, m);
  for (int k = 0; k < m; ++k)
  {
    for (int r = 0; r < 8; ++r)
    {
      jac(r, k) = (e.At(2 * k + 1)[r] - e.At(2 * k)[r]) / (2.0 * eps);
    }
  }
  Eigen::Matrix3d g = Eigen::Matrix3d::Zero();
  g.topLeftCorner(m, m) = jac.transpose() * jac;
  return g;
}

/// Independent H(b) - H(a) for Cube3 (formula re-typed), composite midpoint rule, n panels.
double Cube3Height(double a, double b, int n)
{
  double sum = 0.0;
  const double h = (b - a) / n;
  for (int i = 0; i < n; ++i)
  {
    const double r = a + (i + 0.5) * h;
    const double s = 2.0 / (0.1 + 2.0 * (1.0 - std::exp(-0.01 * std::abs(r * r - 49.0))));
    sum += std::sqrt(s * s - 1.0) * h;
  }
  return sum;
}
} // namespace

int TestReferenceEmbedding(int, char*[])
{
  // 1. Isometry: J^T J = M at sample points of every supported preset.
  {
    struct Sample
    {
      AnalyticPreset Preset;
      double P[3];
    };
    const std::vector<Sample> samples = {
      { AnalyticPreset::Gaussian2D, { 0.21, -0.17, 0.0 } },
      { AnalyticPreset::Gaussian2D, { -0.5, 0.4, 0.0 } },
      { AnalyticPreset::Cube1, { 0.73, 0.2, 0.9 } },
      { AnalyticPreset::Cube2, { 0.31, 0.5, 0.5 } },
      { AnalyticPreset::Cube3, { 5.0, 6.0, 2.0 } },
      { AnalyticPreset::Cube3, { 2.0, 3.0, 9.0 } },
      { AnalyticPreset::SphereCylindrical, { 0.3, -0.4, 0.1 } },
    };
    for (const Sample& s : samples)
    {
      const int m = s.Preset == AnalyticPreset::Gaussian2D ? 2 : 3;
      const Eigen::Matrix3d want = AnalyticMetricAt(s.Preset, s.P);
      const Eigen::Matrix3d got = PullBack(s.Preset, s.P, m, 1e-5);
      const double err = (got - want).cwiseAbs().maxCoeff() / want.cwiseAbs().maxCoeff();
      AV_CHECK_MSG(err < 1e-6, AnalyticPresetName(s.Preset) << " relative pull-back error " << err);
    }
  }

  // 2. Cube1: H(x) - H(0) = (s sqrt(s^2 - 1) - acosh(s)) / 18, s = 1 + 9x; other coordinates kept.
  {
    const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
    const SimplexMesh mesh = MakeKuhnTetGrid(11, 2, 2, lo, hi);
    const Embedding e = ComputeReferenceEmbedding(AnalyticPreset::Cube1, mesh, 8);
    AV_CHECK(e.Dim == 8 && e.NumPoints() == mesh.NumPoints());
    for (std::size_t i = 0; i < mesh.NumPoints(); ++i)
    {
      const double x = mesh.Point(i)[0];
      const double s = 1.0 + 9.0 * x;
      const double want = (s * std::sqrt(s * s - 1.0) - std::acosh(s)) / 18.0;
      AV_CHECK_NEAR(e.At(i)[3], want, 1e-9);
      for (int d = 0; d < 3; ++d)
      {
        AV_CHECK(e.At(i)[d] == mesh.Point(i)[d]);
      }
      for (int d = 4; d < 8; ++d)
      {
        AV_CHECK(e.At(i)[d] == 0.0);
      }
    }
  }

  // 3. Cube3: the height across the cusp at r = 7 against an independent quadrature.
  {
    SimplexMesh pts;
    pts.AmbientDim = 3;
    pts.SimplexDim = 3;
    const std::vector<double> radii = { 6.0, 6.9, 7.0, 7.05, 8.5 };
    for (double r : radii)
    {
      pts.Points.insert(pts.Points.end(), { r * 0.6, r * 0.8, 4.0 });
    }
    const Embedding e = ComputeReferenceEmbedding(AnalyticPreset::Cube3, pts, 5);
    for (std::size_t i = 1; i < radii.size(); ++i)
    {
      const double want = Cube3Height(radii[0], radii[i], 2000000);
      AV_CHECK_NEAR(e.At(i)[3] - e.At(0)[3], want, 1e-7 * want);
    }
  }

  // 4. The piecewise-linear embedding of a grid: small paper §5.1 edge error; a wrong height
  //    (H' = S instead of sqrt(S^2 - 1)) is far off, so the measure can tell them apart.
  {
    const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
    const SimplexMesh mesh = MakeKuhnTetGrid(21, 6, 6, lo, hi);
    const MetricField metric = EvaluateAnalyticMetric(AnalyticPreset::Cube1, mesh);
    Embedding e = ComputeReferenceEmbedding(AnalyticPreset::Cube1, mesh, 8);
    const EdgeLengthErrorResult good = ComputeEdgeLengthError(mesh, metric, e);
    AV_CHECK_MSG(good.AveragePercent < 0.1, "L_avg " << good.AveragePercent);
    AV_CHECK_MSG(good.MaxPercent < 2.0, "L_max " << good.MaxPercent);
    for (std::size_t i = 0; i < mesh.NumPoints(); ++i)
    {
      const double x = mesh.Point(i)[0];
      e.Coords[i * 8 + 3] = x + 4.5 * x * x; // integral of S = 1 + 9x
    }
    const EdgeLengthErrorResult bad = ComputeEdgeLengthError(mesh, metric, e);
    AV_CHECK_MSG(bad.AveragePercent > 10.0 * good.AveragePercent, "L_avg " << bad.AveragePercent);
  }
  {
    const double lo[2] = { -1, -1 }, hi[2] = { 1, 1 };
    const SimplexMesh mesh = MakeTriangleGrid(41, 41, lo, hi);
    const Embedding e = ComputeReferenceEmbedding(AnalyticPreset::Gaussian2D, mesh, 3);
    const EdgeLengthErrorResult r =
      ComputeEdgeLengthError(mesh, EvaluateAnalyticMetric(AnalyticPreset::Gaussian2D, mesh), e);
    AV_CHECK_MSG(r.AveragePercent < 1.0, "gaussian2d L_avg " << r.AveragePercent);
  }

  // 5. Bad input.
  {
    const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
    const SimplexMesh cube = MakeKuhnTetGrid(3, 3, 3, lo, hi);
    AV_CHECK(!HasReferenceEmbedding(AnalyticPreset::SphereCosine));
    AV_CHECK_THROWS(ComputeReferenceEmbedding(AnalyticPreset::SphereCosine, cube, 8));
    AV_CHECK_THROWS(ComputeReferenceEmbedding(AnalyticPreset::Gaussian2D, cube, 8));
    AV_CHECK_THROWS(ComputeReferenceEmbedding(AnalyticPreset::Cube1, cube, 3));
    AV_CHECK_THROWS(ComputeReferenceEmbedding(AnalyticPreset::Cube1, cube, 21));
    SimplexMesh nan = cube;
    nan.Points[4] = std::nan("");
    AV_CHECK_THROWS(ComputeReferenceEmbedding(AnalyticPreset::Cube1, nan, 8));
  }
  return AV_TEST_RESULT();
}
