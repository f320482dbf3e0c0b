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
/// a ∩ b; with relTol >= 0, `changed` tells whether b exceeds a by more than relTol (when not,
/// a is returned as it is).
template <int D>
Eigen::Matrix<double, D, D> Intersect(const Eigen::Matrix<double, D, D>& a,
  const Eigen::Matrix<double, D, D>& b,
  double relTol,
  bool& changed)
{
  using Mat = Eigen::Matrix<double, D, D>;
  // Generalized eigenvectors P of (b, a): P^T a P = I, P^T b P = diag(mu). In that basis the
  // intersection is diag(max(1, mu)); back: P^-T diag P^-1.
  Eigen::GeneralizedSelfAdjointEigenSolver<Mat> ges(b, a);
  const auto mu = ges.eigenvalues();
  changed = mu.maxCoeff() > 1.0 + relTol;
  if (relTol >= 0.0 && !changed)
    return a;
  const Mat p = ges.eigenvectors();
  const Mat pinv = p.inverse();
  Eigen::Matrix<double, D, 1> d;
  for (int k = 0; k < D; ++k)
    d[k] = std::max(1.0, mu[k]);
  const Mat m = pinv.transpose() * d.asDiagonal() * pinv;
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
