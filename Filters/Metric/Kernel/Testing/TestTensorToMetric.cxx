// SPDX-License-Identifier: BSD-3-Clause
// TensorToMetric: exact metrics for known tensors in every mode, anisotropy cap, global scale,
// symmetrization report, 2D, log-Euclidean smoothing, and error handling.
#include "MetricAlgebra.h"
#include "TensorToMetric.h"
#include "AnisoTestChecks.h"

#include <Eigen/Dense>

#include <cmath>
#include <random>
#include <vector>

namespace
{
Eigen::Matrix3d Rotation(double a, double b, double c)
{
  return (Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()) *
    Eigen::AngleAxisd(b, Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(c, Eigen::Vector3d::UnitX()))
    .toRotationMatrix();
}

std::vector<double> Full9(const Eigen::Matrix3d& t)
{
  std::vector<double> v(9);
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      v[3 * i + j] = t(i, j);
    }
  }
  return v;
}

double MaxDiff(const Eigen::Matrix3d& a, const double* packed)
{
  return (a - av::UnpackSymmetric(packed)).cwiseAbs().maxCoeff();
}

// Eq. 20 with |lambda|: M = R diag(s^2) R^T.
void CheckEq20LambdaMR()
{
  const Eigen::Matrix3d R = Rotation(0.3, -0.7, 1.1);
  const Eigen::Matrix3d T = R * Eigen::Vector3d(2.0, -0.5, 0.1).asDiagonal() * R.transpose();
  const std::vector<double> t9 = Full9(T);
  av::TensorToMetricOptions o;
  o.MaximumAnisotropy = 0.0;
  o.ApplyGlobalScale = false;
  const auto r = av::TensorToMetric(t9.data(), 1, 9, o);
  const Eigen::Matrix3d expect =
    R * Eigen::Vector3d(4.0, 0.25, 0.01).asDiagonal() * R.transpose();
  AV_CHECK(MaxDiff(expect, r.Metric.At(0)) < 1e-12);
  AV_CHECK(r.NumNegative == 1 && r.NumClamped == 0 && r.NumCapped == 0);
  AV_CHECK_NEAR(r.StretchRatio[0], 20.0, 1e-9);
  AV_CHECK_NEAR(r.GlobalScale, 1.0, 0.0);
  AV_CHECK_NEAR(r.MaxAsymmetry, 0.0, 1e-15);

  // Global scale: smallest eigenvalue 0.01 -> c = 100, smallest becomes 1.
  o.ApplyGlobalScale = true;
  const auto s = av::TensorToMetric(t9.data(), 1, 9, o);
  AV_CHECK_NEAR(s.GlobalScale, 100.0, 1e-9);
  AV_CHECK(MaxDiff(100.0 * expect, s.Metric.At(0)) < 1e-9);
  AV_CHECK_NEAR(s.MinEigenvalue, 1.0, 1e-12);
  AV_CHECK_NEAR(s.StretchRatio[0], 20.0, 1e-9); // scaling keeps the ratio

  // 6-component input gives the same.
  double t6[6];
  av::PackSymmetric(T, t6);
  const auto p = av::TensorToMetric(t6, 1, 6, o);
  AV_CHECK(MaxDiff(av::UnpackSymmetric(s.Metric.At(0)), p.Metric.At(0)) < 1e-9);
}

// Anisotropy cap raises the small stretches: s = (2, 0.5, 0.1) -> (2, 0.5, 0.4).
void CheckAnisotropyCapRaisesSmallStretches()
{
  const Eigen::Matrix3d R = Rotation(0.3, -0.7, 1.1);
  const Eigen::Matrix3d T = R * Eigen::Vector3d(2.0, -0.5, 0.1).asDiagonal() * R.transpose();
  const std::vector<double> t9 = Full9(T);
  av::TensorToMetricOptions o;
  o.MaximumAnisotropy = 5.0;
  o.ApplyGlobalScale = false;
  const auto r = av::TensorToMetric(t9.data(), 1, 9, o);
  const Eigen::Matrix3d expect =
    R * Eigen::Vector3d(4.0, 0.25, 0.16).asDiagonal() * R.transpose();
  AV_CHECK(MaxDiff(expect, r.Metric.At(0)) < 1e-12);
  AV_CHECK(r.NumCapped == 1);
  AV_CHECK_NEAR(r.MaxStretch, 5.0, 1e-9);
}

