// SPDX-License-Identifier: BSD-3-Clause
// TangentTensorToMetric on a sphere with one constant 3D tensor diag(4, 1, 100): at the poles
// the tangent block is diag(4, 1) (stretch 4, where the plain 3D conversion says 25, capped
// 100), on the equator at +x it is diag(1, 100) (capped at 25); every metric is zero along its
// normal. Errors: smoothing, a zero normal.
#include "AnisoTestChecks.h"
#include "MetricAlgebra.h"
#include "SurfaceCurvatureMetric.h"
#include "SurfaceGenerators.h"
#include "TensorToMetric.h"

#include <Eigen/Dense>

#include <cmath>
#include <vector>

int TestTangentTensorToMetric(int, char*[])
{
  const av::SimplexMesh sphere = av::MakeIcosphere(1.0, 4);
  const std::vector<double> normals = av::SurfaceVertexNormals(sphere);
  const std::size_t n = sphere.NumPoints();
  AV_CHECK(normals.size() == 3 * n);
  std::vector<double> tensors(6 * n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const double t[6] = { 4, 1, 100, 0, 0, 0 };
    std::copy(t, t + 6, tensors.data() + 6 * i);
    // Max's normals of an icosphere are its radial directions.
    AV_CHECK(
      Eigen::Vector3d(normals.data() + 3 * i).dot(Eigen::Vector3d(sphere.Point(i))) > 0.9999);
  }
  av::TensorToMetricOptions o; // stretch = |eigenvalue|, cap 25, global scale on
  const av::TensorToMetricResult r =
    av::TangentTensorToMetric(tensors.data(), n, 6, normals.data(), o);
  const av::TensorToMetricResult plain = av::TensorToMetric(tensors.data(), n, 6, o);
  int poles = 0, equator = 0;
  double worstNormal = 0.0;
  for (std::size_t i = 0; i < n; ++i)
  {
    const Eigen::Vector3d nv(normals.data() + 3 * i);
    const Eigen::Matrix3d M = av::UnpackSymmetric(r.Metric.At(i));
    worstNormal = std::max(worstNormal, (M * nv).norm() / M.norm());
    if (std::abs(nv[2]) > 0.99999)
    {
      ++poles;
      AV_CHECK_NEAR(r.StretchRatio[i], 4.0, 1e-3);
      AV_CHECK_NEAR(plain.StretchRatio[i], 25.0, 1e-9);
    }
    if (nv[0] > 0.99999)
    {
      ++equator;
      AV_CHECK_NEAR(r.StretchRatio[i], 25.0, 1e-6);
    }
  }
  AV_CHECK(poles == 2 && equator == 1);
  AV_CHECK_MSG(worstNormal < 1e-12, "metric along the normal: " << worstNormal);
  // The smallest tangent eigenvalue is 1 after the global scale (the normal's 0 is not counted).
  AV_CHECK_NEAR(r.MinEigenvalue, 1.0, 1e-9);

  o.SmoothingIterations = 2;
  AV_CHECK_THROWS(av::TangentTensorToMetric(tensors.data(), n, 6, normals.data(), o));
  o.SmoothingIterations = 0;
  std::vector<double> bad = normals;
  bad[0] = bad[1] = bad[2] = 0.0;
  AV_CHECK_THROWS(av::TangentTensorToMetric(tensors.data(), n, 6, bad.data(), o));
  AV_CHECK_THROWS(av::TangentTensorToMetric(tensors.data(), n, 7, normals.data(), o));
  return AV_TEST_RESULT();
}
