// SPDX-License-Identifier: BSD-3-Clause
// Checks the §5.2 quality measures on shapes with known answers, including metric mappings
// that only give G = 1 when A is the averaged per-vertex square root of the metric.
#include "MeshQuality.h"
#include "AnisoTestChecks.h"
#include "MetricAlgebra.h"

#include <Eigen/Dense>

#include <cmath>
#include <limits>
#include <vector>

namespace
{
const double kRegularDihedral = std::acos(1.0 / 3.0) * 180.0 / 3.14159265358979323846;

av::SimplexMesh RegularTet()
{
  av::SimplexMesh m;
  m.AmbientDim = 3;
  m.SimplexDim = 3;
  // Positively oriented regular tet with edge length 2 sqrt2.
  m.Points = { 1, 1, 1, -1, 1, -1, 1, -1, -1, -1, -1, 1 };
  m.Cells = { 0, 1, 2, 3 };
  return m;
}

av::MetricField Uniform(std::size_t n, const Eigen::Matrix3d& t)
{
  av::MetricField f;
  for (std::size_t i = 0; i < n; ++i)
    f.Values.insert(f.Values.end(), { t(0, 0), t(1, 1), t(2, 2), t(0, 1), t(1, 2), t(0, 2) });
  return f;
}

void Transform(av::SimplexMesh& m, const Eigen::Matrix3d& t)
{
  for (std::size_t i = 0; i < m.NumPoints(); ++i)
  {
    Eigen::Map<Eigen::Vector3d> p(m.Points.data() + 3 * i);
    p = t * Eigen::Vector3d(p);
  }
}

// Regular tet, identity metric.
void CheckRegularTetIdentityMetric()
{
  const Eigen::Matrix3d id = Eigen::Matrix3d::Identity();
  const av::SimplexMesh tet = RegularTet();
  const auto q = av::EvaluateMeshQuality(tet, Uniform(4, id));
  AV_CHECK_NEAR(q.G[0], 1.0, 1e-12);
  AV_CHECK_NEAR(q.MinAngle[0], kRegularDihedral, 1e-9);
  AV_CHECK_NEAR(q.Summary.ThetaMin, 70.528779, 1e-5);
  AV_CHECK(q.Summary.NumInverted == 0);
  AV_CHECK(q.Summary.NumBad == 0);
  AV_CHECK(q.Summary.NumEdges == 6);
  AV_CHECK_NEAR(q.Summary.PercentEdgesInUnitRange, 100.0, 1e-12);
  AV_CHECK_NEAR(q.Summary.MedianEdgeLength, 2.0 * std::sqrt(2.0), 1e-12);
  AV_CHECK(q.Summary.AngleHistogram.size() == 18 && q.Summary.AngleHistogram[14] == 1);
}

// Pre-stretched by 1/s along x, metric diag(s^2,1,1): the mapped tet is regular again.
void CheckPreStretched1SAlong()
{
  const Eigen::Matrix3d id = Eigen::Matrix3d::Identity();
  const double s = 7.0;
  av::SimplexMesh tet = RegularTet();
  Transform(tet, Eigen::Vector3d(1.0 / s, 1.0, 1.0).asDiagonal());
  Eigen::Matrix3d m = Eigen::Vector3d(s * s, 1.0, 1.0).asDiagonal();
  auto q = av::EvaluateMeshQuality(tet, Uniform(4, m));
  AV_CHECK_NEAR(q.G[0], 1.0, 1e-12);
  AV_CHECK_NEAR(q.MinAngle[0], kRegularDihedral, 1e-9);
  // Under the identity metric the same tet is poor: the test can tell the metric is used.
  q = av::EvaluateMeshQuality(tet, Uniform(4, id));
  AV_CHECK(q.G[0] < 0.6);
}

// Rotated anisotropic metric (all 6 components in use): M = R diag(s^2,t^2,1) R^T and the
// mesh pre-mapped by M^{-1/2}.
void CheckRotatedAnisotropicMetricAll6()
{
  const Eigen::Matrix3d r = (Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()) *
    Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, 2, 3).normalized()))
                              .toRotationMatrix();
  const double s = 5.0, t = 2.0;
  const Eigen::Matrix3d m = r * Eigen::Vector3d(s * s, t * t, 1).asDiagonal() * r.transpose();
  const Eigen::Matrix3d inv = r * Eigen::Vector3d(1 / s, 1 / t, 1).asDiagonal() * r.transpose();
  av::SimplexMesh tet = RegularTet();
  Transform(tet, inv);
  const auto q = av::EvaluateMeshQuality(tet, Uniform(4, m));
  AV_CHECK_NEAR(q.G[0], 1.0, 1e-10);
  AV_CHECK_NEAR(q.MinAngle[0], kRegularDihedral, 1e-7);
  AV_CHECK(q.Summary.NumInverted == 0);
}

