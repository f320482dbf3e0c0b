// SPDX-License-Identifier: BSD-3-Clause
// MetricSimplexQuality: the signed smallest-sine quality of a triangle or tet mapped by the
// mean of its vertices' metric square roots (the measure MeshImprovement's worst-first passes
// optimize), and the §5.2 shape G of the same mapped simplex (its mean-quality sweeps').
#ifndef av_MetricSimplexQuality_h
#define av_MetricSimplexQuality_h

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace av
{

/// Tet (a, b, c, d) mapped by (Sa + Sb + Sc + Sd) / 4: its edge vectors from a.
struct MappedTet
{
  Eigen::Vector3d AB, AC, AD;
  MappedTet(const Eigen::Vector3d& a,
    const Eigen::Vector3d& b,
    const Eigen::Vector3d& c,
    const Eigen::Vector3d& d,
    const Eigen::Matrix3d& sa,
    const Eigen::Matrix3d& sb,
    const Eigen::Matrix3d& sc,
    const Eigen::Matrix3d& sd)
  {
    const Eigen::Matrix3d m = 0.25 * (sa + sb + sc + sd);
    AB = m * (b - a);
    AC = m * (c - a);
    AD = m * (d - a);
  }
};

/// Triangle (a, b, c) in 3D mapped by (Sa + Sb + Sc) / 3: its doubled area, edge lengths and
/// whether its input-space normal agrees with `up`.
struct MappedTriangle
{
  double A2, LAB, LAC, LBC;
  bool Positive;
  MappedTriangle(const Eigen::Vector3d& a,
    const Eigen::Vector3d& b,
    const Eigen::Vector3d& c,
    const Eigen::Matrix3d& sa,
    const Eigen::Matrix3d& sb,
    const Eigen::Matrix3d& sc,
    const Eigen::Vector3d& up)
  {
    const Eigen::Matrix3d m = (sa + sb + sc) / 3.0;
    const Eigen::Vector3d ab = m * (b - a), ac = m * (c - a), bc = ac - ab;
    A2 = ab.cross(ac).norm();
    Positive = (b - a).cross(c - a).dot(up) > 0.0;
    LAB = ab.norm();
    LAC = ac.norm();
    LBC = bc.norm();
  }
};

/// A mapped tet's quality: the smallest sine of its six dihedral angles,
/// sin_ij = 6V l_ij / (|n_k| |n_l|) (n = doubled face area vectors), with the sign of V.
inline double TetQuality(const MappedTet& t)
{
  const Eigen::Vector3d &ab = t.AB, &ac = t.AC, &ad = t.AD;
  const Eigen::Vector3d bc = ac - ab, bd = ad - ab, cd = ad - ac;
  const double v6 = ab.dot(ac.cross(ad));
  // Doubled face areas, face k opposite vertex k.
  const double f0 = bc.cross(bd).norm(), f1 = ac.cross(ad).norm(), f2 = ab.cross(ad).norm(),
               f3 = ab.cross(ac).norm();
  const double denomMin = 1e-300;
  if (f0 * f1 * f2 * f3 <= denomMin)
    return v6 > 0.0 ? 0.0 : -1.0;
  // Edge ij lies on the two faces opposite the other two vertices.
  const double s01 = ab.norm() / (f2 * f3), s02 = ac.norm() / (f1 * f3),
               s03 = ad.norm() / (f1 * f2), s12 = bc.norm() / (f0 * f3),
               s13 = bd.norm() / (f0 * f2), s23 = cd.norm() / (f0 * f1);
  const double s = std::min(std::min(std::min(s01, s02), std::min(s03, s12)), std::min(s13, s23));
  return v6 * s;
}

/// Triangle (a, b, c) in 2D mapped by (Sa + Sb + Sc) / 3: smallest sine of its angles with the
/// sign of its area.
inline double TriangleMetricQuality(const Eigen::Vector2d& a,
  const Eigen::Vector2d& b,
  const Eigen::Vector2d& c,
  const Eigen::Matrix2d& sa,
  const Eigen::Matrix2d& sb,
  const Eigen::Matrix2d& sc)
{
  const Eigen::Matrix2d m = (sa + sb + sc) / 3.0;
  const Eigen::Vector2d ab = m * (b - a), ac = m * (c - a), bc = ac - ab;
  const double a2 = ab.x() * ac.y() - ab.y() * ac.x(); // doubled signed area
  const double lab = ab.norm(), lac = ac.norm(), lbc = bc.norm();
  const double p = lab * lac * lbc;
  if (p <= 1e-300)
    return a2 > 0.0 ? 0.0 : -1.0;
  // sin(angle at a) = 2S / (lab lac): the smallest is the angle between the two longest edges.
  return a2 * std::min(std::min(lab, lac), lbc) / p;
}

/// A mapped triangle's quality (a surface, or a plane at z = 0): the smallest sine of its
/// angles, negative when its input-space normal opposes `up` (the sum of its vertices' surface
/// normals). Equals TriangleMetricQuality for a plane and up = +z.
inline double TriangleQuality(const MappedTriangle& t)
{
  const double a2 = t.A2, lab = t.LAB, lac = t.LAC, lbc = t.LBC;
  const bool positive = t.Positive;
  const double p = lab * lac * lbc;
  if (p <= 1e-300)
    return positive ? 0.0 : -1.0;
  const double q = a2 * std::min(std::min(lab, lac), lbc) / p;
  return positive ? q : -q;
}

/// The §5.2 shape measure G = 12 (9 V^2)^(1/3) / sum l^2 of a mapped tet (1 when regular), with
/// the sign of V (the mean-quality smoothing's objective).
inline double TetMeanRatio(const MappedTet& t)
{
  const Eigen::Vector3d &ab = t.AB, &ac = t.AC, &ad = t.AD;
  const double v = ab.dot(ac.cross(ad)) / 6.0;
  const double l2 = ab.squaredNorm() + ac.squaredNorm() + ad.squaredNorm() +
    (ac - ab).squaredNorm() + (ad - ab).squaredNorm() + (ad - ac).squaredNorm();
  if (!(l2 > 1e-300))
    return v > 0.0 ? 0.0 : -1.0;
  const double g = 12.0 * std::cbrt(9.0 * v * v) / l2;
  return v > 0.0 ? g : -g;
}

/// The §5.2 shape measure G = 2 sqrt3 S / (s h) of a mapped triangle (s the half perimeter, h
/// the longest edge; 1 when equilateral), negative when it faces against `up`.
inline double TriangleMeanRatio(const MappedTriangle& t)
{
  const double sh = (t.LAB + t.LAC + t.LBC) * std::max(std::max(t.LAB, t.LAC), t.LBC); // 2 s h
  if (!(sh > 1e-300))
    return t.Positive ? 0.0 : -1.0;
  const double g = 2.0 * std::sqrt(3.0) * t.A2 / sh;
  return t.Positive ? g : -g;
}

/// Elements at or below this quality count as inverted or degenerate: no operation may make one.
constexpr double kMinImprovementQuality = 1e-6;

/**
 * The acceptance rule of every improvement operation: the worst quality it touches must rise
 * (by more than round-off), and nothing may fall to kMinImprovementQuality or below.
 * `acceptWorsening` is the test hook that shows the tests catch a rule that accepts anything.
 */
inline bool AcceptsImprovement(double after, double before, bool acceptWorsening)
{
  if (after <= kMinImprovementQuality)
    return false;
  return acceptWorsening || after > before + 1e-9;
}

} // namespace av

#endif
