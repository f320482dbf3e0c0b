// SPDX-License-Identifier: BSD-3-Clause
// MetricFieldOps on known answers: log-Euclidean means are geometric and SPD, intersections
// contain both metrics and keep the smaller size per direction, the complexity of a uniform
// metric on a box is its metric volume; surface metrics moved into another plane keep their
// tangent lengths.
#include "AnisoTestChecks.h"
#include "MetricAlgebra.h"
#include "MetricFieldOps.h"
#include "StructuredMeshes.h"

#include <Eigen/Dense>

#include <cmath>
#include <random>

namespace
{
Eigen::Matrix3d RandomSpd(std::mt19937& rng)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Matrix3d a;
  for (int i = 0; i < 9; ++i)
    a(i / 3, i % 3) = u(rng);
  return a * a.transpose() + 0.05 * Eigen::Matrix3d::Identity();
}

/// A random metric with eigenvalues spread over [1, stretch^2] in random directions.
Eigen::Matrix3d RandomStretched(std::mt19937& rng, double stretch)
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Eigen::Matrix3d q = Eigen::HouseholderQR<Eigen::Matrix3d>(RandomSpd(rng)).householderQ();
  Eigen::Vector3d l;
  for (int k = 0; k < 3; ++k)
    l[k] = std::pow(stretch, 2.0 * u(rng));
  return 1e3 * u(rng) * q * l.asDiagonal() * q.transpose();
}

/// The intersection by its definition, with Eigen's generalized solver: P^T a P = I,
/// P^T b P = diag(mu), the result P^-T diag(max(1, mu)) P^-1.
Eigen::Matrix3d ReferenceIntersection(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b)
{
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix3d> ges(b, a);
  const Eigen::Matrix3d pinv = ges.eigenvectors().inverse();
  return pinv.transpose() * ges.eigenvalues().cwiseMax(1.0).asDiagonal() * pinv;
}

void CheckLogEuclideanMean()
{
  double a[6], b[6];
  av::PackSymmetric(Eigen::Matrix3d::Identity(), a);
  av::PackSymmetric(4.0 * Eigen::Matrix3d::Identity(), b);
  const double* ms[2] = { a, b };
  const double w[2] = { 0.5, 0.5 };
  const Eigen::Matrix3d m = av::LogEuclideanMean(ms, w, 2);
  AV_CHECK((m - 2.0 * Eigen::Matrix3d::Identity()).norm() < 1e-12);
  std::mt19937 rng(3);
  for (int t = 0; t < 50; ++t)
  {
    double p[6], q[6];
    av::PackSymmetric(RandomSpd(rng), p);
    av::PackSymmetric(RandomSpd(rng), q);
    const double* pq[2] = { p, q };
    const double wt[2] = { 0.3, 0.7 };
    AV_CHECK(av::IsPositiveDefinite(av::LogEuclideanMean(pq, wt, 2)));
    const double one[1] = { 1.0 };
    AV_CHECK((av::LogEuclideanMean(pq, one, 1) - av::UnpackSymmetric(p)).norm() <
      1e-9 * av::UnpackSymmetric(p).norm());
  }
  // Rank-2 surface metrics stay rank 2.
  double s[6];
  av::PackSymmetric(Eigen::Vector3d(1.0, 9.0, 0.0).asDiagonal(), s);
  const double* ss[2] = { s, s };
  const Eigen::Matrix3d r = av::LogEuclideanMean(ss, w, 2);
  AV_CHECK(std::abs(r(2, 2)) < 1e-12 && std::abs(r(1, 1) - 9.0) < 1e-9);
}

void CheckIntersection()
{
  std::mt19937 rng(5);
  for (int t = 0; t < 100; ++t)
  {
    const Eigen::Matrix3d a = RandomSpd(rng), b = RandomSpd(rng);
    const Eigen::Matrix3d m = av::IntersectMetrics(a, b);
    // m >= a and m >= b (Loewner): the unit ball of m is inside both.
    AV_CHECK(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m - a).eigenvalues().minCoeff() >
      -1e-9 * m.norm());
    AV_CHECK(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m - b).eigenvalues().minCoeff() >
      -1e-9 * m.norm());
    // Intersecting with itself, or with a smaller metric, changes nothing.
    AV_CHECK((av::IntersectMetrics(a, a) - a).norm() < 1e-9 * a.norm());
    AV_CHECK((av::IntersectMetrics(a, 0.5 * a) - a).norm() < 1e-9 * a.norm());
  }
  // Against the definition, with stretches up to 1000 (the gradation's metrics reach 25 and
  // more), and IntersectInto's change flag: set exactly when b pokes out of a.
  for (int t = 0; t < 2000; ++t)
  {
    const Eigen::Matrix3d a = RandomStretched(rng, 1000.0), b = RandomStretched(rng, 1000.0);
    const Eigen::Matrix3d ref = ReferenceIntersection(a, b);
    AV_CHECK((av::IntersectMetrics(a, b) - ref).norm() < 1e-9 * ref.norm());
    Eigen::Matrix3d into = a;
    const double mu =
      Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix3d>(b, a).eigenvalues().maxCoeff();
    const bool changed = av::IntersectInto(into, b, 1e-6);
    AV_CHECK(changed == (mu > 1.0 + 1e-6) || std::abs(mu - 1.0 - 1e-6) < 1e-9);
    AV_CHECK(changed ? (into - ref).norm() < 1e-9 * ref.norm() : into == a);
  }
  // Axis-aligned: the larger eigenvalue in each direction.
  const Eigen::Matrix2d x = Eigen::Vector2d(4.0, 1.0).asDiagonal();
  const Eigen::Matrix2d y = Eigen::Vector2d(1.0, 9.0).asDiagonal();
  AV_CHECK((av::IntersectMetrics(x, y) - Eigen::Matrix2d(Eigen::Vector2d(4.0, 9.0).asDiagonal()))
             .norm() < 1e-12);
}

