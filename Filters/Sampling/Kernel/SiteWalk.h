// SPDX-License-Identifier: BSD-3-Clause
// SiteWalk: moves a site on an embedded simplicial mesh by a displacement in R^Dim, staying on
// the mesh (shared by the sliver perturbation and the ODT smoothing of the Delaunay stage).
#ifndef av_SiteWalk_h
#define av_SiteWalk_h

#include "SimplexMesh.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{

/**
 * Walks site s of `sites` by the embedded displacement d (Dim values): d is projected onto the
 * current element's tangent space (least squares in its edge frame), the barycentric step is
 * cut where a coordinate reaches 0, and the rest continues in the neighbor across that facet
 * (`adjacency` as from ComputeElementAdjacency). The walk stops at the domain boundary (the
 * site stays on it) or after 64 element crossings. Updates the site's cell id, barycentric
 * coordinates and embedded coordinates (recomputed from the barycentrics, so the site stays
 * exactly on the mesh). Works for triangle and tet meshes.
 */
void WalkSiteOnMesh(const SimplexMesh& mesh, const Embedding& embedding,
  const std::vector<std::int32_t>& adjacency, SiteSet& sites, std::size_t s, const double* d);

} // namespace av

#endif
