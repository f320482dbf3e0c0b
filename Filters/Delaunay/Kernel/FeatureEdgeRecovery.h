// SPDX-License-Identifier: BSD-3-Clause
// FeatureEdgeRecovery: makes the dual triangle mesh of a surface follow its feature lines. The
// sampler keeps sites on the creases (paper §4.1), but the restricted Delaunay dual of those
// sites need not connect two sites that are consecutive along a crease: a triangle then cuts
// across the crease, and the Hausdorff distance to the input is set there (turbine: 322 of 795
// consecutive crease-site pairs unconnected). Edge flips put those edges back.
#ifndef av_FeatureEdgeRecovery_h
#define av_FeatureEdgeRecovery_h

#include "RestrictedDelaunay.h"
#include "SharpFeatures.h"
#include "SimplexMesh.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{

/**
 * The pairs of sites that are consecutive along the feature lines of the triangle surface
 * `mesh` (`features` = DetectSharpFeatures of it). A site is on a feature line when one of its
 * barycentric coordinates is exactly 0 and the other two points' edge is a feature edge (the
 * sampler puts its feature-line sites there), and at a feature vertex when two are 0 (corners).
 * From each such site the lines are followed in both directions, through feature vertices
 * where exactly two feature edges meet, to the next site; a line that reaches a junction or an
 * end with no site there stops. Each pair once, smaller id first, sorted.
 */
std::vector<std::array<std::int32_t, 2>> ConsecutiveFeatureSites(
  const SimplexMesh& mesh, const SharpFeatures& features, const SiteSet& sites);

/// Counts of RecoverFeatureEdges.
struct FeatureEdgeRecoveryResult
{
  std::size_t Required = 0;      ///< pairs asked for
  std::size_t Present = 0;       ///< of those, edges of the mesh before
  std::size_t Recovered = 0;     ///< made edges by a flip
  std::size_t Missing = 0;       ///< still not edges after
};

/**
 * Flips edges of the triangle mesh `rdt` (vertices = sites, on the surface `mesh`) so that the
 * `required` site pairs become edges: where a pair (a, b) are the two opposite vertices of the
 * two triangles of an edge (c, d), the edge is replaced by (a, b). A flip is made only when
 * both new triangles face the same way as the input surface at their third vertex (the input
 * triangle holding that site), as the two triangles they replace and as the input triangle
 * nearest their centroid, are not degenerate, the edge (c, d) is manifold and not required
 * itself, and (a, b) is not an edge already. Repeats over the missing pairs while flips happen
 * (at most `maxPasses` passes). Cell orientation is kept; the caller recounts the per-cell data
 * (RecountFinalDual). Surfaces only (SimplexDim 2 in 3D); other meshes are left unchanged.
 */
FeatureEdgeRecoveryResult RecoverFeatureEdges(const SimplexMesh& mesh,
  const SiteSet& sites,
  const std::vector<std::array<std::int32_t, 2>>& required,
  RestrictedDelaunayMesh& rdt,
  int maxPasses = 4);

} // namespace av

#endif
