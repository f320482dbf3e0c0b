// SPDX-License-Identifier: BSD-3-Clause
// OdtSmoothing: optimal-Delaunay-triangulation (ODT) smoothing of the sites of a restricted
// Delaunay mesh in the embedding (not in the paper; see Filters/Delaunay/README.md). The caller
// recomputes the RVD / RDT of the moved sites.
#ifndef av_OdtSmoothing_h
#define av_OdtSmoothing_h

#include "RestrictedDelaunay.h"
#include "RestrictedVoronoi.h"
#include "SimplexMesh.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{

/// Options of SmoothSitesOdt.
struct OdtSmoothingOptions
{
  /// Fraction of the way to the ODT position that a site moves (1 = the full ODT step).
  double StepFraction = 1.0;
  /// ODT steps on the connectivity of the given mesh (the moved positions are re-used).
  int Iterations = 1;
  /// ComputeElementAdjacency(mesh) if the caller has it (nullptr: computed here).
  const std::vector<std::int32_t>* ElementAdjacency = nullptr;
  /// Per site, nonzero: never moves (the sampler's corner and feature-line sites: on a surface
  /// a crease is not the domain boundary, so nothing else keeps them on it). nullptr: none.
  const std::vector<std::uint8_t>* FixedSites = nullptr;
};

/// Output of SmoothSitesOdt.
struct OdtSmoothingResult
{
  SiteSet Sites;               ///< same count and order as the input, moved ones updated
  std::size_t NumMovedSites = 0;
  std::size_t NumFixedSites = 0; ///< sites kept: cell meets the domain boundary, or FixedSites
  double MeanMove = 0.0; ///< mean embedded displacement of the last step's moved sites (before walking)
};

/**
 * Iterations ODT steps (Chen & Xu; Alliez et al. 2005) in R^Dim: every site whose restricted
 * Voronoi cell does not meet the domain boundary moves towards the measure-weighted mean of the
 * circumcenters of its incident dual simplices (circumcenter within each simplex's affine
 * hull in R^Dim, weight its embedded measure), walking on the embedded mesh so that it stays
 * on it. That position minimizes the interpolation error of |x|^2 over the site's star, which
 * regularizes the simplices (more than a Lloyd step does). Sites on or next to the boundary,
 * sites flagged in FixedSites and sites of no simplex keep their exact values. Steps after the
 * first keep the connectivity of `rdt` (cheap: no new diagram; the caller's recomputation fixes
 * it). Deterministic. Throws InputError when sizes do not match or options are out of range.
 */
OdtSmoothingResult SmoothSitesOdt(const SimplexMesh& mesh, const Embedding& embedding,
  const SiteSet& sites, const RestrictedVoronoiDiagram& rvd, const RestrictedDelaunayMesh& rdt,
  const OdtSmoothingOptions& options = OdtSmoothingOptions());

} // namespace av

#endif
