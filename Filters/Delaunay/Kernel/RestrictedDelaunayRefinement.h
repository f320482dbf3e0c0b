// SPDX-License-Identifier: BSD-3-Clause
// RestrictedDelaunayRefinement: repairs inverted (and optionally non-manifold) elements of the
// restricted Delaunay mesh by inserting sites at their dual Voronoi vertices (paper §4.2).
#ifndef av_RestrictedDelaunayRefinement_h
#define av_RestrictedDelaunayRefinement_h

#include "RestrictedDelaunay.h"
#include "RestrictedVoronoi.h"
#include "SimplexMesh.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{

/// Options of RepairRestrictedDelaunay.
struct DelaunayRepairOptions
{
  /// Insertion rounds at most (0: only compute and report). Each round updates the restricted
  /// Voronoi diagram (UpdateRestrictedVoronoi: only the elements near the inserted sites are
  /// clipped again) and recomputes its dual.
  int MaxRounds = 10;
  /// Also insert at the Voronoi vertices of the cells around faces shared by more than two
  /// cells (the dual is then a manifold where it converges). On by default: a non-manifold
  /// dual is invalid (surfaces: holes and pinched edges; volumes: the valid-dual fallback).
  bool RepairNonManifold = true;
  /// A candidate closer than this fraction of its circumradius (embedding distance) to a
  /// candidate accepted in the same round is skipped: nearly coincident Voronoi vertices
  /// (almost co-spherical sites) would otherwise give two sites at almost the same place.
  double MinDistanceFraction = 0.25;
  /// Stop after this many rounds in a row that do not lower the fewest bad elements seen so
  /// far (fewest inverted, then, with RepairNonManifold, fewest non-manifold faces; those are
  /// repaired only once no cell is inverted), and return that best state: on a poor embedding insertions can create more inverted
  /// elements than they remove (the sphere-cos preset: 283 -> 523 -> 765 ...).
  int StallRounds = 2;
  /// Options of every restricted Voronoi computation (ElementBegin/End must be the defaults).
  /// Default: no geometry (the dual needs only the Voronoi vertex records).
  RestrictedVoronoiOptions Voronoi = [] {
    RestrictedVoronoiOptions o;
    o.ComputeGeometry = false;
    return o;
  }();
};

/// What RepairRestrictedDelaunay returns: the final sites and the diagram / dual of them.
struct DelaunayRepairResult
{
  SiteSet Sites;                     ///< input sites unchanged (ids 0..n-1), then inserted ones
  RestrictedVoronoiDiagram Voronoi;  ///< of Sites, with the given options
  RestrictedDelaunayMesh Delaunay;   ///< of Sites (Points: all sites, input space)
  std::size_t NumInputSites = 0;
  std::size_t NumInserted = 0;       ///< Sites.NumSites() - NumInputSites
  std::size_t NumSkipped = 0;        ///< candidates dropped (near another one / not solvable)
  int Rounds = 0;                    ///< insertion rounds done
  std::size_t InitialInverted = 0;   ///< inverted elements before any insertion
  std::size_t InitialNonManifoldFaces = 0;
  std::vector<std::size_t> InsertedPerRound;
  /// Inverted elements after each RDT, also of the rounds a stall discarded.
  std::vector<std::size_t> InvertedPerRound;
  /// No inverted element left (and no non-manifold face when RepairNonManifold).
  bool Converged = false;
  /// The insertions stopped lowering the bad count (StallRounds): the returned state is the
  /// one with the fewest bad elements, the later rounds' sites are dropped.
  bool Stalled = false;
};

/**
 * The Voronoi vertex dual to a restricted Delaunay simplex: the point of `element` (in its
 * embedded affine hull) equidistant in R^Dim from the SimplexDim+1 sites `siteIds`, i.e. the
 * circumcenter of the simplex restricted to the embedded domain (what Delaunay refinement
 * inserts). Writes its barycentric coordinates in `element` (4 values, unused = 0) and the
 * squared distance to the sites; false when the system is singular or the point lies outside
 * the element by more than `tolerance` in barycentric coordinates (then clamped otherwise).
 */
bool ComputeDualVoronoiVertex(const SimplexMesh& mesh, const Embedding& embedding,
  const SiteSet& sites, const std::int32_t* siteIds, std::int32_t element, double bary[4],
  double& radius2, double tolerance = 1e-6);

/**
 * Repairs the restricted Delaunay mesh of `sites` (paper §4.2, "inserts additional points"):
 * loop { RVD; RDT; stop when no element is inverted (and, with RepairNonManifold, no face is
 * non-manifold) or after MaxRounds; insert one site at the Voronoi vertex dual to each bad
 * element }. This is Delaunay refinement by circumcenter insertion measured in the embedding,
 * where the metric is Euclidean, as in Rouxel-Labbé et al. 2016: the new site lies inside the
 * bad simplex's empty circumball, so that simplex disappears, and every new site is at least
 * half the longest edge of its simplex away from all sites. Deterministic (candidates in cell
 * order). Throws InputError as ComputeRestrictedVoronoi.
 */
DelaunayRepairResult RepairRestrictedDelaunay(const SimplexMesh& mesh, const Embedding& embedding,
  const SiteSet& sites, const DelaunayRepairOptions& options = DelaunayRepairOptions());

/**
 * Same, starting from the diagram and dual of `sites` that the caller already computed (with
 * options.Voronoi; moved in, so round 0 is not recomputed). Throws InputError when they do not
 * belong to `sites`.
 */
DelaunayRepairResult RepairRestrictedDelaunay(const SimplexMesh& mesh, const Embedding& embedding,
  const SiteSet& sites, RestrictedVoronoiDiagram voronoi, RestrictedDelaunayMesh delaunay,
  const DelaunayRepairOptions& options = DelaunayRepairOptions());

/// Cells of `rdt` that have a face shared by more than two cells (1 = such a cell).
std::vector<std::uint8_t> NonManifoldCells(const RestrictedDelaunayMesh& rdt);

} // namespace av

#endif
