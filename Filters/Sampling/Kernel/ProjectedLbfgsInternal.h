// SPDX-License-Identifier: BSD-3-Clause
// ProjectedLbfgsInternal: the particle sampler's minimizer: L-BFGS on projected gradients, a
// per-particle trust region, moves walked on the mesh and a backtracking line search.
#ifndef av_ProjectedLbfgsInternal_h
#define av_ProjectedLbfgsInternal_h

#include "FixedBlockSumsInternal.h"
#include "GaussianEnergyInternal.h"
#include "MeshParticlesInternal.h"
#include "ParticleSampler.h"
#include "SamplerDimensions.h"

#include <Eigen/Dense>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <utility>
#include <vector>

namespace av
{
namespace sampling
{

/**
 * Projected L-BFGS (own two-loop recursion: LBFGS++'s line search cannot be combined with a
 * projection) of the GaussianEnergy of the particles. All vector work runs in fixed blocks
 * (FixedBlockSums): the same result for any number of threads.
 */
template <int D, int K>
class ProjectedLbfgs
{
  using Vec = PointVector<D>;
  using CellData = typename MeshParticles<D, K>::CellData;

public:
  ProjectedLbfgs(MeshParticles<D, K>& particles, GaussianEnergy<D, K>& energy, int dim)
    : Particles(particles)
    , Energy(energy)
    , Dim(dim)
  {
  }

  /// n particles; kind[p]: 0 free, 1 on a feature line, 2 corner.
  void Resize(std::size_t n, const std::int8_t* kind)
  {
    N = n;
    Kind = kind;
  }

  /**
   * Projected L-BFGS on the sites in res.Sites at the energy's current kernel: at most
   * `iterations` iterations, energies appended to `energyOut` (the start value first). `done`
   * / `total` scale the progress callback. Returns the iterations done.
   */
  int Minimize(const ParticleSamplerOptions& opt,
    int iterations,
    int done,
    int total,
    std::vector<double>& energyOut,
    ParticleSamplerResult& res)
  {
    Reset(res);
    double energy =
      Energy.Evaluate(res.Sites.Coords, res.Sites.CellIds, res.Sites.Bary, res.FeatureEdge, &G);
    energyOut.push_back(energy);
    int failures = 0, itDone = 0;
    for (int it = 0; it < iterations; ++it)
    {
      if (opt.Progress && !opt.Progress(static_cast<double>(done + it) / total))
      {
        res.Aborted = true;
        break;
      }
      const std::size_t nh = Hist.size();
      if (!(SearchDirection() < 0.0) && !SteepestDescent(nh))
        break;
      LimitSteps();
      double trialEnergy = energy;
      if (!LineSearch(res, energy, trialEnergy))
      {
        energyOut.push_back(energy);
        itDone = it + 1;
        if (Hist.empty() || ++failures >= 2)
          break; // converged as far as the line search can tell
        ClearHistory();
        continue;
      }
      failures = 0;
      StorePair(res.Sites.Coords, opt.History);
      res.Sites.Coords.swap(Xt);
      G.swap(Gt);
      res.Sites.Bary.swap(Bt);
      res.Sites.CellIds.swap(Ct);
      res.FeatureEdge.swap(Et);
      energy = trialEnergy;
      energyOut.push_back(energy);
      itDone = it + 1;
    }
    return itDone;
  }

private:
  struct Pair
  {
    Eigen::VectorXd S, Y;
    double Sy = 0.0, Yy = 0.0; // s.y and |y|^2, kept from the acceptance test
  };

  /// Work vectors for the sites of `res`, the history emptied.
  void Reset(const ParticleSamplerResult& res)
  {
    NumValues = N * static_cast<std::size_t>(Dim);
    G.assign(NumValues, 0.0);
    Xt.assign(NumValues, 0.0);
    Gt.assign(NumValues, 0.0);
    Bt.assign(res.Sites.Bary.size(), 0.0);
    Ct.assign(N, 0);
    Et = res.FeatureEdge;
    Dir.resize(static_cast<Eigen::Index>(NumValues));
    Hist.clear();
    Spare.clear();
  }

