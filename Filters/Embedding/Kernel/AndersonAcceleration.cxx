// SPDX-License-Identifier: BSD-3-Clause
// AndersonAcceleration: ring buffer of differences, incremental Gram matrix, fused passes.
#include "AndersonAcceleration.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>

namespace av
{

namespace
{
/// out[a] = <vs[a], u> (Frobenius) for every a, in one parallel pass over the rows with fixed
/// chunks summed in order (deterministic).
void FusedDots(const std::vector<Eigen::MatrixXd>& vs, const Eigen::MatrixXd& u, double* out)
{
  const std::size_t h = vs.size(), n = static_cast<std::size_t>(u.size());
  constexpr std::size_t chunk = 16384;
  const std::size_t nchunks = (n + chunk - 1) / chunk;
  std::vector<double> partial(nchunks * h, 0.0);
  tbb::parallel_for(std::size_t(0), nchunks, [&](std::size_t c) {
    const std::size_t i0 = c * chunk, i1 = std::min(n, i0 + chunk);
    const double* pu = u.data();
    for (std::size_t a = 0; a < h; ++a)
    {
      const double* pv = vs[a].data();
      double sum = 0.0;
      for (std::size_t i = i0; i < i1; ++i)
      {
        sum += pv[i] * pu[i];
      }
      partial[c * h + a] = sum;
    }
  });
  for (std::size_t a = 0; a < h; ++a)
  {
    double sum = 0.0;
    for (std::size_t c = 0; c < nchunks; ++c)
    {
      sum += partial[c * h + a];
    }
    out[a] = sum;
  }
}

/// xa = g - sum_a theta(a) dG[a], one parallel pass.
void CombineAnderson(const Eigen::MatrixXd& g, const std::vector<Eigen::MatrixXd>& dG,
  const Eigen::VectorXd& theta, Eigen::MatrixXd& xa)
{
  xa.resize(g.rows(), g.cols());
  const std::size_t n = static_cast<std::size_t>(g.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16384),
    [&](const tbb::blocked_range<std::size_t>& r) {
      double* px = xa.data();
      const double* pg = g.data();
      for (std::size_t i = r.begin(); i != r.end(); ++i)
      {
        px[i] = pg[i];
      }
      for (std::size_t a = 0; a < dG.size(); ++a)
      {
        const double t = theta(static_cast<Eigen::Index>(a));
        const double* pd = dG[a].data();
        for (std::size_t i = r.begin(); i != r.end(); ++i)
        {
          px[i] -= t * pd[i];
        }
      }
    });
}
} // namespace

AndersonAcceleration::AndersonAcceleration(int window)
  : Window(window)
  , Gram(Eigen::MatrixXd::Zero(std::max(window, 1), std::max(window, 1)))
  , Dots(static_cast<std::size_t>(std::max(window, 1)))
{
}

void AndersonAcceleration::AddDifferences(const Eigen::MatrixXd& g)
{
  int slot = this->Head;
  if (static_cast<int>(this->DG.size()) < this->Window)
  {
    slot = static_cast<int>(this->DG.size());
    this->DG.emplace_back();
    this->DF.emplace_back();
  }
  else
  {
    this->Head = (this->Head + 1) % this->Window;
  }
  this->DG[slot] = g - this->GPrev;
  this->DF[slot] = this->F - this->FPrev;
  FusedDots(this->DF, this->DF[slot], this->Dots.data());
  for (std::size_t b = 0; b < this->DF.size(); ++b)
  {
    const Eigen::Index bi = static_cast<Eigen::Index>(b);
    this->Gram(slot, bi) = this->Gram(bi, slot) = this->Dots[b];
  }
}

bool AndersonAcceleration::Extrapolate(
  const Eigen::MatrixXd& x, const Eigen::MatrixXd& g, Eigen::MatrixXd& xa)
{
  if (this->Window <= 0)
  {
    return false;
  }
  this->F = g - x;
  if (this->GPrev.size() > 0)
  {
    this->AddDifferences(g);
  }
  this->GPrev = g;
  this->FPrev = this->F;
  const int h = static_cast<int>(this->DF.size());
  if (h == 0)
  {
    return false;
  }
  FusedDots(this->DF, this->F, this->Dots.data());
  const Eigen::VectorXd rhs = Eigen::Map<const Eigen::VectorXd>(this->Dots.data(), h);
  // Tikhonov guard against (nearly) dependent differences.
  Eigen::MatrixXd gh = this->Gram.topLeftCorner(h, h);
  gh.diagonal().array() += 1e-10 * gh.diagonal().maxCoeff() + 1e-300;
  const Eigen::VectorXd theta = gh.ldlt().solve(rhs);
  if (!theta.allFinite())
  {
    return false;
  }
  CombineAnderson(g, this->DG, theta, xa);
  return true;
}

} // namespace av
