// SPDX-License-Identifier: BSD-3-Clause
// Boundary-layer metric: sizes at the wall and far from it, the closed-form normal length
// against a numerical quadrature of 1 / h_z, the graded levels, the exact isometric embedding
// (edge lengths of the embedding against the metric's) and bad options.
#include "BoundaryLayerMetric.h"
#include "MetricAlgebra.h"
#include "StructuredMeshes.h"
#include "AnisoTestChecks.h"

#include <cmath>

namespace
{
using namespace av;

/// Simpson's rule of 1 / h_z on [0, z] with n (even) panels: an independent normal length.
double NormalLengthByQuadrature(const BoundaryLayerMetricOptions& o, double z, int n)
{
  const double h = z / n;
  double s = 1.0 / BoundaryLayerNormalSize(o, 0.0) + 1.0 / BoundaryLayerNormalSize(o, z);
  for (int i = 1; i < n; ++i)
    s += (i % 2 ? 4.0 : 2.0) / BoundaryLayerNormalSize(o, i * h);
  return s * h / 3.0;
}

void CheckProfile(BoundaryLayerProfile profile)
{
  BoundaryLayerMetricOptions o;
  o.Profile = profile;
  o.Stretch = 1000.0;
  const double h0 = o.TangentSize;
  AV_CHECK_NEAR(BoundaryLayerNormalSize(o, 0.0), h0 / 1000.0, 1e-15);
  // Linear reaches h0 at z = 1; the exponential is within e^-4 of it there (Thickness 0.25).
  AV_CHECK(BoundaryLayerNormalSize(o, 1.0) <= h0 * (1.0 + 1e-12));
  AV_CHECK(BoundaryLayerNormalSize(o, 1.0) > 0.98 * h0);
  for (double z : { 1e-4, 0.01, 0.3, 1.0 })
  {
    const double exact = BoundaryLayerNormalLength(o, z);
    const double quad = NormalLengthByQuadrature(o, z, 200000);
    AV_CHECK_NEAR(exact / quad, 1.0, 1e-6);
  }
  const double p[3] = { 0.3, 0.7, 0.05 };
  const Eigen::Matrix3d m = BoundaryLayerMetricAt(o, p);
  const double hz = BoundaryLayerNormalSize(o, 0.05);
  AV_CHECK_NEAR(m(0, 0) * h0 * h0, 1.0, 1e-12);
  AV_CHECK_NEAR(m(1, 1) * h0 * h0, 1.0, 1e-12);
  AV_CHECK_NEAR(m(2, 2) * hz * hz, 1.0, 1e-12);
  AV_CHECK(m(0, 1) == 0.0 && m(1, 2) == 0.0 && m(0, 2) == 0.0);

  // Levels: from 0 to 1, each step half of h_z below it (the last may be up to 1.25x that).
  const std::vector<double> z = BoundaryLayerLevels(o, 0.5);
  AV_CHECK(z.front() == 0.0 && z.back() == 1.0);
  for (std::size_t i = 1; i < z.size(); ++i)
  {
    const double step = z[i] - z[i - 1], h = BoundaryLayerNormalSize(o, z[i - 1]);
    AV_CHECK(step > 0.0 && step <= 0.5 * h * 1.25 + 1e-15);
  }
  // The isometric embedding: every edge of the graded grid has the metric's length (up to the
  // variation of h_z along one edge, a few % at most with half-size steps).
  std::vector<double> across(6);
  for (int i = 0; i < 6; ++i)
    across[i] = i / 5.0;
  const SimplexMesh grid = MakeKuhnTetGrid(across, across, z);
  const MetricField f = EvaluateBoundaryLayerMetric(o, grid);
  AV_CHECK(f.NumPoints() == grid.NumPoints());
  const Embedding e = BoundaryLayerIsometricEmbedding(o, grid, 8, 4.0);
  AV_CHECK(e.Dim == 8 && e.NumPoints() == grid.NumPoints());
  double worst = 0.0;
  for (std::size_t c = 0; c < grid.NumCells(); ++c)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b)
      {
        const std::int32_t i = grid.Cell(c)[a], j = grid.Cell(c)[b];
        const double* pi = grid.Point(i);
        const double* pj = grid.Point(j);
        // Exact metric length of the straight edge: the tangent part and the normal length
        // combine in quadrature only for axis-aligned edges, so compare those.
        const bool normal = pi[0] == pj[0] && pi[1] == pj[1];
        const bool tangent = pi[2] == pj[2];
        if (!normal && !tangent)
          continue;
        const double want = normal
          ? 2.0 * std::abs(BoundaryLayerNormalLength(o, pj[2]) - BoundaryLayerNormalLength(o, pi[2]))
          : 2.0 * std::hypot(pj[0] - pi[0], pj[1] - pi[1]) / h0;
        double got = 0.0;
        for (int d = 0; d < 8; ++d)
          got += (e.At(j)[d] - e.At(i)[d]) * (e.At(j)[d] - e.At(i)[d]);
        worst = std::max(worst, std::abs(std::sqrt(got) / want - 1.0));
        for (int d = 3; d < 8; ++d)
          AV_CHECK(e.At(i)[d] == 0.0);
      }
  AV_CHECK(worst < 1e-12);
}
} // namespace

int TestBoundaryLayerMetric(int, char*[])
{
  CheckProfile(BoundaryLayerProfile::Linear);
  CheckProfile(BoundaryLayerProfile::Exponential);
  AV_CHECK(BoundaryLayerProfileName(BoundaryLayerProfile::Exponential) == "exponential");
  // Isotropic limit: no layer, the normal length is z / h0.
  BoundaryLayerMetricOptions flat;
  flat.Stretch = 1.0;
  AV_CHECK_NEAR(BoundaryLayerNormalLength(flat, 0.5), 5.0, 1e-12);
  // Bad options and meshes.
  BoundaryLayerMetricOptions bad;
  bad.Stretch = 0.5;
  AV_CHECK_THROWS(CheckBoundaryLayerOptions(bad));
  bad.Stretch = std::nan("");
  AV_CHECK_THROWS(BoundaryLayerLevels(bad, 0.5));
  bad = BoundaryLayerMetricOptions();
  bad.TangentSize = 0.0;
  AV_CHECK_THROWS(CheckBoundaryLayerOptions(bad));
  bad = BoundaryLayerMetricOptions();
  bad.Thickness = -1.0;
  AV_CHECK_THROWS(CheckBoundaryLayerOptions(bad));
  AV_CHECK_THROWS(BoundaryLayerLevels(BoundaryLayerMetricOptions(), 0.0));
  AV_CHECK_THROWS(BoundaryLayerLevels(BoundaryLayerMetricOptions(), 1.5));
  const double lo[2] = { 0, 0 }, hi[2] = { 1, 1 };
  AV_CHECK_THROWS(EvaluateBoundaryLayerMetric(BoundaryLayerMetricOptions(), MakeTriangleGrid(3, 3, lo, hi)));
  const std::vector<double> two{ 0.0, 1.0 }, unsorted{ 0.0, 0.5, 0.2 };
  AV_CHECK_THROWS(MakeKuhnTetGrid(two, two, unsorted));
  AV_CHECK_THROWS(MakeKuhnTetGrid(two, std::vector<double>{ 0.0 }, two));
  return AV_TEST_RESULT();
}
