// SPDX-License-Identifier: BSD-3-Clause
// MetricDelaunayFlips: 2-3 and 3-2 flips of a valid tet mesh towards the Delaunay criterion of
// a per-vertex metric (Borouchaki, George et al., "Delaunay mesh generation governed by metric
// specifications", 1997).
#ifndef av_MetricDelaunayFlips_h
#define av_MetricDelaunayFlips_h

#include "SimplexMesh.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{

/// Counts of FlipTowardsMetricDelaunay.
struct MetricDelaunayFlipResult
{
  std::size_t NumFlips23 = 0;
  std::size_t NumFlips32 = 0;
  std::size_t NumChecked = 0;     ///< interior faces tested
  std::size_t NumTargetFlips = 0; ///< of the flips, made to create a target tet
  bool Capped = false;            ///< stopped at the flip budget (the metric varies: no guarantee)
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
 *
 * With target tets (`targets`: vertex quadruples of the same points, in any order;
 * MakeDualValid gives the valid cells of the restricted Delaunay dual): a target tet of the
 * mesh is never flipped away, and a valid flip that creates a target tet is made even across a
 * face that is metric Delaunay. The number of target tets in the mesh never falls, so the mesh
 * moves towards the targets wherever they form a valid mesh.
 */
MetricDelaunayFlipResult FlipTowardsMetricDelaunay(SimplexMesh& mesh,
  const MetricField& metric,
  const std::vector<std::array<std::int32_t, 4>>& targets = {});

} // namespace av

#endif
