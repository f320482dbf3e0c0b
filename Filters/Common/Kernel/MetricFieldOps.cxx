// SPDX-License-Identifier: BSD-3-Clause
#include "MetricFieldOps.h"

#include "MetricAlgebra.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <functional>

namespace av
{

Eigen::Matrix3d LogEuclideanMean(const double* const* metrics, const double* weights, int n)
{
  Eigen::Matrix3d logSum = Eigen::Matrix3d::Zero();
  bool rank2 = false;
  for (int i = 0; i < n; ++i)
  {
    const SymmetricEigen3 e = EigenDecompose(UnpackSymmetric(metrics[i]));
    const double top = std::max(e.Values.maxCoeff(), 1e-300);
    Eigen::Vector3d l;
    for (int k = 0; k < 3; ++k)
    {
      if (e.Values[k] <= 1e-12 * top)
      {
        rank2 = true;
        l[k] = std::log(1e-12 * top); // finite stand-in for the zero eigenvalue
      }
      else
      {
        l[k] = std::log(e.Values[k]);
      }
    }
    logSum += weights[i] * (e.Vectors * l.asDiagonal() * e.Vectors.transpose());
  }
  const SymmetricEigen3 e = EigenDecompose(logSum);
  Eigen::Vector3d v = e.Values.array().exp().matrix();
  if (rank2)
  {
    v[0] = 0.0; // the smallest: the (averaged) normal direction of a surface metric
  }
  return e.Vectors * v.asDiagonal() * e.Vectors.transpose();
}

namespace
{
/// The inverse of a lower triangular matrix by forward substitution (fixed size: no general
/// triangular-solve kernel, no heap).
template <int D>
Eigen::Matrix<double, D, D> InverseLower(const Eigen::Matrix<double, D, D>& l)
{
  Eigen::Matrix<double, D, D> x = Eigen::Matrix<double, D, D>::Zero();
  for (int j = 0; j < D; ++j)
  {
    x(j, j) = 1.0 / l(j, j);
    for (int i = j + 1; i < D; ++i)
    {
      double s = 0.0;
      for (int k = j; k < i; ++k)
        s += l(i, k) * x(k, j);
      x(i, j) = -s / l(i, i);
    }
  }
  return x;
}

/// a ∩ b; with relTol >= 0, `changed` tells whether b exceeds a by more than relTol (when not,
/// a is returned as it is).
template <int D>
Eigen::Matrix<double, D, D> Intersect(const Eigen::Matrix<double, D, D>& a,
  const Eigen::Matrix<double, D, D>& b,
  double relTol,
  bool& changed)
{
  using Mat = Eigen::Matrix<double, D, D>;
  // Simultaneous reduction: a = L L^T, C = L^-1 b L^-T = Q diag(mu) Q^T. In the basis
  // P = L^-T Q, P^T a P = I and P^T b P = diag(mu), and the intersection is diag(max(1, mu)):
  // back, L Q diag(max(1, mu)) Q^T L^T. The closed-form eigensolver of the small symmetric C
  // (the gradation calls this per edge and sweep: the generalized solver's general kernels
  // were 3/4 of the metric preparation).
  const Eigen::LLT<Mat> llt(a);
  if (llt.info() != Eigen::Success)
  {
    // Not reachable with SPD a (callers check); kept exact for a semidefinite one.
    Eigen::GeneralizedSelfAdjointEigenSolver<Mat> ges(b, a);
    const auto mu = ges.eigenvalues();
    changed = mu.maxCoeff() > 1.0 + relTol;
    if (relTol >= 0.0 && !changed)
      return a;
    const Mat pinv = ges.eigenvectors().inverse();
    Eigen::Matrix<double, D, 1> d = mu.cwiseMax(1.0);
    const Mat m = pinv.transpose() * d.asDiagonal() * pinv;
    return 0.5 * (m + m.transpose());
  }
  const Mat l = llt.matrixL();
  const Mat x = InverseLower<D>(l);
  Mat c = x * b * x.transpose();
  c = 0.5 * (c + c.transpose());
  // b inside a to relTol (the common case in the gradation's sweeps): (1 + relTol) I - C
  // positive definite by its leading minors, no eigensolver needed.
  if (relTol >= 0.0)
  {
    const Mat e = Mat::Identity() * (1.0 + relTol) - c;
    bool inside = e(0, 0) > 0.0 && e.template topLeftCorner<2, 2>().determinant() > 0.0;
    if constexpr (D == 3)
      inside = inside && e.determinant() > 0.0;
    if (inside)
    {
      changed = false;
      return a;
    }
  }
  Eigen::SelfAdjointEigenSolver<Mat> es;
  es.computeDirect(c);
  // The closed form loses about eps x (spread of mu) in the small eigenvalues' directions:
  // beyond a spread of 1e4, the iterative solver (1e-8 against 1e-13 at a spread of 1e9).
  if (!(es.eigenvalues().maxCoeff() <= 1e4 * es.eigenvalues().minCoeff()))
    es.compute(c);
  const Eigen::Matrix<double, D, 1> mu = es.eigenvalues();
  changed = mu.maxCoeff() > 1.0 + relTol;
  if (relTol >= 0.0 && !changed)
    return a;
  const Mat lq = l * es.eigenvectors();
  const Mat m = lq * mu.cwiseMax(1.0).asDiagonal() * lq.transpose();
  return 0.5 * (m + m.transpose());
}

template <int D>
Eigen::Matrix<double, D, D> Intersect(
  const Eigen::Matrix<double, D, D>& a, const Eigen::Matrix<double, D, D>& b)
{
  bool changed = false;
  return Intersect<D>(a, b, -1.0, changed);
}
} // namespace

Eigen::Matrix3d IntersectMetrics(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b)
{
  return Intersect<3>(a, b);
}

Eigen::Matrix2d IntersectMetrics(const Eigen::Matrix2d& a, const Eigen::Matrix2d& b)
{
  return Intersect<2>(a, b);
}

bool IntersectInto(Eigen::Matrix3d& a, const Eigen::Matrix3d& b, double relTol)
{
  bool changed = false;
  const Eigen::Matrix3d m = Intersect<3>(a, b, relTol, changed);
  if (changed)
    a = m;
  return changed;
}

bool IntersectInto(Eigen::Matrix2d& a, const Eigen::Matrix2d& b, double relTol)
{
  bool changed = false;
  const Eigen::Matrix2d m = Intersect<2>(a, b, relTol, changed);
  if (changed)
    a = m;
  return changed;
}

double MetricEdgeLength(
  const double* ma6, const double* mb6, const double* a, const double* b, int ambientDim)
{
  const Eigen::Matrix3d q =
    0.5 * (SymmetricSqrt(UnpackSymmetric(ma6)) + SymmetricSqrt(UnpackSymmetric(mb6)));
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  for (int k = 0; k < ambientDim; ++k)
    d[k] = b[k] - a[k];
  return (q * d).norm();
}

double MetricCellMeasure(const SimplexMesh& mesh, const MetricField& metric, std::size_t cell)
{
  const std::int32_t* v = mesh.Cell(cell);
  const int k = mesh.SimplexDim, m = mesh.AmbientDim;
  Eigen::Matrix3d mean = Eigen::Matrix3d::Zero();
  for (int i = 0; i <= k; ++i)
    mean += UnpackSymmetric(metric.At(static_cast<std::size_t>(v[i])));
  mean /= (k + 1);
  Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 3> e(3, k);
  e.setZero();
  for (int j = 0; j < k; ++j)
    for (int d = 0; d < m; ++d)
      e(d, j) = mesh.Point(static_cast<std::size_t>(v[j + 1]))[d] -
        mesh.Point(static_cast<std::size_t>(v[0]))[d];
  const Eigen::MatrixXd g = e.transpose() * mean * e;
  return std::sqrt(std::max(0.0, g.determinant())) / (k == 3 ? 6.0 : 2.0);
}

double MetricComplexity(const SimplexMesh& mesh, const MetricField& metric)
{
  const std::size_t nc = mesh.NumCells();
  return tbb::parallel_deterministic_reduce(
    tbb::blocked_range<std::size_t>(0, nc, 4096), 0.0,
    [&](const tbb::blocked_range<std::size_t>& r, double sum)
    {
      for (std::size_t c = r.begin(); c != r.end(); ++c)
        sum += MetricCellMeasure(mesh, metric, c);
      return sum;
    },
    std::plus<double>());
}

double UnitVertexMeasure(int simplexDim)
{
  return simplexDim == 3 ? 1.0 / std::sqrt(2.0) : std::sqrt(3.0) / 2.0;
}

} // namespace av