// Different vertex metrics: A = (sum sqrt(M_i))/4 = diag(4,1,1) maps the pre-stretched tet
// to the regular one; sqrt of the averaged metric (sqrt(20) along x) would not.
void CheckDifferentVertexMetricsSumSqrt()
{
  av::SimplexMesh tet = RegularTet();
  Transform(tet, Eigen::Vector3d(0.25, 1.0, 1.0).asDiagonal());
  av::MetricField f;
  for (double sx : { 2.0, 2.0, 6.0, 6.0 })
    f.Values.insert(f.Values.end(), { sx * sx, 1, 1, 0, 0, 0 });
  const auto q = av::EvaluateMeshQuality(tet, f);
  AV_CHECK_NEAR(q.G[0], 1.0, 1e-12);
}

// Equilateral triangle in 2D, identity, and pre-stretched under diag(s^2, 1).
void CheckEquilateralTriangle2DIdentityPre()
{
  const Eigen::Matrix3d id = Eigen::Matrix3d::Identity();
  av::SimplexMesh tri;
  tri.AmbientDim = 2;
  tri.SimplexDim = 2;
  tri.Points = { 0, 0, 1, 0, 0.5, std::sqrt(3.0) / 2 };
  tri.Cells = { 0, 1, 2 };
  av::MetricField f = Uniform(3, id);
  f.Values[6] = std::numeric_limits<double>::quiet_NaN();
  AV_CHECK_THROWS(av::EvaluateMeshQuality(tri, f));
  auto q = av::EvaluateMeshQuality(tri, Uniform(3, id));
  AV_CHECK_NEAR(q.G[0], 1.0, 1e-12);
  AV_CHECK_NEAR(q.MinAngle[0], 60.0, 1e-9);
  AV_CHECK(q.Summary.AngleHistogram[12] == 1);
  AV_CHECK(q.Summary.NumInverted == 0);
  const double s = 10.0;
  for (std::size_t i = 0; i < 3; ++i)
    tri.Points[2 * i] /= s;
  q = av::EvaluateMeshQuality(tri, Uniform(3, Eigen::Vector3d(s * s, 1, 1).asDiagonal()));
  AV_CHECK_NEAR(q.G[0], 1.0, 1e-12);
  AV_CHECK_NEAR(q.Summary.ThetaAvg, 60.0, 1e-9);
  // Clockwise order counts as inverted in 2D.
  tri.Cells = { 0, 2, 1 };
  q = av::EvaluateMeshQuality(tri, Uniform(3, id));
  AV_CHECK(q.Summary.NumInverted == 1);
  AV_CHECK(q.Summary.NumBad == 1); // stretched triangle under identity: min angle < 30
}

// Sliver: four nearly coplanar points -> G ~ 0, min dihedral ~ 0, counted as bad.
void CheckSliverFourNearlyCoplanarPoints()
{
  const Eigen::Matrix3d id = Eigen::Matrix3d::Identity();
  av::SimplexMesh tet;
  tet.Points = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 1e-4 };
  tet.Cells = { 0, 1, 2, 3 };
  const auto q = av::EvaluateMeshQuality(tet, Uniform(4, id));
  AV_CHECK(q.G[0] < 0.01);
  AV_CHECK(q.MinAngle[0] < 0.1);
  AV_CHECK(q.Summary.NumBad == 1);
  AV_CHECK_NEAR(q.Summary.PercentBad, 100.0, 1e-12);
  AV_CHECK(q.Summary.NumInverted == 0);
}

