// SPDX-License-Identifier: BSD-3-Clause
// MetricScaling: after scaling the smallest eigenvalue over the field is 1 when it was < 1 and
// the field is unchanged otherwise; 2D domains, rank-2 surface metrics and bad fields.
#include "MetricAlgebra.h"
#include "MetricScaling.h"
#include "AnisoTestChecks.h"

#include <Eigen/Dense>

#include <vector>

namespace
{
/// A mesh of the given kind; ScaleMetricForEmbedding reads only its dimensions.
av::SimplexMesh Mesh(int ambientDim, int simplexDim)
{
  av::SimplexMesh mesh;
  mesh.AmbientDim = ambientDim;
  mesh.SimplexDim = simplexDim;
  return mesh;
}

/// One point per diagonal, each rotated by a different frame.
av::MetricField Field(const std::vector<Eigen::Vector3d>& diagonals)
{
  av::MetricField f;
  f.Values.resize(6 * diagonals.size());
  for (std::size_t i = 0; i < diagonals.size(); ++i)
  {
    const Eigen::Matrix3d r =
      Eigen::AngleAxisd(0.4 + 0.3 * i, Eigen::Vector3d(1.0, 2.0, -0.5).normalized())
        .toRotationMatrix();
    av::PackSymmetric(r * diagonals[i].asDiagonal() * r.transpose(), f.Values.data() + 6 * i);
  }
  return f;
}

double Smallest(const av::MetricField& f, bool dim2)
{
  double lo = 0.0, hi = 0.0;
  av::EigenvalueRange(f, dim2, lo, hi);
  return lo;
}

void CheckVolumes()
{
  const av::SimplexMesh volume = Mesh(3, 3);
  // Smallest eigenvalue 0.25 < 1: c = 4, smallest becomes 1, the whole field is multiplied.
  av::MetricField f = Field({ { 2.0, 3.0, 5.0 }, { 0.25, 1.0, 9.0 }, { 1.0, 1.0, 1.0 } });
  const av::MetricField before = f;
  const av::MetricScaling s = av::ScaleMetricForEmbedding(volume, f);
  AV_CHECK_NEAR(s.SmallestEigenvalue, 0.25, 1e-12);
  AV_CHECK_NEAR(s.Scale, 4.0, 1e-11);
  AV_CHECK_NEAR(Smallest(f, false), 1.0, 1e-12);
  for (std::size_t k = 0; k < f.Values.size(); ++k)
  {
    AV_CHECK(f.Values[k] == before.Values[k] * s.Scale);
  }
  // Already >= 1 (including exactly 1 after the scaling above): unchanged, bit for bit.
  for (av::MetricField g : { Field({ { 1.5, 2.0, 30.0 }, { 4.0, 1.2, 1.1 } }), f })
  {
    const av::MetricField kept = g;
    const av::MetricScaling t = av::ScaleMetricForEmbedding(volume, g);
    AV_CHECK(t.Scale == 1.0);
    AV_CHECK(g.Values == kept.Values);
  }
}

void CheckDomain2D()
{
  // 2D domain: only the XX, YY, XY block counts (ZZ = 0 would make a 3D metric singular).
  av::MetricField f;
  f.Values = { 0.5, 2.0, 0.0, 0.0, 0.0, 0.0, 3.0, 4.0, 0.0, 1.0, 0.0, 0.0 };
  const double lambda = Smallest(f, true);
  AV_CHECK(lambda > 0.0 && lambda < 1.0);
  const av::MetricScaling s = av::ScaleMetricForEmbedding(Mesh(2, 2), f);
  AV_CHECK_NEAR(s.Scale, 1.0 / lambda, 1e-12);
  AV_CHECK_NEAR(Smallest(f, true), 1.0, 1e-12);
  AV_CHECK(f.Values[2] == 0.0 && f.Values[8] == 0.0);
}

void CheckSurfaces()
{
  // Rank-2 tangent metrics (zero along the normal), tangent eigenvalue 0.5 < 1: left unscaled.
  av::MetricField f = Field({ { 0.0, 0.5, 4.0 }, { 0.0, 1.0, 2.0 } });
  const av::MetricField kept = f;
  const av::MetricScaling s = av::ScaleMetricForEmbedding(Mesh(3, 2), f, false);
  AV_CHECK(s.Scale == 1.0);
  AV_CHECK(f.Values == kept.Values);
  AV_CHECK(s.SmallestEigenvalue < 1e-12);
}

void CheckErrors()
{
  const av::SimplexMesh volume = Mesh(3, 3);
  av::MetricField nearlySingular = Field({ { 1.0, 2.0, 3.0 }, { -1e-3, 1.0, 1.0 } });
  AV_CHECK_THROWS(av::ScaleMetricForEmbedding(volume, nearlySingular));
  av::MetricField indefinite = Field({ { -1.0, 2.0, 3.0 } });
  AV_CHECK_THROWS(av::ScaleMetricForEmbedding(volume, indefinite));
  // Needs scaling but scaling is not allowed: an error, and the field is left alone.
  av::MetricField small = Field({ { 0.5, 2.0, 3.0 } });
  const av::MetricField kept = small;
  AV_CHECK_THROWS(av::ScaleMetricForEmbedding(volume, small, false));
  AV_CHECK(small.Values == kept.Values);
}
} // namespace

int TestMetricScaling(int, char*[])
{
  CheckVolumes();
  CheckDomain2D();
  CheckSurfaces();
  CheckErrors();
  return AV_TEST_RESULT();
}
