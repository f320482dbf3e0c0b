// SPDX-License-Identifier: BSD-3-Clause
// BoundaryNotchClosure: makes the boundary of a surface's dual mesh follow the input's open
// boundary. A site just inside the boundary whose restricted Voronoi cell reaches the boundary
// between two boundary sites a and c puts itself on the dual's boundary: the boundary runs
// a -> b -> c and the input strip between the chord a-c and b is left uncovered (mushroom, 2000
// sites: 12 of 93 boundary vertices, a sampled Hausdorff distance of 1.15 % of the diagonal
// where the vertices alone give 0.23 %). The triangle (a, c, b) closes such a notch.
#ifndef av_BoundaryNotchClosure_h
#define av_BoundaryNotchClosure_h

#include "RestrictedDelaunay.h"
#include "SimplexMesh.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{

/**
 * Per site, 1 where it lies on the open boundary of the triangle surface `mesh`: on an edge
 * without a neighbour in `adjacency` (ComputeElementAdjacency), or at a vertex of such an edge
 * (its barycentric coordinates within `tolerance` of 0 or 1). The sampler puts its boundary
 * sites there exactly; the default also takes the sites it leaves within 1e-3 of an element's
 * size (mushroom: 9, 1e-6 to 1e-5 from the rim), where a notch would be a needle and the
 * distance to the input nil. All 0 for other meshes.
 */
std::vector<std::uint8_t> SitesOnOpenBoundary(const SimplexMesh& mesh,
  const std::vector<std::int32_t>& adjacency,
  const SiteSet& sites,
  double tolerance = 1e-3);

/// Counts of CloseBoundaryNotches.
struct BoundaryNotchResult
{
  std::size_t Notches = 0; ///< boundary vertices of the dual off the input's boundary, before
  std::size_t Closed = 0;  ///< triangles added
  std::size_t Left = 0;    ///< boundary vertices still off the input's boundary after
};

/**
 * Closes the notches of the boundary of the triangle mesh `rdt` (vertices = sites, on the
 * surface `mesh`): while a boundary vertex b with `onBoundary[b]` == 0 has exactly one boundary
 * edge in and one out, a -> b -> c, the triangle (a, c, b) is added when a != c, the edge a-c is
 * not in the mesh yet, and the triangle is not degenerate and faces the way of the two
 * triangles on a-b and b-c, of the input triangles holding a, b and c, and of the input triangle
 * nearest its centroid (an ear over a convex corner at b would fold back over b's triangles).
 * b is then inside; a and c are tried again when they are off the boundary too (a deeper
 * notch). Cell orientation is kept; the caller recounts the per-cell data (RecountFinalDual).
 * Surfaces only (SimplexDim 2 in 3D), and only when some site is on the boundary (none: a
 * closed surface, whose dual's holes are the repair's); other meshes are left unchanged.
 */
BoundaryNotchResult CloseBoundaryNotches(const SimplexMesh& mesh,
  const SiteSet& sites,
  const std::vector<std::uint8_t>& onBoundary,
  RestrictedDelaunayMesh& rdt);

} // namespace av

#endif
