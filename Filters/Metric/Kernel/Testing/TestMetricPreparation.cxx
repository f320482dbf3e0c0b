// SPDX-License-Identifier: BSD-3-Clause
// MetricPreparation: the gradation bound on every edge of a field with a 1000x size jump (2D
// and 3D), unit determinant in uniform mode, SPD output, hmin/hmax, the target complexity,
// idempotence, the deviation statistics and the input errors.
#include "AnisoTestChecks.h"
#include "MeshTopology.h"
#include "MetricAlgebra.h"
#include "MetricFieldOps.h"
#include "MetricPreparation.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <vector>

namespace
{
/// n x n squares of [0, 1]^2, two triangles each.
av::SimplexMesh Square(int n)
{
  av::SimplexMesh mesh;
  mesh.AmbientDim = 2;
  mesh.SimplexDim = 2;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
    {
      mesh.Points.push_back(static_cast<double>(i) / n);
      mesh.Points.push_back(static_cast<double>(j) / n);
    }
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      mesh.Cells.insert(mesh.Cells.end(),
        { id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j), id(i + 1, j + 1), id(i, j + 1) });
  return mesh;
}

/// n^3 cubes of [0, 1]^3, six tetrahedra each (Kuhn split, all positively oriented or not:
/// only the measures' absolute values matter here).
av::SimplexMesh Cube(int n)
{
  av::SimplexMesh mesh;
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i)
        mesh.Points.insert(mesh.Points.end(),
          { static_cast<double>(i) / n, static_cast<double>(j) / n, static_cast<double>(k) / n });
  auto id = [n](int i, int j, int k) { return (k * (n + 1) + j) * (n + 1) + i; };
  const int paths[6][3] = {
    { 0, 1, 2 }, { 0, 2, 1 }, { 1, 0, 2 }, { 1, 2, 0 }, { 2, 0, 1 }, { 2, 1, 0 }
  };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (const auto& path : paths)
        {
          int c[3] = { i, j, k };
          mesh.Cells.push_back(id(c[0], c[1], c[2]));
          for (int axis : path)
          {
            ++c[axis];
            mesh.Cells.push_back(id(c[0], c[1], c[2]));
          }
        }
  return mesh;
}

/// Anisotropic metric with size h along a frame rotating with x (stretch 5), per vertex.
av::MetricField Field(const av::SimplexMesh& mesh, double (*size)(const double*))
{
  av::MetricField f;
  f.Values.resize(6 * mesh.NumPoints());
  for (std::size_t i = 0; i < mesh.NumPoints(); ++i)
  {
    const double* x = mesh.Point(i);
    const double h = size(x);
    const Eigen::Matrix3d r =
      Eigen::AngleAxisd(2.0 * x[0] + 0.5 * x[1], Eigen::Vector3d(0.2, 0.3, 1.0).normalized())
        .toRotationMatrix();
    Eigen::Vector3d s(1.0 / h, 5.0 / h, mesh.AmbientDim == 2 ? 0.0 : 2.0 / h);
    Eigen::Matrix3d m = av::MetricFromFrame(r, s);
    if (mesh.AmbientDim == 2)
    {
      const Eigen::Matrix2d r2 = Eigen::Rotation2Dd(2.0 * x[0] + 0.5 * x[1]).toRotationMatrix();
      const Eigen::Vector2d l(1.0 / (h * h), 25.0 / (h * h));
      av::PackSymmetric2(r2 * l.asDiagonal() * r2.transpose(), f.Values.data() + 6 * i);
      continue;
    }
    av::PackSymmetric(m, f.Values.data() + 6 * i);
  }
  return f;
}

/// A 1000x size jump across x = 0.5.
double Jump(const double* x)
{
  return x[0] < 0.5 ? 1e-4 : 1e-1;
}
double Smooth(const double* x)
{
  return 0.02 * (1.0 + 3.0 * x[0] * x[0] + x[1]);
}

