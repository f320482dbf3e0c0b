// SPDX-License-Identifier: BSD-3-Clause
// MetricScaling: the global constant c of paper §6 that makes every used metric eigenvalue >= 1
// before the embedding (extra coordinates can only lengthen edges). VTK-free.
#ifndef av_MetricScaling_h
#define av_MetricScaling_h

#include "SimplexMesh.h"

namespace av
{

/// What ScaleMetricForEmbedding found and did.
struct MetricScaling
{
  double SmallestEigenvalue = 0.0; ///< smallest eigenvalue over the field, before scaling
  double Scale = 1.0;              ///< c, already applied to the field (1: left as it was)
};

/**
 * Prepares `metric` (one tensor per vertex of `mesh`) for the embedding. Domains (SimplexDim ==
 * AmbientDim; a 2D domain reads XX, YY, XY only) need a positive definite field; when its
 * smallest eigenvalue λ_min over the field is below 1 the whole field is multiplied by
 * c = 1 / λ_min, so that the smallest eigenvalue becomes 1. Surface metrics (triangles in 3D,
 * typically rank 2 with a zero eigenvalue along the normal) are left unscaled (c = 1).
 *
 * Throws InputError when a domain metric is not positive definite, or when it needs scaling
 * and `allowScaling` is false.
 */
MetricScaling ScaleMetricForEmbedding(
  const SimplexMesh& mesh, MetricField& metric, bool allowScaling = true);

} // namespace av

#endif