void CheckComplexity()
{
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 2, 1, 1 };
  const av::SimplexMesh m = av::MakeKuhnTetGrid(5, 4, 3, lo, hi);
  av::MetricField f;
  const Eigen::Matrix3d metric = Eigen::Vector3d(9.0, 4.0, 1.0).asDiagonal();
  for (std::size_t i = 0; i < m.NumPoints(); ++i)
  {
    double v[6];
    av::PackSymmetric(metric, v);
    f.Values.insert(f.Values.end(), v, v + 6);
  }
  // sqrt(det M) x volume = 6 x 2.
  AV_CHECK_NEAR(av::MetricComplexity(m, f), 12.0, 1e-9);
  const double a[3] = { 0, 0, 0 }, b[3] = { 1, 1, 0 };
  AV_CHECK_NEAR(av::MetricEdgeLength(f.At(0), f.At(1), a, b, 3), std::sqrt(13.0), 1e-12);
  AV_CHECK_NEAR(av::UnitVertexMeasure(2), std::sqrt(3.0) / 2.0, 1e-15);
}
} // namespace

/// MoveSurfaceMetric / SurfaceMetricNormal / SurfaceEdgeMetricLength2 on known answers.
void CheckSurfaceMetricMove()
{
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial)
  {
    // A rank-2 metric with stretch 3 in the plane normal to a random n.
    const Eigen::Matrix3d q = Eigen::HouseholderQR<Eigen::Matrix3d>(RandomSpd(rng)).householderQ();
    const Eigen::Vector3d n = q.col(2), t1 = q.col(0), t2 = q.col(1);
    const Eigen::Matrix3d m = t1 * t1.transpose() + 9.0 * t2 * t2.transpose();
    const Eigen::Vector3d found = av::SurfaceMetricNormal(m);
    AV_CHECK(std::abs(std::abs(found.dot(n)) - 1.0) < 1e-12);
    const Eigen::Vector3d to = q * Eigen::Vector3d(RandomSpd(rng).col(0)).normalized();
    const Eigen::Matrix3d moved = av::MoveSurfaceMetric(m, found, to);
    // Null along `to`, the same eigenvalues, and the direction normal to both normals (the
    // rotation's axis) measured as before.
    AV_CHECK((moved * to).norm() < 1e-12 * m.norm());
    const Eigen::Vector3d ev0 = av::EigenDecompose(m).Values, ev1 = av::EigenDecompose(moved).Values;
    AV_CHECK((ev0 - ev1).norm() < 1e-12 * m.norm());
    const Eigen::Vector3d axis = n.cross(to);
    if (axis.norm() > 1e-6)
    {
      const Eigen::Vector3d u = axis.normalized();
      AV_CHECK(std::abs(u.dot(moved * u) - u.dot(m * u)) < 1e-12 * m.norm());
    }
    // Either sign of the target, and a zero source, leave it as it is.
    AV_CHECK(av::MoveSurfaceMetric(m, found, -found) == m);
    AV_CHECK(av::MoveSurfaceMetric(m, Eigen::Vector3d::Zero(), to) == m);
  }
  AV_CHECK(av::SurfaceMetricNormal(Eigen::Matrix3d::Identity()).norm() == 0.0);

  // Identity tangent metric normal to z: an edge along z (a rim) has its full length, not 0; an
  // edge in the plane keeps the plain §5.1 length; a 45 deg edge its full length (plain: 1/sqrt2).
  const Eigen::Matrix3d root = Eigen::Vector3d(1, 1, 0).asDiagonal();
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  auto len = [&](const Eigen::Vector3d& d)
  { return std::sqrt(av::SurfaceEdgeMetricLength2(d, root, z, root, z)); };
  AV_CHECK(std::abs(len(Eigen::Vector3d(0, 0, 0.3)) - 0.3) < 1e-12);
  AV_CHECK(std::abs(len(Eigen::Vector3d(0.4, 0, 0)) - 0.4) < 1e-15);
  AV_CHECK(std::abs(len(Eigen::Vector3d(1, 0, 1)) - std::sqrt(2.0)) < 1e-12);
  AV_CHECK(std::abs((root * Eigen::Vector3d(1, 0, 1)).norm() - 1.0) < 1e-15);
}

int TestMetricFieldOps(int, char*[])
{
  CheckSurfaceMetricMove();
  CheckLogEuclideanMean();
  CheckIntersection();
  CheckComplexity();
  return AV_TEST_RESULT();
}
