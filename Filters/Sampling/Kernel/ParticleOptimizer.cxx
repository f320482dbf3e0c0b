// SPDX-License-Identifier: BSD-3-Clause
// ParticleOptimizer: the sampler's iteration schedule over its parts (mesh particles, neighbor
// lists, energy, L-BFGS), instantiated for the compiled embedding dimensions.
#include "ParticleOptimizer.h"

#include "FaceNeighbors.h"
#include "GaussianEnergyInternal.h"
#include "MeshParticlesInternal.h"
#include "ParticleNeighborListsInternal.h"
#include "ProjectedLbfgsInternal.h"

#include <Eigen/Core>

namespace av
{
namespace sampling
{
namespace
{

/// The optimizer for a compile-time embedding dimension D (Eigen::Dynamic: runtime, stack
/// storage up to kMaxDim) and simplex dimension K.
template <int D, int K>
class ParticleOptimizer
{
public:
  ParticleOptimizer(const SimplexMesh& mesh,
    const Embedding& emb,
    const VertexCells& vc,
    const SharpFeatures* features)
    : Particles(mesh, emb, vc, features)
    , Lists(emb.Dim)
    , Energy(Particles, Lists, emb.Dim)
    , Lbfgs(Particles, Energy, emb.Dim)
  {
  }

  void Run(const ParticleSamplerOptions& opt, ParticleSamplerResult& res)
  {
    const std::size_t n = res.Sites.NumSites();
    const std::int8_t* kind = res.FeatureKind.data();
    Lists.Resize(n);
    Energy.Resize(n, kind);
    Particles.Resize(n);
    Lbfgs.Resize(n, kind);
    const int total = opt.WarmupIterations + opt.Iterations;
    int done = 0;
    // Warm-up at the narrower kernel (harder repulsion: the nearest-neighbor distances even
    // out faster), then the paper's kernel.
    if (opt.WarmupIterations > 0)
    {
      SetKernel(res.Sigma * opt.WarmupKernelWidthFactor / opt.KernelWidthFactor, opt);
      res.WarmupIterationsDone =
        Lbfgs.Minimize(opt, opt.WarmupIterations, done, total, res.WarmupEnergy, res);
      done += res.WarmupIterationsDone;
    }
    SetKernel(res.Sigma, opt);
    if (!res.Aborted)
      res.IterationsDone = Lbfgs.Minimize(opt, opt.Iterations, done, total, res.Energy, res);
    else
      res.Energy.push_back(Energy.Evaluate(
        res.Sites.Coords, res.Sites.CellIds, res.Sites.Bary, res.FeatureEdge, nullptr));
    res.MeanNeighbors = Lists.MeanNeighbors(res.Sites.Coords);
    res.EnergyEvaluations = Energy.Evaluations();
    res.NeighborRebuilds = Lists.OuterBuilds();
    if (opt.Progress)
      opt.Progress(1.0);
  }

private:
  /// Kernel width sigma, cutoff c sigma, list skins; forces a list rebuild.
  void SetKernel(double sigma, const ParticleSamplerOptions& opt)
  {
    // Skins tuned on cube2 (5000 sites): a thin inner skin keeps the energy loops short
    // (the inner lists are rebuilt most iterations, cheaply), the outer one makes grid
    // builds rare (about one in 9 evaluations).
    Energy.SetKernel(sigma, opt.NeighborCutoff * sigma);
    Lists.SetRadii(opt.NeighborCutoff * sigma, 0.5 * sigma, 2.0 * sigma);
  }

  MeshParticles<D, K> Particles;
  ParticleNeighborLists<D> Lists;
  GaussianEnergy<D, K> Energy;
  ProjectedLbfgs<D, K> Lbfgs;
};

template <int D>
void RunDim(const SimplexMesh& mesh,
  const Embedding& emb,
  const VertexCells& vc,
  const SharpFeatures* features,
  const ParticleSamplerOptions& opt,
  ParticleSamplerResult& res)
{
  if (mesh.SimplexDim == 2)
    ParticleOptimizer<D, 2>(mesh, emb, vc, features).Run(opt, res);
  else
    ParticleOptimizer<D, 3>(mesh, emb, vc, features).Run(opt, res);
}

} // namespace

void OptimizeParticles(const SimplexMesh& mesh,
  const Embedding& embedding,
  const SharpFeatures* features,
  const ParticleSamplerOptions& opt,
  ParticleSamplerResult& res)
{
  const VertexCells vc = BuildVertexCells(mesh);
  switch (embedding.Dim)
  {
    case 2:
      RunDim<2>(mesh, embedding, vc, features, opt, res);
      break;
    case 3:
      RunDim<3>(mesh, embedding, vc, features, opt, res);
      break;
    case 4:
      RunDim<4>(mesh, embedding, vc, features, opt, res);
      break;
    case 5:
      RunDim<5>(mesh, embedding, vc, features, opt, res);
      break;
    case 6:
      RunDim<6>(mesh, embedding, vc, features, opt, res);
      break;
    case 8:
      RunDim<8>(mesh, embedding, vc, features, opt, res);
      break;
    default:
      RunDim<Eigen::Dynamic>(mesh, embedding, vc, features, opt, res);
      break;
  }
}

} // namespace sampling
} // namespace av
