// SPDX-License-Identifier: BSD-3-Clause
// GaussianEnergyInternal: the particle sampler's shifted Gaussian repulsion energy and its
// gradients projected onto each particle's feasible directions.
#ifndef av_GaussianEnergyInternal_h
#define av_GaussianEnergyInternal_h

#include "GaussianKernel.h"
#include "MeshParticlesInternal.h"
#include "ParticleNeighborListsInternal.h"
#include "SamplerDimensions.h"

#include <Eigen/Dense>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace av
{
namespace sampling
{

/**
 * E = sum_{p<q, |x_p - x_q| < c} [exp(-|x_p - x_q|^2 / (4 sigma^2)) - exp(-c^2 / (4 sigma^2))]
 * over the inner neighbor lists. The kernel is shifted by its value at the cutoff, so the
 * energy is continuous in the positions and does not depend on the neighbor lists.
 */
template <int D, int K>
class GaussianEnergy
{
  using Vec = PointVector<D>;

public:
  GaussianEnergy(MeshParticles<D, K>& particles, ParticleNeighborLists<D>& lists, int dim)
    : Particles(particles)
    , Lists(lists)
    , Dim(dim)
  {
  }

  /// n particles; kind[p]: 0 free, 1 on a feature line, 2 corner.
  void Resize(std::size_t n, const std::int8_t* kind)
  {
    N = n;
    Kind = kind;
    PerParticle.assign(N, 0.0);
  }

  void SetKernel(double sigma, double cutoff)
  {
    Sigma = sigma;
    Cutoff = cutoff;
  }
  double KernelWidth() const { return Sigma; }
  int Evaluations() const { return NumEvaluations; }

  /// Energy (returned) and, with `grad`, projected gradients; per-particle outputs, serial sum.
  double Evaluate(const std::vector<double>& x,
    const std::vector<std::int32_t>& cells,
    const std::vector<double>& bary,
    const std::vector<std::int32_t>& edges,
    std::vector<double>* grad)
  {
    ++NumEvaluations;
    Lists.Update(x);
    const double inv4s2 = 1.0 / (4.0 * Sigma * Sigma);
    const double rc2 = Cutoff * Cutoff;
    double shift = 0.0;
    GaussianKernel(&rc2, &shift, 1, inv4s2, std::numeric_limits<double>::infinity());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, N),
      [&](const tbb::blocked_range<std::size_t>& r)
      {
        double d2[kExpChunk], w[kExpChunk];
        for (std::size_t p = r.begin(); p != r.end(); ++p)
        {
          Vec g = Vec::Zero(Dim);
          PerParticle[p] = 0.5 * PairSums(x, p, inv4s2, rc2, shift, d2, w, g);
          if (grad)
          {
            Eigen::Map<Vec> gp(grad->data() + p * static_cast<std::size_t>(Dim), Dim);
            if (Kind[p] == 0)
              gp =
                Particles.ProjectGradient(Particles.Data(p, cells[p], 0), bary.data() + 4 * p, g);
            else if (Kind[p] == 1)
            {
              double len = 0.0;
              const Vec u = Particles.EdgeDirection(edges[p], &len);
              gp = u.dot(g) * u; // along the feature line only
            }
            else
              gp.setZero(); // corners do not move
          }
        }
      });
    double sum = 0.0;
    for (double v : PerParticle)
      sum += v;
    return sum;
  }

private:
  /// Particle p's kernel sum over its inner list (returned) and its gradient g, in chunks:
  /// distances, then the kernel of the whole chunk (vectorized exp), then the sums in list
  /// order. d2, w: kExpChunk scratch values.
  double PairSums(const std::vector<double>& x,
    std::size_t p,
    double inv4s2,
    double rc2,
    double shift,
    double* d2,
    double* w,
    Vec& g) const
  {
    const Eigen::Map<const Vec> xp(x.data() + p * static_cast<std::size_t>(Dim), Dim);
    double e = 0.0;
    const std::uint32_t* list = Lists.InnerList(p);
    const std::size_t count = Lists.InnerCountOf(p);
    for (std::size_t j0 = 0; j0 < count; j0 += kExpChunk)
    {
      const std::size_t m = std::min(count - j0, kExpChunk);
      for (std::size_t j = 0; j < m; ++j)
      {
        const Eigen::Map<const Vec> xq(
          x.data() + list[j0 + j] * static_cast<std::size_t>(Dim), Dim);
        d2[j] = (xp - xq).squaredNorm();
      }
      GaussianKernel(d2, w, m, inv4s2, rc2);
      for (std::size_t j = 0; j < m; ++j)
      {
        if (d2[j] >= rc2)
          continue;
        const Eigen::Map<const Vec> xq(
          x.data() + list[j0 + j] * static_cast<std::size_t>(Dim), Dim);
        e += w[j] - shift;
        g -= (2.0 * inv4s2 * w[j]) * (xp - xq);
      }
    }
    return e;
  }

  MeshParticles<D, K>& Particles;
  ParticleNeighborLists<D>& Lists;
  const int Dim;
  std::size_t N = 0;
  const std::int8_t* Kind = nullptr; // per particle: 0 free, 1 feature line, 2 corner
  double Sigma = 1.0;
  double Cutoff = 5.0;
  int NumEvaluations = 0;
  std::vector<double> PerParticle;
};

} // namespace sampling
} // namespace av

#endif