// Inverted tet (two vertices swapped) is counted; quality itself is unsigned.
void CheckInvertedTetTwoVerticesSwapped()
{
  const Eigen::Matrix3d id = Eigen::Matrix3d::Identity();
  av::SimplexMesh tet = RegularTet();
  tet.Cells = { 0, 2, 1, 3, 0, 1, 2, 3 };
  const auto q = av::EvaluateMeshQuality(tet, Uniform(4, id));
  AV_CHECK(q.Summary.NumInverted == 1);
  AV_CHECK(q.Inverted[0] == 1 && q.Inverted[1] == 0);
  AV_CHECK_NEAR(q.Summary.GMin, 1.0, 1e-12);
  AV_CHECK(q.Summary.NumEdges == 6);
}

// Edge-length ratio: a 2x1 rectangle split in two triangles has edges 1,1,2,2,sqrt5;
// median 2 -> normalized 0.5,0.5,1,1,1.118 -> 60 % in [1/sqrt2, sqrt2].
void CheckEdgeLengthRatio2x1Rectangle()
{
  const Eigen::Matrix3d id = Eigen::Matrix3d::Identity();
  av::SimplexMesh quad;
  quad.AmbientDim = 2;
  quad.SimplexDim = 2;
  quad.Points = { 0, 0, 2, 0, 2, 1, 0, 1 };
  quad.Cells = { 0, 1, 2, 0, 2, 3 };
  const auto q = av::EvaluateMeshQuality(quad, Uniform(4, id));
  AV_CHECK(q.Summary.NumEdges == 5);
  AV_CHECK_NEAR(q.Summary.MedianEdgeLength, 2.0, 1e-12);
  AV_CHECK_NEAR(q.Summary.PercentEdgesInUnitRange, 60.0, 1e-12);
  // Under diag(1/4, 1) (A = diag(1/2,1)) all edges become 1,1,1,1,sqrt2 -> 100 %.
  const auto q2 =
    av::EvaluateMeshQuality(quad, Uniform(4, Eigen::Vector3d(0.25, 1, 1).asDiagonal()));
  AV_CHECK_NEAR(q2.Summary.PercentEdgesInUnitRange, 100.0, 1e-12);
  AV_CHECK_NEAR(q2.Summary.MedianEdgeLength, 1.0, 1e-12);

  // Metric interpolation at sites.
  av::MetricField f;
  for (double v : { 1.0, 2.0, 3.0, 4.0 })
    f.Values.insert(f.Values.end(), { v, 2 * v, 3 * v, v, -v, 0.5 * v });
  av::SiteSet sites;
  sites.Dim = 2;
  sites.Coords = { 1.0, 0.5, 0.0, 1.0 };
  sites.CellIds = { 1, 0 };
  sites.Bary = { 0.5, 0.25, 0.25, 0, 0.2, 0.3, 0.5, 0 };
  const auto mi = av::InterpolateMetricAtSites(quad, f, sites);
  AV_CHECK(mi.NumPoints() == 2);
  // cell 1 = (0,2,3): 0.5*1 + 0.25*3 + 0.25*4 = 2.25; cell 0 = (0,1,2): .2+.6+1.5 = 2.3
  AV_CHECK_NEAR(mi.At(0)[0], 2.25, 1e-12);
  AV_CHECK_NEAR(mi.At(0)[4], -2.25, 1e-12);
  AV_CHECK_NEAR(mi.At(1)[1], 4.6, 1e-12);
  sites.CellIds[0] = 2;
  AV_CHECK_THROWS(av::InterpolateMetricAtSites(quad, f, sites));
  sites.CellIds[0] = 1;
  sites.Bary.pop_back();
  AV_CHECK_THROWS(av::InterpolateMetricAtSites(quad, f, sites));
}