Eigen::Matrix3d Block(const av::MetricField& f, std::size_t i, int dim)
{
  Eigen::Matrix3d m = av::UnpackSymmetric(f.At(i));
  if (dim == 2)
    m(2, 2) = 1.0; // the unused direction: a neutral value for the 3x3 algebra below
  return m;
}

/// Largest generalized eigenvalue of (b, a): how much b exceeds a (<= 1: b <= a).
double Excess(const Eigen::Matrix3d& b, const Eigen::Matrix3d& a)
{
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix3d> ges(b, a);
  return ges.eigenvalues().maxCoeff();
}

/// Largest violation over every edge and both directions of M_q >= (1 + l_p ln beta)^-2 M_p.
double WorstGradation(const av::SimplexMesh& mesh, const av::MetricField& f, double beta, int dim)
{
  const std::vector<std::int32_t> edges = av::UniqueEdges(mesh);
  double worst = 0.0;
  for (std::size_t e = 0; e < edges.size(); e += 2)
  {
    for (int dir = 0; dir < 2; ++dir)
    {
      const auto p = static_cast<std::size_t>(edges[e + dir]);
      const auto q = static_cast<std::size_t>(edges[e + 1 - dir]);
      Eigen::Vector3d d = Eigen::Vector3d::Zero();
      for (int k = 0; k < mesh.AmbientDim; ++k)
        d[k] = mesh.Point(q)[k] - mesh.Point(p)[k];
      const Eigen::Matrix3d mp = Block(f, p, dim), mq = Block(f, q, dim);
      const double l = std::sqrt(d.dot(mp * d));
      const double eta = std::pow(1.0 + l * std::log(beta), -2.0);
      Eigen::Matrix3d propagated = eta * mp;
      if (dim == 2)
        propagated(2, 2) = 1.0;
      worst = std::max(worst, Excess(propagated, mq));
    }
  }
  return worst;
}

bool AllSpd(const av::MetricField& f, int dim)
{
  for (std::size_t i = 0; i < f.NumPoints(); ++i)
    if (!(dim == 3 ? av::IsPositiveDefinite(av::UnpackSymmetric(f.At(i)))
                   : av::IsPositiveDefinite(av::UnpackSymmetric2(f.At(i)))))
      return false;
  return true;
}

void CheckGradation(const av::SimplexMesh& mesh, int dim)
{
  const av::MetricField raw = Field(mesh, Jump);
  const double beta = 1.3;
  AV_CHECK_MSG(WorstGradation(mesh, raw, beta, dim) > 2.0, "the raw jump violates the bound");
  av::MetricField graded = raw;
  int sweeps = 0;
  const std::size_t changed = av::GradeMetric(mesh, {}, beta, dim, graded, sweeps);
  const double worst = WorstGradation(mesh, graded, beta, dim);
  AV_CHECK_MSG(worst <= 1.0 + 1e-5, "gradation bound on every edge: worst excess " << worst);
  AV_CHECK(AllSpd(graded, dim));
  AV_CHECK(changed > 0 && changed < mesh.NumPoints());
  AV_CHECK(sweeps > 1);
  // Gradation only refines (intersection): M_graded >= M_raw at every vertex, and the fine side
  // of the jump is kept as it was.
  for (std::size_t i = 0; i < mesh.NumPoints(); ++i)
  {
    AV_CHECK(Excess(Block(raw, i, dim), Block(graded, i, dim)) <= 1.0 + 1e-9);
    if (mesh.Point(i)[0] < 0.5)
      AV_CHECK(
        (Block(graded, i, dim) - Block(raw, i, dim)).norm() <= 1e-9 * Block(raw, i, dim).norm());
  }
  // A second pass has nothing left to do.
  av::MetricField again = graded;
  AV_CHECK(av::GradeMetric(mesh, {}, beta, dim, again, sweeps) == 0);
  AV_CHECK(again.Values == graded.Values);
}