  /**
   * Dir = -H g by the two-loop recursion over the history, each update of Dir fused with the
   * next dot product (pending: Dir = ps Dir + pa px, applied in the next pass). Returns g . Dir
   * (0 without history: Dir is then left as it is).
   */
  double SearchDirection()
  {
    double* d = Dir.data();
    const std::size_t nh = Hist.size();
    Alpha.assign(nh, 0.0);
    double ps = 0.0, pa = -1.0;
    const double* px = G.data();
    if (nh == 0)
      return 0.0;
    for (std::size_t h = nh; h-- > 0;)
    {
      Alpha[h] = Sums.ScaleAddDot(NumValues, ps, pa, px, d, Hist[h].S.data()) / Hist[h].Sy;
      ps = 1.0;
      pa = -Alpha[h];
      px = Hist[h].Y.data();
    }
    const double gamma = Hist.back().Sy / Hist.back().Yy;
    ps = gamma;
    pa *= gamma;
    for (std::size_t h = 0; h < nh; ++h)
    {
      const double beta = Sums.ScaleAddDot(NumValues, ps, pa, px, d, Hist[h].Y.data()) / Hist[h].Sy;
      ps = 1.0;
      pa = Alpha[h] - beta;
      px = Hist[h].S.data();
    }
    return Sums.ScaleAddDot(NumValues, ps, pa, px, d, G.data());
  }

  /// First step, or not a descent direction: steepest descent moving the average particle by
  /// sigma / 2 (the history dropped). False when there is nothing to descend (g = 0 and no
  /// history before).
  bool SteepestDescent(std::size_t nh)
  {
    if (nh > 0)
      ClearHistory();
    const double rms = std::sqrt(
      Sums.ScaleAddDot(NumValues, 1.0, 0.0, nullptr, G.data(), G.data()) / static_cast<double>(N));
    if (rms <= 0.0 && nh == 0)
      return false;
    Sums.ScaleAddDot(NumValues,
      0.0,
      -0.5 * Energy.KernelWidth() / std::max(rms, 1e-300),
      G.data(),
      Dir.data(),
      nullptr);
    return true;
  }

  /// Trust region per particle: no particle jumps more than one sigma per step.
  void LimitSteps()
  {
    const double sigma = Energy.KernelWidth();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, N),
      [&](const tbb::blocked_range<std::size_t>& r)
      {
        for (std::size_t p = r.begin(); p != r.end(); ++p)
        {
          auto dp = Dir.segment(static_cast<Eigen::Index>(p) * Dim, Dim);
          const double len = dp.norm();
          if (len > sigma)
            dp *= sigma / len;
        }
      });
  }

  /// Backtracking (Armijo) line search along Dir, up to 12 halvings; on success the trial
  /// state (Xt, Gt, Bt, Ct, Et) holds the accepted step and trialEnergy its energy.
  bool LineSearch(ParticleSamplerResult& res, double energy, double& trialEnergy)
  {
    const std::vector<double>& x = res.Sites.Coords;
    bool accepted = false;
    double step = 1.0;
    for (int ls = 0; ls < 12 && !accepted; ++ls, step *= 0.5)
    {
      TrialMove(res, step);
      trialEnergy = Energy.Evaluate(Xt, Ct, Bt, Et, &Gt);
      const double slope = Sums.Sum<1>(NumValues,
        [&](std::size_t i0, std::size_t i1, double* out)
        {
          double acc[4] = { 0.0, 0.0, 0.0, 0.0 };
          std::size_t i = i0;
          for (; i + 4 <= i1; i += 4)
            for (std::size_t k = 0; k < 4; ++k)
              acc[k] += G[i + k] * (Xt[i + k] - x[i + k]);
          for (; i < i1; ++i)
            acc[0] += G[i] * (Xt[i] - x[i]);
          out[0] = (acc[0] + acc[1]) + (acc[2] + acc[3]);
        })[0];
      accepted = trialEnergy <= energy + 1e-4 * slope && trialEnergy < energy;
    }
    return accepted;
  }

