// SPDX-License-Identifier: BSD-3-Clause
// RestrictedDelaunay: the dual mesh of a restricted Voronoi diagram (paper §4.2), with the
// inverted / non-manifold elements of its back-projection counted (RestrictedDelaunayRefinement
// repairs them).
#ifndef av_RestrictedDelaunay_h
#define av_RestrictedDelaunay_h

#include "RestrictedVoronoi.h"
#include "SimplexMesh.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{

/**
 * Restricted Delaunay mesh: one triangle (tet) per Voronoi vertex strictly inside the domain
 * where 3 (4) restricted cells meet. Vertices are the sites in input space (first AmbientDim
 * coordinates of their embedded position); point ids equal site ids (unused sites stay in
 * Points but are referenced by no cell).
 */
struct RestrictedDelaunayMesh
{
  int SimplexDim = 3;
  int AmbientDim = 3;
  std::vector<double> Points;       ///< NumSites x AmbientDim
  std::vector<std::int32_t> Cells;  ///< NumCells x (SimplexDim+1), positive in the tangent frame
  std::vector<std::int32_t> CellElement; ///< input element holding the dual Voronoi vertex
  std::vector<std::uint8_t> Inverted;    ///< 1 where the input-space orientation disagrees or the cell is flat

  std::size_t NumInverted = 0;   ///< cells whose back-projection is inverted or flat
  std::size_t NumNonManifoldFaces = 0;   ///< faces shared by more than two cells
  std::size_t NumOpenInteriorFaces = 0;  ///< faces of one cell whose dual does not reach the boundary
  std::size_t NumUnusedSites = 0;        ///< sites referenced by no cell

  std::size_t NumCells() const { return Cells.size() / static_cast<std::size_t>(SimplexDim + 1); }
};

/**
 * Builds the dual of `rvd` (computed from the same mesh / embedding / sites). Each simplex is
 * oriented positively in the frame of the element that holds its Voronoi vertex (sites
 * projected onto that element's affine hull in R^Dim) and flagged inverted when, mapped back
 * to input space, its orientation in the same element's input frame is not positive or it is
 * flat (k! volume below 1e-7 (sum of squared edge lengths)^(k/2), both in that frame), or,
 * on a surface, flipped: its normal opposes the sum of the normals of the input triangles that
 * hold its three sites (a fold across a strongly curved region that one element's frame misses).
 * No repair here: RepairRestrictedDelaunay (RestrictedDelaunayRefinement.h) inserts sites.
 */
RestrictedDelaunayMesh ComputeRestrictedDelaunay(const SimplexMesh& mesh,
  const Embedding& embedding, const SiteSet& sites, const RestrictedVoronoiDiagram& rvd);

/**
 * Checks the input of a site move on a restricted Delaunay mesh (ODT smoothing, sliver
 * perturbation): site arrays against the embedding dimension, the embedding against the mesh,
 * site cell ids, and the Delaunay cells' site ids. Throws InputError("<caller>: ...").
 */
void ValidateSiteMoveInput(const char* caller, const SimplexMesh& mesh,
  const Embedding& embedding, const SiteSet& sites, const RestrictedDelaunayMesh& rdt);

} // namespace av

#endif
