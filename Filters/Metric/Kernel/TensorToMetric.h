// SPDX-License-Identifier: BSD-3-Clause
// TensorToMetric: turns a physical tensor field (stress, strain rate, diffusion, ...) into a
// symmetric positive definite metric field usable by the embedding (paper §6.4, Eq. 20).
// VTK-free.
#ifndef av_TensorToMetric_h
#define av_TensorToMetric_h

#include "SimplexMesh.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{

/// How a symmetric tensor T = V diag(lambda) V^T becomes a metric.
enum class TensorInterpretation
{
  /// Paper Eq. 20: the eigenvalues are stretch factors s_i = f(lambda_i); M = V diag(s_i^2) V^T.
  EigenvaluesAsStretch,
  /// The tensor already is metric-like (e.g. diffusion): M = V diag(f(lambda_i)) V^T.
  TensorAsMetric
};

/// f(lambda): what to do with negative eigenvalues (compression in a stress tensor, ...).
enum class EigenvalueHandling
{
  Absolute, ///< |lambda|: the magnitude matters, not the sign
  Clamp     ///< max(lambda, floor): negative directions get the floor
};

/// Parameters of TensorToMetric (defaults in brackets).
struct TensorToMetricOptions
{
  TensorInterpretation Interpretation = TensorInterpretation::EigenvaluesAsStretch;
  EigenvalueHandling Eigenvalues = EigenvalueHandling::Absolute;
  /// Floor on f(lambda), relative to the largest |lambda| of the whole dataset, in (0, 1]
  /// [1e-3]: zero and tiny eigenvalues would otherwise give unbounded anisotropy.
  double MinimumEigenvalue = 1e-3;
  /// Cap on s_max / s_min per point (the smaller stretches are raised); 0 = no cap [25].
  double MaximumAnisotropy = 25.0;
  /// Log-Euclidean Laplacian smoothing: iterations of log(M_i) <- (log(M_i) + mean over the
  /// neighbors of log(M_j)) / 2. Needs the edges argument. 0 = off [0].
  int SmoothingIterations = 0;
  /// 3, or 2 for a flat 2D domain: only XX, YY, XY are read and written [3].
  int Dimension = 3;
  /// Multiply the field by c = 1 / (smallest metric eigenvalue) when that is < 1, so that
  /// every eigenvalue is >= 1 as the embedding needs (paper §6) [true].
  bool ApplyGlobalScale = true;
};

/// Output of TensorToMetric.
struct TensorToMetricResult
{
  MetricField Metric;              ///< 6 components per tuple, VTK order; 2D: ZZ, YZ, XZ are 0
  std::vector<double> StretchRatio; ///< s_max / s_min per tuple (= sqrt of the eigenvalue ratio)
  double GlobalScale = 1.0;        ///< c, already applied to Metric
  double MinEigenvalue = 0.0;      ///< smallest / largest eigenvalue of Metric (after scaling)
  double MaxEigenvalue = 0.0;
  double MinStretch = 0.0;         ///< range of StretchRatio
  double MaxStretch = 0.0;
  /// Largest relative asymmetry |T - T^T|_F / (2 |T|_F) of the input (9-component input only;
  /// the tensor was symmetrized (T + T^T) / 2). Report it when it is not round-off.
  double MaxAsymmetry = 0.0;
  std::size_t NumNegative = 0; ///< tuples with at least one negative eigenvalue
  std::size_t NumClamped = 0;  ///< tuples where an eigenvalue was raised to the floor
  std::size_t NumCapped = 0;   ///< tuples whose anisotropy was capped
};

/**
 * @brief Converts `count` tensors into an SPD metric field.
 *
 * tensors: count x numComponents values, numComponents 9 (row-major 3x3, possibly
 * non-symmetric) or 6 (symmetric, VTK order XX, YY, ZZ, XY, YZ, XZ). The tuples may be per
 * point or per cell; edges (flat pairs of tuple ids, e.g. UniqueEdges(mesh) for point data)
 * are only used by the smoothing.
 * Steps: symmetrize, eigen-decompose, f(lambda), floor, interpret, cap the anisotropy, smooth
 * (log-Euclidean), global scale.
 * Throws InputError on: empty input, numComponents not 6/9, NaN/Inf values, an all-zero
 * field, invalid options, edges out of range, smoothing without edges.
 */
TensorToMetricResult TensorToMetric(const double* tensors, std::size_t count, int numComponents,
  const TensorToMetricOptions& options, const std::vector<std::int32_t>& edges = {});

/**
 * @brief TensorToMetric for tensors given on a surface: each tensor is restricted to the
 * tangent plane of its tuple before the conversion.
 *
 * normals: count x 3 unit normals (e.g. SurfaceVertexNormals). Each tensor is written in a
 * frame (t1, t2, n) of its tangent plane and normal, its 2x2 tangent block goes through
 * TensorToMetric with Dimension 2 (every step, floor, cap and global scale on the tangent
 * eigenvalues only), and the result is rotated back: a rank-2 metric, zero along n, as the
 * curvature metric (Eq. 19). The normal components of the input never reach the stretch.
 * Throws InputError for a normal of zero length or NaN, SmoothingIterations > 0 (the per-tuple
 * frames differ, so a log-Euclidean average in them would be wrong: smooth the tensor field
 * first) and whatever TensorToMetric throws.
 */
TensorToMetricResult TangentTensorToMetric(const double* tensors, std::size_t count,
  int numComponents, const double* normals, TensorToMetricOptions options);

} // namespace av

#endif
