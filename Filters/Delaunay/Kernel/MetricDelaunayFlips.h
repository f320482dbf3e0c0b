// SPDX-License-Identifier: BSD-3-Clause
// MetricDelaunayFlips: 2-3 and 3-2 flips of a valid tet mesh towards the Delaunay criterion of
// a per-vertex metric (Borouchaki, George et al., "Delaunay mesh generation governed by metric
// specifications", 1997).
#ifndef av_MetricDelaunayFlips_h
#define av_MetricDelaunayFlips_h

#include "SimplexMesh.h"

#include <cstddef>

namespace av
{

/// Counts of FlipTowardsMetricDelaunay.
struct MetricDelaunayFlipResult
{
  std::size_t NumFlips23 = 0;
  std::size_t NumFlips32 = 0;
  std::size_t NumChecked = 0; ///< interior faces tested
  bool Capped = false;        ///< stopped at the flip budget (the metric varies: no guarantee)
};

/**
 * Flips the tets of `mesh` (AmbientDim 3, every tet positive) towards the metric Delaunay
 * criterion: an interior face abc with apexes d, e is not Delaunay when e lies inside the
 * circumsphere of abcd after mapping the five points by S, the mean of their symmetric metric
 * square roots (`metric`, one per point). Such a face is flipped 2-3 when the segment de
 * crosses it, or 3-2 (removing the edge the segment passes) when that edge has exactly three
 * tets. A flip is made only when every new tet is positive in input space with a margin (k!
 * volume above 1e-7 (sum of squared edges)^(3/2)), so the mesh stays valid and covers the same
 * domain with the same boundary faces; faces on the boundary or shared by more than two tets
 * are never flipped. At most 10 flips per tet (the criterion changes with the metric between
 * neighbors, so the flips need not terminate on their own). Points are not changed.
 */
MetricDelaunayFlipResult FlipTowardsMetricDelaunay(SimplexMesh& mesh, const MetricField& metric);

} // namespace av

#endif