// Clamp: the negative eigenvalue goes to the floor 1e-3 * 2.
void CheckClampNegativeEigenvalueGoesFloor()
{
  const Eigen::Matrix3d R = Rotation(0.3, -0.7, 1.1);
  const Eigen::Matrix3d T = R * Eigen::Vector3d(2.0, -0.5, 0.1).asDiagonal() * R.transpose();
  const std::vector<double> t9 = Full9(T);
  av::TensorToMetricOptions o;
  o.Eigenvalues = av::EigenvalueHandling::Clamp;
  o.MaximumAnisotropy = 0.0;
  o.ApplyGlobalScale = false;
  const auto r = av::TensorToMetric(t9.data(), 1, 9, o);
  const Eigen::Matrix3d expect =
    R * Eigen::Vector3d(4.0, 4e-6, 0.01).asDiagonal() * R.transpose();
  AV_CHECK(MaxDiff(expect, r.Metric.At(0)) < 1e-12);
  AV_CHECK(r.NumClamped == 1 && r.NumNegative == 1);
}

// Tensor used as a metric directly; non-symmetric input is symmetrized and reported.
void CheckTensorUsedMetricDirectlyNon()
{
  const Eigen::Matrix3d R = Rotation(0.3, -0.7, 1.1);
  const Eigen::Matrix3d S = R * Eigen::Vector3d(4.0, 1.0, 0.25).asDiagonal() * R.transpose();
  Eigen::Matrix3d K;
  K << 0, 0.1, -0.2, -0.1, 0, 0.3, 0.2, -0.3, 0;
  const std::vector<double> t = Full9(S + K);
  av::TensorToMetricOptions o;
  o.Interpretation = av::TensorInterpretation::TensorAsMetric;
  const auto r = av::TensorToMetric(t.data(), 1, 9, o);
  AV_CHECK_NEAR(r.GlobalScale, 4.0, 1e-9);
  AV_CHECK(MaxDiff(4.0 * S, r.Metric.At(0)) < 1e-9);
  AV_CHECK_NEAR(r.MaxAsymmetry, K.norm() / (S + K).norm(), 1e-12);
  AV_CHECK_NEAR(r.StretchRatio[0], 4.0, 1e-9);
}

// 2D: only XX, YY, XY are read (ZZ may even be NaN); ZZ, YZ, XZ are written as 0.
void CheckDOnlyXXYYXY()
{
  const double t6[6] = { 3.0, 1.0, std::nan(""), 1.0, std::nan(""), std::nan("") };
  av::TensorToMetricOptions o;
  o.Dimension = 2;
  o.ApplyGlobalScale = false;
  const auto r = av::TensorToMetric(t6, 1, 6, o);
  Eigen::Matrix2d m;
  m << 3, 1, 1, 1;
  const Eigen::Matrix2d expect = m * m; // eigenvalues squared, same eigenvectors
  const double* out = r.Metric.At(0);
  AV_CHECK_NEAR(out[0], expect(0, 0), 1e-12);
  AV_CHECK_NEAR(out[1], expect(1, 1), 1e-12);
  AV_CHECK_NEAR(out[3], expect(0, 1), 1e-12);
  AV_CHECK(out[2] == 0.0 && out[4] == 0.0 && out[5] == 0.0);
}

