// SPDX-License-Identifier: BSD-3-Clause
// MetricFieldOps: operations on a metric field over a mesh that several stages share: SPD-safe
// (log-Euclidean) interpolation, intersection, metric lengths of edges, metric measure of cells
// and the field's complexity (how many unit cells it holds).
#ifndef av_MetricFieldOps_h
#define av_MetricFieldOps_h

#include "SimplexMesh.h"

#include <Eigen/Dense>

#include <cstddef>
#include <cstdint>

namespace av
{

/**
 * Log-Euclidean mean exp(sum_i w_i log M_i) of `n` metrics (6-component packs), weights summing
 * to 1: SPD whenever the inputs are, and geometric in sizes (I and 4I give 2I). Eigenvalues
 * below 1e-12 x the largest (the normal direction of a rank-2 surface metric) stay at zero.
 */
Eigen::Matrix3d LogEuclideanMean(const double* const* metrics, const double* weights, int n);

/**
 * The intersection of two SPD metrics (Alauzet & Frey): the largest metric whose unit ball is
 * contained in both unit balls, by simultaneous reduction. It is SPD, and >= both in the Loewner
 * order, so it keeps the smaller size of the two in every direction.
 */
Eigen::Matrix3d IntersectMetrics(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b);
Eigen::Matrix2d IntersectMetrics(const Eigen::Matrix2d& a, const Eigen::Matrix2d& b);

/**
 * a <- a ∩ b only when b asks for more than a somewhere: its largest generalized eigenvalue
 * against a exceeds 1 + relTol. Returns whether `a` changed. The gradation's inner step: most
 * propagated metrics are already contained, and this tells so with one reduction.
 */
bool IntersectInto(Eigen::Matrix3d& a, const Eigen::Matrix3d& b, double relTol);
bool IntersectInto(Eigen::Matrix2d& a, const Eigen::Matrix2d& b, double relTol);

/// Metric length of the segment a -> b (AmbientDim values each) as paper §5.1 measures it:
/// |Q (b - a)| with Q = (M_a^{1/2} + M_b^{1/2}) / 2.
double MetricEdgeLength(
  const double* ma6, const double* mb6, const double* a, const double* b, int ambientDim);

/**
 * Measure (area or volume) of `cell` in the metric: sqrt(det(E^T Mbar E)) / k!, E the cell's edge
 * vectors, Mbar the mean of its vertex metrics. Works for flat 2D, surface and volume cells.
 */
double MetricCellMeasure(const SimplexMesh& mesh, const MetricField& metric, std::size_t cell);

/// Complexity of the field: the sum of the cells' metric measures (the integral of sqrt(det M)).
double MetricComplexity(const SimplexMesh& mesh, const MetricField& metric);

/**
 * Measure per vertex of a mesh of unit-length edges: sqrt(3)/2 for triangles (equilateral, two
 * per vertex), 1/sqrt(2) for tetrahedra (the regular-tetrahedron packing estimate that MMG and
 * Feflo.a use). A field of complexity C holds about C / UnitVertexMeasure(k) unit cells.
 */
double UnitVertexMeasure(int simplexDim);

} // namespace av

#endif
