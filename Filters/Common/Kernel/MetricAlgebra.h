// SPDX-License-Identifier: BSD-3-Clause
// MetricAlgebra: small dense helpers on symmetric metric tensors (packing, eigen-decomposition,
// SPD checks, symmetric square root, stretch ratio). Header-light, VTK-free, reusable by every
// kernel that reads a MetricField.
#ifndef av_MetricAlgebra_h
#define av_MetricAlgebra_h

#include "SimplexMesh.h"

#include <Eigen/Dense>

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

/// Smallest and largest eigenvalue over a whole field (3x3 tensors; 2x2 block when dim2 is true).
void EigenvalueRange(const MetricField& field, bool dim2, double& minEig, double& maxEig);

} // namespace av

#endif
