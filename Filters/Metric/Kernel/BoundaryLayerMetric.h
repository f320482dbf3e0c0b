// SPDX-License-Identifier: BSD-3-Clause
// BoundaryLayerMetric: analytic boundary-layer metrics on the unit cube with the wall at z = 0
// (issue 12's strongly anisotropic test case): size h0 along the wall everywhere, wall-normal size
// h_z(z) growing from h0 / Stretch at the wall to h0. The metric is flat, so
// (x / h0, y / h0, integral of dz / h_z) is an exact isometric embedding: the error of an embedding
// and the rest of the pipeline can be told apart on it.
#ifndef av_BoundaryLayerMetric_h
#define av_BoundaryLayerMetric_h

#include "SimplexMesh.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace av
{

/// How the wall-normal size grows with the distance z from the wall.
enum class BoundaryLayerProfile
{
  /// h_z = h_w + (h0 - h_w) z: a constant growth ratio per layer of cells (about
  /// exp(h0 - h_w) = 1.105 for h0 = 0.1), the geometric law of CFD prism layers.
  Linear,
  /// h_z = h0 - (h0 - h_w) exp(-z / Thickness): the size rises exponentially to h0 within a few
  /// Thickness of the wall, like the paper's Cube2 profile; near the wall a cell is up to
  /// exp((h0 - h_w) / Thickness) (1.49 for the defaults) times the one below it.
  Exponential
};

struct BoundaryLayerMetricOptions
{
  double Stretch = 100.0;    ///< h0 / h_w, the anisotropy at the wall (>= 1)
  BoundaryLayerProfile Profile = BoundaryLayerProfile::Linear;
  double TangentSize = 0.1;  ///< h0: the size along the wall everywhere, and normal to it far away
  double Thickness = 0.25;   ///< Exponential: the e-folding distance of h0 - h_z
};

/// "linear" / "exponential".
std::string BoundaryLayerProfileName(BoundaryLayerProfile profile);

/// Throws InputError unless Stretch >= 1, TangentSize > 0 and Thickness > 0 (all finite).
void CheckBoundaryLayerOptions(const BoundaryLayerMetricOptions& options);

/// h_z at distance z from the wall.
double BoundaryLayerNormalSize(const BoundaryLayerMetricOptions& options, double z);

/// The metric length from the wall to z along the normal, integral_0^z dt / h_z(t) (closed form):
/// the third coordinate of the isometric embedding, in units of h0 = 1 after multiplying by h0.
double BoundaryLayerNormalLength(const BoundaryLayerMetricOptions& options, double z);

/// diag(1 / h0^2, 1 / h0^2, 1 / h_z^2) at point p (3 values).
Eigen::Matrix3d BoundaryLayerMetricAt(const BoundaryLayerMetricOptions& options, const double* p);

/// The metric at every point of a 3D mesh (packed XX, YY, ZZ, XY, YZ, XZ); InputError for a
/// mesh that is not 3D.
MetricField EvaluateBoundaryLayerMetric(const BoundaryLayerMetricOptions& options, const SimplexMesh& mesh);

/**
 * Levels 0 = z_0 < z_1 < ... < z_n = 1 of a background graded along the normal: each step is
 * `fraction` x h_z at its lower level (the last one merged into the one below when it would be
 * shorter than a quarter of that). InputError unless 0 < fraction <= 1.
 */
std::vector<double> BoundaryLayerLevels(const BoundaryLayerMetricOptions& options, double fraction);

/**
 * The exact isometric embedding of the metric in R^dim (dim >= 3): (x / h0, y / h0,
 * BoundaryLayerNormalLength(z), 0, ...) times sqrt(scale), for a metric that was multiplied by
 * `scale` (e.g. by ScaleMetricForEmbedding).
 */
Embedding BoundaryLayerIsometricEmbedding(const BoundaryLayerMetricOptions& options,
  const SimplexMesh& mesh, int dim, double scale = 1.0);

} // namespace av

#endif
