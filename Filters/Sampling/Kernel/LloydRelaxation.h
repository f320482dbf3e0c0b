// SPDX-License-Identifier: BSD-3-Clause
// LloydRelaxation: constrained centroidal Voronoi (Lloyd) steps of sites on an embedded
// simplicial mesh. Not in the paper (§4.1 stops after the particle optimization): an optional
// post-processing that regularizes the sites and so the restricted Delaunay mesh.
#ifndef av_LloydRelaxation_h
#define av_LloydRelaxation_h

#include "SimplexMesh.h"

#include <cstddef>
#include <vector>

namespace av
{

/// Output of RelaxSitesLloyd.
struct LloydResult
{
  SiteSet Sites;              ///< relaxed sites (embedded coords, cell, barycentrics)
  std::vector<double> Energy; ///< CVT energy at the start of each iteration
  std::vector<double> MeanMove; ///< mean site displacement (R^Dim) of each iteration
  int IterationsDone = 0;
  std::size_t FixedBoundarySites = 0; ///< sites held on the boundary (keepBoundarySites)
  double Seconds = 0.0;
};

/**
 * Runs `iterations` Lloyd steps in the embedding: every site moves to the centroid (in R^Dim,
 * embedded measure) of its restricted Voronoi cell, projected back onto the embedded mesh (the
 * closest point on the elements that the cell covers, or the site's own element; the
 * projection is exact on each candidate element). Each step therefore does not increase the
 * CVT energy sum_s int_{cell s} |x - s|^2 dx. Sites with an empty cell stay put. With
 * keepBoundarySites, sites that lie on the domain boundary (barycentric 0 on a boundary facet)
 * do not move: a free Lloyd step pulls them half a cell inwards and uncovers the boundary.
 * Deterministic. Throws InputError (via ValidateRestrictedVoronoiInput) on bad input and
 * when iterations < 0.
 */
LloydResult RelaxSitesLloyd(const SimplexMesh& mesh, const Embedding& embedding,
  const SiteSet& sites, int iterations, bool keepBoundarySites = true);

/// CVT energy sum_s int_{RVD cell of s} |x - s|^2 dx in R^Dim (embedded measure).
double ComputeCVTEnergy(const SimplexMesh& mesh, const Embedding& embedding, const SiteSet& sites);

} // namespace av

#endif