void CheckUniform()
{
  const av::SimplexMesh mesh = Cube(6);
  const av::MetricField raw = Field(mesh, Smooth);
  av::MetricPreparationOptions o;
  o.SizeMode = av::MetricSizeMode::Uniform;
  o.Gradation = false;
  o.TargetSites = 500;
  const av::MetricPreparationResult r = av::PrepareMetric(mesh, raw, o);
  double lo = 1e300, hi = 0.0;
  for (std::size_t i = 0; i < mesh.NumPoints(); ++i)
  {
    const double det = av::UnpackSymmetric(r.Metric.At(i)).determinant();
    lo = std::min(lo, det);
    hi = std::max(hi, det);
  }
  AV_CHECK_MSG(hi / lo - 1.0 < 1e-9, "uniform mode: det M constant, spread " << hi / lo - 1.0);
  // Shapes kept: the stretch ratio is the raw one.
  for (std::size_t i = 0; i < mesh.NumPoints(); ++i)
    AV_CHECK_NEAR(r.StretchRatio[i], av::StretchRatio(av::UnpackSymmetric(raw.At(i))), 1e-8);
  // Blend 0.5: det M proportional to sqrt(det M_raw).
  o.SizeMode = av::MetricSizeMode::Blend;
  const av::MetricPreparationResult b = av::PrepareMetric(mesh, raw, o);
  const double ratio0 = av::UnpackSymmetric(b.Metric.At(0)).determinant() /
    std::sqrt(av::UnpackSymmetric(raw.At(0)).determinant());
  for (std::size_t i = 1; i < mesh.NumPoints(); ++i)
    AV_CHECK_NEAR(av::UnpackSymmetric(b.Metric.At(i)).determinant() /
        std::sqrt(av::UnpackSymmetric(raw.At(i)).determinant()) / ratio0,
      1.0,
      1e-9);
}

void CheckLimitsAndTarget()
{
  const av::SimplexMesh mesh = Cube(8);
  const av::MetricField raw = Field(mesh, Jump);
  av::MetricPreparationOptions o;
  o.TargetSites = 3000;
  o.HMin = 0.05;
  o.HMax = 0.25;
  const av::MetricPreparationResult r = av::PrepareMetric(mesh, raw, o);
  AV_CHECK(AllSpd(r.Metric, 3));
  AV_CHECK_MSG(r.NumHMinClamped > 0 && r.NumHMaxClamped > 0 && r.NumGraded > 0,
    "hmin " << r.NumHMinClamped << " hmax " << r.NumHMaxClamped << " graded " << r.NumGraded);
  for (std::size_t i = 0; i < mesh.NumPoints(); ++i)
  {
    const Eigen::Vector3d l = av::EigenDecompose(av::UnpackSymmetric(r.Metric.At(i))).Values;
    AV_CHECK(l.minCoeff() >= (1.0 - 1e-9) / (o.HMax * o.HMax));
    AV_CHECK(l.maxCoeff() <= (1.0 + 1e-9) / (o.HMin * o.HMin));
  }
  // The target complexity is met after the limits and the gradation, measured independently.
  const double c = av::MetricComplexity(mesh, r.Metric);
  AV_CHECK_NEAR(c / (o.TargetSites * av::UnitVertexMeasure(3)), 1.0, 2.5e-3);
  AV_CHECK_NEAR(r.ImpliedSites, o.TargetSites, 0.0025 * o.TargetSites);
  AV_CHECK(r.NormalizationRounds > 1); // the gradation added complexity: the scale was re-fitted
}

