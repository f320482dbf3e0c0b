// SPDX-License-Identifier: BSD-3-Clause
// SiteImprovement: one round of site moves between two restricted Voronoi diagrams: ODT
// smoothing, then the sliver perturbation (neither is in the paper; see
// Filters/Delaunay/README.md). The caller recomputes the RVD / RDT of the moved sites.
#ifndef av_SiteImprovement_h
#define av_SiteImprovement_h

#include "OdtSmoothing.h"
#include "RestrictedDelaunay.h"
#include "RestrictedVoronoi.h"
#include "SimplexMesh.h"
#include "SliverPerturbation.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{

/// Options of ImproveSites.
struct SiteImprovementOptions
{
  /// ODT steps on the given connectivity (OdtSmoothingOptions::Iterations); 0 = no ODT.
  int OdtIterations = 3;
  OdtSmoothingOptions Odt;
  /// Push the sites of slivers apart after the ODT steps (tet meshes only).
  bool PerturbSlivers = true;
  SliverPerturbationOptions Sliver;
  /// ComputeElementAdjacency(mesh), shared by both steps (nullptr: each computes it).
  const std::vector<std::int32_t>* ElementAdjacency = nullptr;
};

/// Output of ImproveSites.
struct SiteImprovementResult
{
  SiteSet Sites;                 ///< same count and order as the input
  std::size_t NumOdtMoved = 0;   ///< sites moved by the ODT steps
  std::size_t NumFixedSites = 0; ///< sites kept by the ODT steps (cell meets the boundary)
  std::size_t NumSlivers = 0;    ///< slivers found after the ODT steps
  std::size_t NumMovedSites = 0; ///< sites whose position changed in all
};

/**
 * Moves the sites of a restricted Delaunay mesh towards a better mesh, keeping them on the
 * embedded mesh: OdtIterations ODT steps (SmoothSitesOdt) on the connectivity of `rdt`, then
 * the sliver perturbation (PerturbSliverSites) of the slivers that the moved sites form with
 * the same connectivity. Both use one RVD / RDT, so a round costs one recomputation. Sites
 * that neither step moves keep their exact values. Deterministic.
 * Throws InputError on inconsistent input (see SmoothSitesOdt / PerturbSliverSites).
 */
SiteImprovementResult ImproveSites(const SimplexMesh& mesh, const Embedding& embedding,
  const SiteSet& sites, const RestrictedVoronoiDiagram& rvd, const RestrictedDelaunayMesh& rdt,
  const SiteImprovementOptions& options = SiteImprovementOptions());

} // namespace av

#endif