// Quality in an embedding: cells mapped into R^8 by x -> Q A x (Q orthonormal columns, A a
// constant metric square root) have the G that EvaluateMeshQuality gives with M = A^2.
void CheckQualityEmbeddingCellsMappedInto()
{
  Eigen::Matrix<double, 8, 8> raw;
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j)
      raw(i, j) = std::sin(1.0 + 3.0 * i + 7.0 * j * j);
  const Eigen::Matrix<double, 8, 8> q = Eigen::HouseholderQR<Eigen::Matrix<double, 8, 8>>(raw).householderQ();
  Eigen::Matrix3d a;
  a << 3.0, 0.5, 0.2, 0.5, 1.2, -0.3, 0.2, -0.3, 0.8;
  av::SimplexMesh mesh;
  mesh.AmbientDim = 3;
  mesh.SimplexDim = 3;
  mesh.Points = { 0, 0, 0, 1, 0.1, 0, 0.2, 0.9, 0.1, 0.3, 0.2, 1.1, 1.0, 1.0, 1.0, 0.5, 0.5, -0.05 };
  mesh.Cells = { 0, 1, 2, 3, 1, 2, 3, 4, 0, 1, 2, 5 };
  const auto want = av::EvaluateMeshQuality(mesh, Uniform(mesh.NumPoints(), a * a));
  std::vector<double> coords;
  for (std::size_t i = 0; i < mesh.NumPoints(); ++i)
  {
    const Eigen::Matrix<double, 8, 1> x =
      q.leftCols(3) * (a * Eigen::Vector3d(mesh.Point(i))) + Eigen::Matrix<double, 8, 1>::Constant(0.7);
    coords.insert(coords.end(), x.data(), x.data() + 8);
  }
  const std::vector<double> g = av::SimplexQualityInEmbedding(mesh.Cells, 3, coords, 8);
  AV_CHECK(g.size() == 3);
  for (std::size_t c = 0; c < g.size(); ++c)
    AV_CHECK_NEAR(g[c], want.G[c], 1e-12);
  AV_CHECK(want.G[2] < 0.3); // the flat third cell really is bad

  // Triangles: the same for a 2D mesh mapped into R^5.
  av::SimplexMesh tri;
  tri.AmbientDim = 2;
  tri.SimplexDim = 2;
  tri.Points = { 0, 0, 1, 0.2, 0.3, 0.8, 1.4, 1.1 };
  tri.Cells = { 0, 1, 2, 1, 3, 2 };
  Eigen::Matrix3d a2 = Eigen::Matrix3d::Zero();
  a2.topLeftCorner<2, 2>() << 2.0, 0.4, 0.4, 0.9;
  const auto want2 = av::EvaluateMeshQuality(tri, Uniform(tri.NumPoints(), a2 * a2));
  const Eigen::Matrix<double, 5, 5> q5 =
    Eigen::HouseholderQR<Eigen::Matrix<double, 5, 5>>(raw.topLeftCorner<5, 5>()).householderQ();
  std::vector<double> c2;
  for (std::size_t i = 0; i < tri.NumPoints(); ++i)
  {
    const Eigen::Vector2d y = a2.topLeftCorner<2, 2>() * Eigen::Vector2d(tri.Point(i));
    const Eigen::Matrix<double, 5, 1> x = q5.leftCols<2>() * y;
    c2.insert(c2.end(), x.data(), x.data() + 5);
  }
  const std::vector<double> g2 = av::SimplexQualityInEmbedding(tri.Cells, 2, c2, 5);
  for (std::size_t c = 0; c < g2.size(); ++c)
    AV_CHECK_NEAR(g2[c], want2.G[c], 1e-12);

  // Bad input.
  AV_CHECK_THROWS(av::SimplexQualityInEmbedding(mesh.Cells, 4, coords, 8));
  AV_CHECK_THROWS(av::SimplexQualityInEmbedding(mesh.Cells, 3, coords, 2));
  AV_CHECK_THROWS(av::SimplexQualityInEmbedding(mesh.Cells, 3, std::vector<double>(7, 0.0), 8));
  std::vector<std::int32_t> badIds = mesh.Cells;
  badIds[5] = 6;
  AV_CHECK_THROWS(av::SimplexQualityInEmbedding(badIds, 3, coords, 8));
  coords[9] = std::numeric_limits<double>::infinity();
  AV_CHECK_THROWS(av::SimplexQualityInEmbedding(mesh.Cells, 3, coords, 8));
}