void CheckIdempotenceAndDeviation()
{
  for (int dim : { 2, 3 })
  {
    const av::SimplexMesh mesh = dim == 2 ? Square(30) : Cube(8);
    const av::MetricField raw = Field(mesh, Jump);
    av::MetricPreparationOptions o;
    o.Dimension = dim;
    o.TargetSites = 2000;
    o.HMax = 0.3;
    const av::MetricPreparationResult first = av::PrepareMetric(mesh, raw, o);
    AV_CHECK(WorstGradation(mesh, first.Metric, o.GradationFactor, dim) <= 1.0 + 1e-5);
    // Preparation changed the jump field (graded the coarse side) and says so.
    AV_CHECK(first.Deviation.Percentile95 > 0.5 && first.Deviation.ChangedFraction > 0.1);
    const av::MetricPreparationResult second = av::PrepareMetric(mesh, first.Metric, o);
    AV_CHECK_MSG(second.Deviation.Maximum < 5e-3,
      "idempotence (dim " << dim << "): largest change " << second.Deviation.Maximum);
    double worst = 0.0;
    for (std::size_t i = 0; i < mesh.NumPoints(); ++i)
    {
      const Eigen::Matrix3d m1 = av::UnpackSymmetric(first.Metric.At(i));
      worst = std::max(worst, (av::UnpackSymmetric(second.Metric.At(i)) - m1).norm() / m1.norm());
    }
    AV_CHECK_MSG(worst < 1e-2, "idempotence: largest relative change of a metric " << worst);
    AV_CHECK_MSG(second.Deviation.Median < 1e-3, "median change " << second.Deviation.Median);
  }
  // The deviation ignores a global scale and sees a local change: one vertex whose length along
  // a raw eigenvector doubles (eigenvalue x 4).
  const av::SimplexMesh mesh = Cube(6);
  const av::MetricField raw = Field(mesh, Smooth);
  av::MetricField scaled = raw;
  for (double& v : scaled.Values)
    v *= 7.0;
  AV_CHECK(av::MeasureMetricDeviation(mesh, raw, scaled, 3).Maximum < 1e-9);
  av::MetricField local = raw;
  const std::size_t i = mesh.NumPoints() / 2;
  const auto e = av::EigenDecompose(av::UnpackSymmetric(raw.At(i)));
  const Eigen::Vector3d v = e.Vectors.col(2);
  av::PackSymmetric(av::UnpackSymmetric(raw.At(i)) + 3.0 * e.Values[2] * v * v.transpose(),
    local.Values.data() + 6 * i);
  const av::MetricDeviation d = av::MeasureMetricDeviation(mesh, raw, local, 3);
  AV_CHECK_NEAR(d.Maximum, 1.0, 0.01);
  AV_CHECK_NEAR(d.ChangedFraction, 1.0 / mesh.NumPoints(), 1e-12);
  AV_CHECK(d.Median < 1e-2);
}

void CheckErrors()
{
  const av::SimplexMesh mesh = Cube(2);
  const av::MetricField good = Field(mesh, Smooth);
  av::MetricPreparationOptions o;
  av::MetricField bad = good;
  bad.Values[0] = -1.0; // not positive definite
  AV_CHECK_THROWS(av::PrepareMetric(mesh, bad, o));
  bad = good;
  bad.Values[3] = NAN;
  AV_CHECK_THROWS(av::PrepareMetric(mesh, bad, o));
  bad = good;
  bad.Values.resize(6);
  AV_CHECK_THROWS(av::PrepareMetric(mesh, bad, o));
  o.HMin = 0.5;
  o.HMax = 0.1;
  AV_CHECK_THROWS(av::PrepareMetric(mesh, good, o));
  o = av::MetricPreparationOptions();
  o.GradationFactor = 1.0;
  AV_CHECK_THROWS(av::PrepareMetric(mesh, good, o));
  o = av::MetricPreparationOptions();
  o.SizeBlend = 1.5;
  o.SizeMode = av::MetricSizeMode::Blend;
  AV_CHECK_THROWS(av::PrepareMetric(mesh, good, o));
  o = av::MetricPreparationOptions();
  AV_CHECK_THROWS(av::PrepareMetric(mesh, good, o, { 0, 1000 }));
  AV_CHECK_THROWS(av::PrepareMetric(av::SimplexMesh(), av::MetricField(), o));
}
} // namespace

int TestMetricPreparation(int, char*[])
{
  CheckGradation(Square(40), 2);
  CheckGradation(Cube(10), 3);
  CheckUniform();
  CheckLimitsAndTarget();
  CheckIdempotenceAndDeviation();
  CheckErrors();
  return AV_TEST_RESULT();
}