  /// Trial state: every particle moved by step * Dir from the accepted state (walked on the
  /// mesh, along its feature line, or not at all for corners).
  void TrialMove(const ParticleSamplerResult& res, double step)
  {
    const std::vector<std::int32_t>& cells = res.Sites.CellIds;
    const std::vector<double>& bary = res.Sites.Bary;
    const std::vector<std::int32_t>& edges = res.FeatureEdge;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, N),
      [&](const tbb::blocked_range<std::size_t>& r)
      {
        for (std::size_t p = r.begin(); p != r.end(); ++p)
        {
          std::int32_t c = cells[p];
          double* b = Bt.data() + 4 * p;
          std::copy_n(bary.data() + 4 * p, 4, b);
          const Vec d = step * Vec(Dir.segment(static_cast<Eigen::Index>(p) * Dim, Dim));
          Et[p] = edges[p];
          const CellData& cd = Kind[p] == 0
            ? Particles.Walk(p, c, b, d)
            : (Kind[p] == 1 ? Particles.WalkLine(p, c, b, Et[p], d) : Particles.Data(p, c, 0));
          Ct[p] = c;
          Eigen::Map<Vec>(Xt.data() + p * static_cast<std::size_t>(Dim), Dim) =
            Particles.Position(cd, b);
        }
      });
  }

  /// Appends the pair (s, y) = (Xt - x, Gt - G) of an accepted step to the history when it
  /// keeps the inverse Hessian estimate positive definite (s.y > 1e-10 |y|^2); at most
  /// `history` pairs. Storage of dropped pairs is reused (no 2 x nd allocation per step).
  void StorePair(const std::vector<double>& x, int history)
  {
    Pair pr;
    if (!Spare.empty())
    {
      pr = std::move(Spare.back());
      Spare.pop_back();
    }
    pr.S.resize(static_cast<Eigen::Index>(NumValues));
    pr.Y.resize(static_cast<Eigen::Index>(NumValues));
    const std::array<double, 2> products = Sums.Sum<2>(NumValues,
      [&](std::size_t i0, std::size_t i1, double* out)
      {
        double* sv = pr.S.data();
        double* yv = pr.Y.data();
        for (std::size_t i = i0; i < i1; ++i)
        {
          sv[i] = Xt[i] - x[i];
          yv[i] = Gt[i] - G[i];
        }
        out[0] = Dot(sv + i0, yv + i0, i1 - i0);
        out[1] = Dot(yv + i0, yv + i0, i1 - i0);
      });
    pr.Sy = products[0];
    pr.Yy = products[1];
    if (pr.Sy > 1e-10 * pr.Yy)
    {
      Hist.push_back(std::move(pr));
      if (static_cast<int>(Hist.size()) > history)
      {
        Spare.push_back(std::move(Hist.front()));
        Hist.pop_front();
      }
    }
    else
      Spare.push_back(std::move(pr));
  }

  void ClearHistory()
  {
    for (auto& pr : Hist)
      Spare.push_back(std::move(pr));
    Hist.clear();
  }

  MeshParticles<D, K>& Particles;
  GaussianEnergy<D, K>& Energy;
  const int Dim;
  std::size_t N = 0;
  std::size_t NumValues = 0;         // N * Dim, the length of the vectors below
  const std::int8_t* Kind = nullptr; // per particle: 0 free, 1 feature line, 2 corner
  FixedBlockSums Sums;
  std::vector<double> G;            // projected gradient at the accepted state
  std::vector<double> Xt, Gt, Bt;   // trial positions, gradients, barycentrics
  std::vector<std::int32_t> Ct, Et; // trial cells, feature edges
  Eigen::VectorXd Dir;              // search direction
  std::deque<Pair> Hist;            // the last History (s, y) pairs
  std::vector<Pair> Spare;          // storage of dropped pairs
  std::vector<double> Alpha;        // two-loop coefficients
};

} // namespace sampling
} // namespace av

#endif