// Bad input.
void CheckBadInput()
{
  const Eigen::Matrix3d id = Eigen::Matrix3d::Identity();
  av::SimplexMesh tet = RegularTet();
  AV_CHECK_THROWS(av::EvaluateMeshQuality(tet, Uniform(3, id)));
  av::SimplexMesh empty;
  AV_CHECK_THROWS(av::EvaluateMeshQuality(empty, av::MetricField()));
  tet.Cells[2] = 9;
  AV_CHECK_THROWS(av::EvaluateMeshQuality(tet, Uniform(4, id)));
  tet = RegularTet();
  tet.Points[4] = std::numeric_limits<double>::quiet_NaN();
  AV_CHECK_THROWS(av::EvaluateMeshQuality(tet, Uniform(4, id)));
}

} // namespace

/// An equilateral triangle in z = 0 whose vertex metrics are rank 2 in a plane tilted 60 deg about
/// x (isotropic there: a rim vertex's normal averaged over two faces). Moved into the triangle's
/// plane they are the identity there: G = 1, every edge of length 1. Restricted without the move
/// the y lengths shrink by cos 60 (G = 0.65), and the site interpolation would not be rank 2.
void CheckTiltedSurfaceMetric()
{
  av::SimplexMesh m;
  m.AmbientDim = 3;
  m.SimplexDim = 2;
  m.Points = { 0, 0, 0, 1, 0, 0, 0.5, std::sqrt(3.0) / 2.0, 0 };
  m.Cells = { 0, 1, 2 };
  const double a = 60.0 * 3.14159265358979323846 / 180.0;
  const Eigen::Vector3d n(0.0, -std::sin(a), std::cos(a));
  const Eigen::Matrix3d tangent = Eigen::Matrix3d::Identity() - n * n.transpose();
  av::MetricField f;
  f.Values.resize(18);
  for (int v = 0; v < 3; ++v)
    av::PackSymmetric(tangent, f.Values.data() + 6 * v);
  const av::MeshQualityResult r = av::EvaluateMeshQuality(m, f);
  std::cout << "tilted surface metric: G " << r.G[0] << ", edges " << r.EdgeLengths[0] << " "
            << r.EdgeLengths[1] << " " << r.EdgeLengths[2] << "\n";
  AV_CHECK(std::abs(r.G[0] - 1.0) < 1e-12);
  for (double l : r.EdgeLengths)
    AV_CHECK(std::abs(l - 1.0) < 1e-12);

  av::SiteSet sites;
  sites.Dim = 3;
  sites.CellIds = { 0 };
  sites.Bary = { 0.2, 0.3, 0.5, 0.0 };
  sites.Coords = { 0, 0, 0 };
  const av::MetricField at = av::InterpolateMetricAtSites(m, f, sites);
  const Eigen::Matrix3d ms = av::UnpackSymmetric(at.Values.data());
  AV_CHECK((ms - Eigen::Vector3d(1, 1, 0).asDiagonal().toDenseMatrix()).norm() < 1e-12);
}

int TestMeshQuality(int, char*[])
{
  CheckTiltedSurfaceMetric();
  CheckRegularTetIdentityMetric();
  CheckPreStretched1SAlong();
  CheckRotatedAnisotropicMetricAll6();
  CheckDifferentVertexMetricsSumSqrt();
  CheckEquilateralTriangle2DIdentityPre();
  CheckSliverFourNearlyCoplanarPoints();
  CheckInvertedTetTwoVerticesSwapped();
  CheckEdgeLengthRatio2x1Rectangle();
  CheckQualityEmbeddingCellsMappedInto();
  CheckBadInput();
  return AV_TEST_RESULT();
}
