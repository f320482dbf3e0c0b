// SPDX-License-Identifier: BSD-3-Clause
// ValidDualMesh: a final tet mesh that is valid by construction where the repaired restricted
// Delaunay dual is not (inverted or flat cells, faces shared by more than two cells).
#ifndef av_ValidDualMesh_h
#define av_ValidDualMesh_h

#include "MetricDelaunayFlips.h"
#include "RestrictedDelaunay.h"
#include "SimplexMesh.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{

/// Counts of MakeDualValid.
struct ValidDualResult
{
  bool Replaced = false;             ///< the dual was invalid and its cells were replaced
  std::size_t InvalidCells = 0;      ///< inverted / flat cells of the dual before
  std::size_t NonManifoldFaces = 0;  ///< its faces shared by more than two cells before
  std::size_t UnusedSites = 0;       ///< its sites in no cell before (holes in the mesh)
  std::size_t TargetCells = 0;       ///< valid cells of the dual away from its bad ones (targets)
  std::size_t KeptCells = 0;         ///< tets of the result that are target cells
  bool Constrained = false;          ///< TetGen kept the targets' faces (else plain Delaunay)
  std::size_t DelaunayCells = 0;     ///< tets of the Delaunay tetrahedralization of the sites
  std::size_t OutsideCells = 0;      ///< of those, removed: centroid outside the input domain
  std::size_t FlatBoundaryCells = 0; ///< removed: flat, on the boundary of what is kept
  MetricDelaunayFlipResult Flips;    ///< towards the metric's Delaunay criterion
  std::size_t BoundarySlivers = 0;   ///< boundary tets below 10 deg in the metric, peeled after
  double VolumeBeforePeel = 0.0;     ///< of the flipped mesh, before the sliver peel
  double PeeledVolume = 0.0;         ///< what the peel removed (at most 0.2 % of it)
};

/**
 * Recounts the cells of a final dual whose cells were changed (improved or replaced):
 * Inverted (the signed input-space measure not above 1e-7 (sum of squared edge lengths)^(k/2),
 * the flat rule of ComputeRestrictedDelaunay; on a surface (`input` triangles in 3D) also a
 * triangle whose normal opposes the sum of the normals of the input triangles of its sites),
 * NumInverted, CellElement (the element of each cell's first site), NumNonManifoldFaces and
 * NumUnusedSites (NumOpenInteriorFaces is left).
 */
void RecountFinalDual(const SimplexMesh& input, RestrictedDelaunayMesh& rdt, const SiteSet& sites);

/// Sites a dual may leave out (in no cell) before it counts as holed: a fraction of them.
/// A valid dual uses every site; the restricted Delaunay dual drops a few where four Voronoi
/// cells never meet inside the domain (cube3: 4 of 5600), but a domain thinner than the cells
/// drops whole layers (the CalculiX rotor: 1283 of 3000 sites, 31 % of the volume uncovered).
constexpr double kMaxUnusedSiteFraction = 0.01;

/// Whether MakeDualValid replaces the dual: inverted or flat cells, non-manifold faces, or
/// more than kMaxUnusedSiteFraction of the sites in no cell.
bool DualNeedsReplacement(const RestrictedDelaunayMesh& rdt);

/**
 * When `rdt` (tets of a volume mesh, AmbientDim 3) has inverted or flat cells, non-manifold
 * faces or holes (DualNeedsReplacement), replaces its cells by a mesh of the same sites that is
 * valid by construction: the Delaunay tetrahedralization of the sites' input positions mapped by
 * the mean of the sites' metric square roots, each scaled to determinant 1 (TetGen, no new points;
 * the plain Euclidean one without `siteMetric`; one per body of the input, LabelBodies, so that no
 * tet joins two parts of a contact assembly), without the tets whose centroid lies outside the
 * input domain (a walk in `mesh` from the elements of the tet's sites, `adjacency` as from
 * ComputeElementAdjacency), then without the flat tets or nearly flat tets on the boundary of what
 * is left (peeled until none is), then, with `siteMetric` (one per site; nullptr: none), flipped
 * towards the metric's Delaunay criterion (FlipTowardsMetricDelaunay with the dual's valid cells
 * away from its bad ones as targets: those are never flipped away and flips that create them are
 * made, so the result keeps the restricted Delaunay dual wherever it is valid and reachable by 2-3
 * / 3-2 flips), and rid of the boundary tets below 10 deg in the metric whose vertices are all on
 * the boundary and in another tet (worst first, at most 0.2 % of the volume). Every tet of it is
 * positive and every face is shared by at most two: no inverted cell (but an interior flat one,
 * rare) and no non-manifold face. The mesh improvement (FinalMeshImprovement) then works on its
 * worst elements. A valid dual (and any other kind of mesh) is left as it is. Recounts `rdt`
 * (RecountFinalDual) when replaced, and sets NumOpenInteriorFaces to 0: a cell not dual to the RVD
 * has no Voronoi face to compare with.
 */
ValidDualResult MakeDualValid(const SimplexMesh& mesh, const std::vector<std::int32_t>& adjacency,
  const SiteSet& sites, const MetricField* siteMetric, RestrictedDelaunayMesh& rdt);

} // namespace av

#endif
