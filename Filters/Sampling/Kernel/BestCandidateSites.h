// SPDX-License-Identifier: BSD-3-Clause
// BestCandidateSites: the particle sampler's well-spaced start (each site the farthest of m
// measure-proportional candidates from the sites placed before), internal to the sampler.
#ifndef av_BestCandidateSites_h
#define av_BestCandidateSites_h

#include "SamplerRandom.h"
#include "SimplexMesh.h"

#include <cstddef>
#include <vector>

namespace av
{
namespace sampling
{

/**
 * Best-candidate start: count - placed.NumSites() sites placed one at a time, each the farthest
 * (in R^Dim) from the sites already placed (`placed` first) among m = `candidates` candidates
 * drawn proportionally to the embedded measure `meas`; a candidate with no site within
 * r = (|mesh| / count)^{1/k} is taken at once (dart throwing with a fallback; r 0.75 / 0.9 /
 * 1.2 spacings gave starts as good or worse). Neighbors come from a grid on the 3 principal
 * coordinates of the embedded vertices (a projection only shortens distances: no site within r
 * is missed). Returns the new sites in cell order (ties keep placement order). Serial:
 * deterministic for the state of `rng`.
 */
SiteSet BestCandidateSites(const SimplexMesh& mesh,
  const Embedding& emb,
  const std::vector<double>& meas,
  std::size_t count,
  int candidates,
  Rng& rng,
  const SiteSet& placed);

} // namespace sampling
} // namespace av

#endif
