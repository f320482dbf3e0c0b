// SPDX-License-Identifier: BSD-3-Clause
// FinalMeshImprovement: runs ImproveMesh on the meshing pipeline's final dual mesh in the metric
// interpolated at its sites, and keeps the moved sites located on the input mesh.
#ifndef av_FinalMeshImprovement_h
#define av_FinalMeshImprovement_h

#include "MeshImprovement.h"
#include "RestrictedDelaunayRefinement.h"
#include "SharpFeatures.h"

#include <cstdint>
#include <vector>

namespace av
{

/**
 * Improves `repaired.Delaunay` in place (MeshImprovement.h) against `metric` (per vertex of
 * `mesh`) interpolated at the sites. A vertex move is accepted only where its new position lies
 * in an element of `mesh` (a walk from the site's element in input space, over `adjacency` as
 * from ComputeElementAdjacency); the site then gets that element, its barycentric coordinates
 * and the interpolated embedding, and moved[site] is set (for the first moved.size() sites).
 * Sites flagged in `fixedSites` (nullptr: none; the input sites only) never move. The dual's
 * cells are replaced: CellElement becomes the element of each cell's first site, Inverted and
 * NumInverted are recounted from the signed input-space measure (flat: as in
 * ComputeRestrictedDelaunay). On a surface with `features` (DetectSharpFeatures of `mesh`), the
 * sites flagged FeatureLinePoint that lie on one of its lines slide along that line (between
 * the corners and junctions that end it) in the smoothing.
 */
MeshImprovementResult ImproveFinalMesh(const SimplexMesh& mesh,
  const Embedding& embedding,
  const std::vector<std::int32_t>& adjacency,
  const MetricField& metric,
  const std::vector<std::uint8_t>* fixedSites,
  const MeshImprovementOptions& options,
  DelaunayRepairResult& repaired,
  std::vector<std::uint8_t>& moved,
  const SharpFeatures* features = nullptr);

} // namespace av

#endif
