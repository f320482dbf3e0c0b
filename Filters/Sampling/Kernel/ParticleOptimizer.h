// SPDX-License-Identifier: BSD-3-Clause
// ParticleOptimizer: the iterations of the particle sampler (warm-up, then the paper's kernel)
// on sites already placed, internal to SampleParticles.
#ifndef av_ParticleOptimizer_h
#define av_ParticleOptimizer_h

#include "ParticleSampler.h"
#include "SharpFeatures.h"
#include "SimplexMesh.h"

namespace av
{
namespace sampling
{

/**
 * Runs opt.WarmupIterations projected L-BFGS iterations at the warm-up kernel, then
 * opt.Iterations at res.Sigma, on res.Sites (with res.FeatureKind / FeatureEdge, moved in
 * place), and fills the energy histories, iteration and evaluation counts, MeanNeighbors
 * and Aborted of `res`. `features`: the sharp features the line sites follow (nullptr when
 * there are none). Dispatches once on the embedding dimension (compiled for 2-6 and 8, a
 * runtime-size fallback otherwise) and the simplex dimension.
 */
void OptimizeParticles(const SimplexMesh& mesh,
  const Embedding& embedding,
  const SharpFeatures* features,
  const ParticleSamplerOptions& opt,
  ParticleSamplerResult& res);

} // namespace sampling
} // namespace av

#endif
