// SPDX-License-Identifier: BSD-3-Clause
// MetricAlgebra: small dense helpers on symmetric metric tensors (packing, eigen-decomposition,
// SPD checks, symmetric square root, stretch ratio). Header-light, VTK-free, reusable by every
// kernel that reads a MetricField.
#ifndef av_MetricAlgebra_h
#define av_MetricAlgebra_h

#include "SimplexMesh.h"

#include <Eigen/Dense>

#include <vector>

namespace av
{

/// Unpacks a 6-component symmetric tensor (VTK order XX, YY, ZZ, XY, YZ, XZ) into a 3x3 matrix.
Eigen::Matrix3d UnpackSymmetric(const double* v6);

/// Upper-left 2x2 block (XX, XY, YY) of a packed tensor: the metric of a flat 2D domain.
Eigen::Matrix2d UnpackSymmetric2(const double* v6);

/// Packs a symmetric 3x3 matrix into VTK order (XX, YY, ZZ, XY, YZ, XZ); symmetrizes first.
void PackSymmetric(const Eigen::Matrix3d& m, double* v6);

/// Packs a 2x2 metric (ZZ, YZ, XZ set to 0).
void PackSymmetric2(const Eigen::Matrix2d& m, double* v6);

/// Eigen-decomposition of a symmetric 3x3 matrix: eigenvalues ascending, eigenvectors in columns
/// (orthonormal, right-handed). Uses the iterative (accurate) solver.
struct SymmetricEigen3
{
  Eigen::Vector3d Values;
  Eigen::Matrix3d Vectors;
};
SymmetricEigen3 EigenDecompose(const Eigen::Matrix3d& m);

/// Same for 2x2 (closed form, accurate).
struct SymmetricEigen2
{
  Eigen::Vector2d Values;
  Eigen::Matrix2d Vectors;
};
SymmetricEigen2 EigenDecompose(const Eigen::Matrix2d& m);

/// True when all n values are finite (no NaN / Inf).
bool AllFinite(const double* v, int n);

/**
 * True when the symmetric matrix is positive definite: smallest eigenvalue > relTol times the
 * largest absolute eigenvalue (and > 0). relTol guards against numerically singular metrics.
 */
bool IsPositiveDefinite(const Eigen::Matrix3d& m, double relTol = 1e-12);
bool IsPositiveDefinite(const Eigen::Matrix2d& m, double relTol = 1e-12);

/// True when the smallest eigenvalue >= -relTol * largest |eigenvalue| (rank-deficient allowed).
bool IsPositiveSemiDefinite(const Eigen::Matrix3d& m, double relTol = 1e-10);

/**
 * Symmetric square root A = R^T S R of M = R^T S^2 R, so that A^T A = M. Eigenvalues below zero
 * (round-off on a semi-definite metric) are clamped to 0.
 */
Eigen::Matrix3d SymmetricSqrt(const Eigen::Matrix3d& m);
Eigen::Matrix2d SymmetricSqrt(const Eigen::Matrix2d& m);

/// M = R diag(s^2) R^T where the columns of R are the principal directions and s the stretches.
Eigen::Matrix3d MetricFromFrame(const Eigen::Matrix3d& directions, const Eigen::Vector3d& stretch);

/**
 * Stretching ratio sqrt(lambda_max / lambda_min) of an SPD metric (ratio of the largest to the
 * smallest stretch). Returns +inf when lambda_min <= 0.
 */
double StretchRatio(const Eigen::Matrix3d& m);
double StretchRatio(const Eigen::Matrix2d& m);

/**
 * Stretch ratio of a rank-2 surface metric: sqrt of the ratio of its two largest eigenvalues
 * (the third, along the normal, is ~0 and ignored).
 */
double SurfaceStretchRatio(const Eigen::Matrix3d& m);

/**
 * The normal of a rank-2 surface metric (pass the metric, not its square root, whose round-off is
 * larger): the unit eigenvector of its smallest eigenvalue when that is at most 1e-6 of the
 * largest; the zero vector for a metric of full rank (no tangent plane to move) or a zero one.
 */
Eigen::Vector3d SurfaceMetricNormal(const Eigen::Matrix3d& m);

/**
 * A surface metric (or its square root) `s` with normal `from` (SurfaceMetricNormal) moved by the
 * smallest rotation R that takes `from` onto the line of the unit vector `to` (either sign): R s
 * R^T measures in the plane normal to `to` the lengths s measures in its own tangent plane. Where
 * a vertex normal is far from an adjacent triangle's (a thin CAD rim, a crease), s itself gives
 * the triangle's edges along `from` almost no length. `from` = 0: s is returned as it is.
 */
Eigen::Matrix3d MoveSurfaceMetric(
  const Eigen::Matrix3d& s, const Eigen::Vector3d& from, const Eigen::Vector3d& to);

/**
 * The squared §5.1 length |(A_a + A_b) / 2 d|² of the edge d = b − a on a surface whose vertex
 * metric roots A_a, A_b are rank 2 with normals n_a, n_b (SurfaceMetricNormal; 0 = full rank):
 * each A is first moved (MoveSurfaceMetric) by the smallest rotation that puts d into its
 * tangent plane, so that an edge along a vertex normal gets that vertex's tangent lengths.
 */
double SurfaceEdgeMetricLength2(const Eigen::Vector3d& d,
  const Eigen::Matrix3d& rootA,
  const Eigen::Vector3d& normalA,
  const Eigen::Matrix3d& rootB,
  const Eigen::Vector3d& normalB);

/// SurfaceMetricNormal of every tensor of a field (in parallel).
std::vector<Eigen::Vector3d> SurfaceMetricNormals(const MetricField& field);

/// Smallest and largest eigenvalue over a whole field (3x3 tensors; 2x2 block when dim2 is true).
void EigenvalueRange(const MetricField& field, bool dim2, double& minEig, double& maxEig);

} // namespace av

#endif
