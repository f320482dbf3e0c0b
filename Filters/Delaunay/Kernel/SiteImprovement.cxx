// SPDX-License-Identifier: BSD-3-Clause
// One round of ODT smoothing and sliver perturbation of restricted Delaunay sites.
#include "SiteImprovement.h"

#include <string>

namespace av
{

SiteImprovementResult ImproveSites(const SimplexMesh& mesh, const Embedding& embedding,
  const SiteSet& sites, const RestrictedVoronoiDiagram& rvd, const RestrictedDelaunayMesh& rdt,
  const SiteImprovementOptions& options)
{
  if (options.OdtIterations < 0)
    throw InputError("ImproveSites: OdtIterations must be >= 0");
  SiteImprovementResult r;
  r.Sites = sites;
  if (options.OdtIterations > 0)
  {
    OdtSmoothingOptions oo = options.Odt;
    if (!oo.ElementAdjacency)
      oo.ElementAdjacency = options.ElementAdjacency;
    oo.Iterations = options.OdtIterations;
    OdtSmoothingResult od = SmoothSitesOdt(mesh, embedding, r.Sites, rvd, rdt, oo);
    r.Sites = std::move(od.Sites);
    r.NumOdtMoved = od.NumMovedSites;
    r.NumFixedSites = od.NumFixedSites;
  }
  if (options.PerturbSlivers)
  {
    SliverPerturbationOptions so = options.Sliver;
    if (!so.ElementAdjacency)
      so.ElementAdjacency = options.ElementAdjacency;
    SliverPerturbationResult sp = PerturbSliverSites(mesh, embedding, r.Sites, rdt, so);
    r.Sites = std::move(sp.Sites);
    r.NumSlivers = sp.NumSlivers;
  }
  const std::size_t dim = static_cast<std::size_t>(embedding.Dim);
  for (std::size_t s = 0; s < sites.NumSites(); ++s)
  {
    bool same = r.Sites.CellIds[s] == sites.CellIds[s];
    for (std::size_t q = 0; q < dim && same; ++q)
      same = r.Sites.Coords[s * dim + q] == sites.Coords[s * dim + q];
    r.NumMovedSites += same ? 0 : 1;
  }
  return r;
}

} // namespace av
