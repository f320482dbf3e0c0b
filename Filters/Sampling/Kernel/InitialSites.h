// SPDX-License-Identifier: BSD-3-Clause
// InitialSites: the particle sampler's start (measure-proportional draws, stratified along a
// Morton order, or a best-candidate start, merged with the feature sites), internal to it.
#ifndef av_InitialSites_h
#define av_InitialSites_h

#include "FeatureSites.h"
#include "ParticleSampler.h"
#include "SimplexMesh.h"

#include <vector>

namespace av
{
namespace sampling
{

/**
 * Initial sites: cells drawn proportionally to their embedded measure `meas` (stratified along
 * a Morton order of the input-space cell centroids when options.StratifiedInitialSites; a
 * best-candidate start when options.InitialCandidates > 1), uniform barycentrics inside the
 * cell, plus the feature sites `placed`; all ordered by cell id. Writes res.Sites (sized
 * NumSites, zero coordinates), res.FeatureKind and res.FeatureEdge.
 */
void DrawInitialSites(const SimplexMesh& mesh,
  const Embedding& emb,
  const std::vector<double>& meas,
  const ParticleSamplerOptions& opt,
  const FeatureSitePlacement& placed,
  ParticleSamplerResult& res);

} // namespace sampling
} // namespace av

#endif