// Log-Euclidean smoothing: one iteration on an edge gives the geometric mean, not the
// arithmetic one, and rotates the principal directions consistently.
void CheckLogEuclideanSmoothingOneIteration()
{
  const double t6[12] = { 4, 1, 1, 0, 0, 0, /**/ 1, 4, 1, 0, 0, 0 };
  av::TensorToMetricOptions o;
  o.Interpretation = av::TensorInterpretation::TensorAsMetric;
  o.SmoothingIterations = 1;
  const auto r = av::TensorToMetric(t6, 2, 6, o, { 0, 1 });
  for (int i = 0; i < 2; ++i)
  {
    AV_CHECK(MaxDiff(Eigen::Vector3d(2, 2, 1).asDiagonal().toDenseMatrix(), r.Metric.At(i)) <
      1e-12);
  }
  // A constant field is a fixed point; an isolated outlier is pulled to its neighbors.
  std::vector<double> chain;
  for (int i = 0; i < 20; ++i)
  {
    const double s = (i == 10) ? 9.0 : 1.0;
    chain.insert(chain.end(), { s, 1, 1, 0, 0, 0 });
  }
  std::vector<std::int32_t> edges;
  for (int i = 0; i + 1 < 20; ++i)
  {
    edges.insert(edges.end(), { i, i + 1 });
  }
  o.SmoothingIterations = 5;
  const auto c = av::TensorToMetric(chain.data(), 20, 6, o, edges);
  AV_CHECK(c.Metric.At(0)[0] < 1.0 + 1e-12 && c.Metric.At(0)[1] == c.Metric.At(0)[0]);
  AV_CHECK(c.Metric.At(10)[0] < 3.0 && c.Metric.At(10)[0] > 1.2);
  AV_CHECK(c.Metric.At(9)[0] > 1.1);
  double logSum = 0.0; // the averaging preserves the mean of log(M) on a chain only roughly;
  for (int i = 0; i < 20; ++i) // check it stays within the input range instead
  {
    logSum += std::log(c.Metric.At(i)[0]);
    AV_CHECK(c.Metric.At(i)[0] >= 1.0 - 1e-12 && c.Metric.At(i)[0] <= 9.0);
  }
  AV_CHECK(logSum > 0.0);
}

// Random field, threaded path: every output SPD, min eigenvalue 1, cap respected.
void CheckRandomFieldThreadedPathEvery()
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  const std::size_t n = 20000;
  std::vector<double> t(9 * n);
  for (double& v : t)
  {
    v = u(rng);
  }
  av::TensorToMetricOptions o;
  o.MaximumAnisotropy = 10.0;
  const auto r = av::TensorToMetric(t.data(), n, 9, o);
  AV_CHECK(r.MaxAsymmetry > 0.1);
  AV_CHECK_NEAR(r.MinEigenvalue, 1.0, 1e-9);
  AV_CHECK(r.MaxStretch <= 10.0 + 1e-9);
  AV_CHECK(r.NumNegative > n / 2 && r.NumCapped > 0);
  std::size_t bad = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    const auto e = av::EigenDecompose(av::UnpackSymmetric(r.Metric.At(i)));
    bad += !(e.Values[0] >= 1.0 - 1e-9) ||
      std::abs(std::sqrt(e.Values[2] / e.Values[0]) - r.StretchRatio[i]) > 1e-6;
  }
  AV_CHECK_MSG(bad == 0, bad << " bad metrics");
}

// Errors.
void CheckErrors()
{
  const Eigen::Matrix3d R = Rotation(0.3, -0.7, 1.1);
  const Eigen::Matrix3d T = R * Eigen::Vector3d(2.0, -0.5, 0.1).asDiagonal() * R.transpose();
  const std::vector<double> t9 = Full9(T);
  const double zero[12] = {};
  av::TensorToMetricOptions o;
  AV_CHECK_THROWS(av::TensorToMetric(zero, 2, 6, o));
  AV_CHECK_THROWS(av::TensorToMetric(zero, 0, 6, o));
  AV_CHECK_THROWS(av::TensorToMetric(t9.data(), 1, 4, o));
  std::vector<double> nan = t9;
  nan[8] = std::numeric_limits<double>::infinity();
  AV_CHECK_THROWS(av::TensorToMetric(nan.data(), 1, 9, o));
  o.SmoothingIterations = 2;
  AV_CHECK_THROWS(av::TensorToMetric(t9.data(), 1, 9, o));
  AV_CHECK_THROWS(av::TensorToMetric(t9.data(), 1, 9, o, { 0, 3 }));
  o.SmoothingIterations = 0;
  o.MinimumEigenvalue = 0.0;
  AV_CHECK_THROWS(av::TensorToMetric(t9.data(), 1, 9, o));
}

} // namespace

int TestTensorToMetric(int, char*[])
{
  CheckEq20LambdaMR();
  CheckAnisotropyCapRaisesSmallStretches();
  CheckClampNegativeEigenvalueGoesFloor();
  CheckTensorUsedMetricDirectlyNon();
  CheckDOnlyXXYYXY();
  CheckLogEuclideanSmoothingOneIteration();
  CheckRandomFieldThreadedPathEvery();
  CheckErrors();
  return AV_TEST_RESULT();
}
