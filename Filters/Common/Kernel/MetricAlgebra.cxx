// SPDX-License-Identifier: BSD-3-Clause
#include "MetricAlgebra.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace av
{

Eigen::Matrix3d UnpackSymmetric(const double* v)
{
  Eigen::Matrix3d m;
  m << v[0], v[3], v[5], //
    v[3], v[1], v[4],    //
    v[5], v[4], v[2];
  return m;
}

Eigen::Matrix2d UnpackSymmetric2(const double* v)
{
  Eigen::Matrix2d m;
  m << v[0], v[3], v[3], v[1];
  return m;
}

void PackSymmetric(const Eigen::Matrix3d& m, double* v)
{
  v[0] = m(0, 0);
  v[1] = m(1, 1);
  v[2] = m(2, 2);
  v[3] = 0.5 * (m(0, 1) + m(1, 0));
  v[4] = 0.5 * (m(1, 2) + m(2, 1));
  v[5] = 0.5 * (m(0, 2) + m(2, 0));
}

void PackSymmetric2(const Eigen::Matrix2d& m, double* v)
{
  v[0] = m(0, 0);
  v[1] = m(1, 1);
  v[2] = 0.0;
  v[3] = 0.5 * (m(0, 1) + m(1, 0));
  v[4] = 0.0;
  v[5] = 0.0;
}

SymmetricEigen3 EigenDecompose(const Eigen::Matrix3d& m)
{
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(0.5 * (m + m.transpose()));
  SymmetricEigen3 r;
  r.Values = es.eigenvalues();
  r.Vectors = es.eigenvectors();
  if (r.Vectors.determinant() < 0.0)
  {
    r.Vectors.col(2) = -r.Vectors.col(2);
  }
  return r;
}

SymmetricEigen2 EigenDecompose(const Eigen::Matrix2d& m)
{
  const double a = m(0, 0), c = m(1, 1), b = 0.5 * (m(0, 1) + m(1, 0));
  const double mean = 0.5 * (a + c);
  const double d = std::hypot(0.5 * (a - c), b);
  const double theta = 0.5 * std::atan2(2.0 * b, a - c); // direction of the largest eigenvalue
  SymmetricEigen2 r;
  r.Values << mean - d, mean + d;
  const double cs = std::cos(theta), sn = std::sin(theta);
  r.Vectors << -sn, cs, //
    cs, sn;
  return r;
}

bool AllFinite(const double* v, int n)
{
  for (int i = 0; i < n; ++i)
  {
    if (!std::isfinite(v[i]))
    {
      return false;
    }
  }
  return true;
}

bool IsPositiveDefinite(const Eigen::Matrix3d& m, double relTol)
{
  if (!AllFinite(m.data(), 9))
  {
    return false;
  }
  const Eigen::Vector3d ev = EigenDecompose(m).Values;
  const double scale = ev.cwiseAbs().maxCoeff();
  return ev(0) > 0.0 && ev(0) > relTol * scale;
}

bool IsPositiveDefinite(const Eigen::Matrix2d& m, double relTol)
{
  if (!AllFinite(m.data(), 4))
  {
    return false;
  }
  const Eigen::Vector2d ev = EigenDecompose(m).Values;
  const double scale = ev.cwiseAbs().maxCoeff();
  return ev(0) > 0.0 && ev(0) > relTol * scale;
}

bool IsPositiveSemiDefinite(const Eigen::Matrix3d& m, double relTol)
{
  if (!AllFinite(m.data(), 9))
  {
    return false;
  }
  const Eigen::Vector3d ev = EigenDecompose(m).Values;
  const double scale = ev.cwiseAbs().maxCoeff();
  return scale > 0.0 && ev(0) >= -relTol * scale;
}

Eigen::Matrix3d SymmetricSqrt(const Eigen::Matrix3d& m)
{
  const SymmetricEigen3 e = EigenDecompose(m);
  const Eigen::Vector3d s = e.Values.cwiseMax(0.0).cwiseSqrt();
  return e.Vectors * s.asDiagonal() * e.Vectors.transpose();
}

Eigen::Matrix2d SymmetricSqrt(const Eigen::Matrix2d& m)
{
  const SymmetricEigen2 e = EigenDecompose(m);
  const Eigen::Vector2d s = e.Values.cwiseMax(0.0).cwiseSqrt();
  return e.Vectors * s.asDiagonal() * e.Vectors.transpose();
}

Eigen::Matrix3d MetricFromFrame(const Eigen::Matrix3d& r, const Eigen::Vector3d& s)
{
  return r * s.cwiseAbs2().asDiagonal() * r.transpose();
}

double StretchRatio(const Eigen::Matrix3d& m)
{
  const Eigen::Vector3d ev = EigenDecompose(m).Values;
  if (!(ev(0) > 0.0))
  {
    return std::numeric_limits<double>::infinity();
  }
  return std::sqrt(ev(2) / ev(0));
}

double StretchRatio(const Eigen::Matrix2d& m)
{
  const Eigen::Vector2d ev = EigenDecompose(m).Values;
  if (!(ev(0) > 0.0))
  {
    return std::numeric_limits<double>::infinity();
  }
  return std::sqrt(ev(1) / ev(0));
}

double SurfaceStretchRatio(const Eigen::Matrix3d& m)
{
  const Eigen::Vector3d ev = EigenDecompose(m).Values;
  if (!(ev(1) > 0.0))
  {
    return std::numeric_limits<double>::infinity();
  }
  return std::sqrt(ev(2) / ev(1));
}

Eigen::Vector3d SurfaceMetricNormal(const Eigen::Matrix3d& m)
{
  const SymmetricEigen3 e = EigenDecompose(m);
  if (!(e.Values(2) > 0.0) || std::abs(e.Values(0)) > 1e-6 * e.Values(2))
  {
    return Eigen::Vector3d::Zero();
  }
  return e.Vectors.col(0).normalized();
}

Eigen::Matrix3d MoveSurfaceMetric(
  const Eigen::Matrix3d& s, const Eigen::Vector3d& from, const Eigen::Vector3d& to)
{
  const double c0 = from.dot(to);
  const Eigen::Vector3d b = c0 < 0.0 ? Eigen::Vector3d(-to) : to;
  const double c = std::abs(c0);
  if (from.squaredNorm() == 0.0 || c >= 1.0 - 1e-15)
  {
    return s;
  }
  // Rodrigues with v = from x b, |v| = sin: R = I + [v]x + [v]x^2 / (1 + cos).
  const Eigen::Vector3d v = from.cross(b);
  Eigen::Matrix3d vx;
  vx << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  const Eigen::Matrix3d r = Eigen::Matrix3d::Identity() + vx + vx * vx / (1.0 + c);
  return r * s * r.transpose();
}

double SurfaceEdgeMetricLength2(const Eigen::Vector3d& d,
  const Eigen::Matrix3d& rootA,
  const Eigen::Vector3d& normalA,
  const Eigen::Matrix3d& rootB,
  const Eigen::Vector3d& normalB)
{
  const double dn = d.norm();
  if (!(dn > 0.0))
  {
    return 0.0;
  }
  const Eigen::Vector3d t = d / dn;
  auto moved = [&t](const Eigen::Matrix3d& root, const Eigen::Vector3d& n) -> Eigen::Matrix3d
  {
    Eigen::Vector3d to = n - n.dot(t) * t;
    if (to.squaredNorm() < 1e-24)
    {
      to = t.unitOrthogonal(); // the edge along the normal: any plane through it
    }
    return MoveSurfaceMetric(root, n, to.normalized());
  };
  return (0.5 * (moved(rootA, normalA) + moved(rootB, normalB)) * d).squaredNorm();
}

std::vector<Eigen::Vector3d> SurfaceMetricNormals(const MetricField& field)
{
  std::vector<Eigen::Vector3d> n(field.NumPoints());
  tbb::parallel_for(std::size_t(0), n.size(),
    [&](std::size_t i) { n[i] = SurfaceMetricNormal(UnpackSymmetric(field.At(i))); });
  return n;
}

void EigenvalueRange(const MetricField& field, bool dim2, double& minEig, double& maxEig)
{
  minEig = std::numeric_limits<double>::infinity();
  maxEig = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < field.NumPoints(); ++i)
  {
    if (dim2)
    {
      const Eigen::Vector2d ev = EigenDecompose(UnpackSymmetric2(field.At(i))).Values;
      minEig = std::min(minEig, ev(0));
      maxEig = std::max(maxEig, ev(1));
    }
    else
    {
      const Eigen::Vector3d ev = EigenDecompose(UnpackSymmetric(field.At(i))).Values;
      minEig = std::min(minEig, ev(0));
      maxEig = std::max(maxEig, ev(2));
    }
  }
}

} // namespace av
