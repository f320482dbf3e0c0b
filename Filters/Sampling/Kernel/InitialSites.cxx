// SPDX-License-Identifier: BSD-3-Clause
// InitialSites: Morton order of the cells, jittered stratified draws and the merge of the free
// and feature sites into one cell-ordered start.
#include "InitialSites.h"

#include "BestCandidateSites.h"
#include "SamplerRandom.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>

namespace av
{
namespace sampling
{
namespace
{

/// 30-bit Morton code of a point in the box [lo, lo + ext] (2 or 3 coordinates).
std::uint32_t Morton(const double* p, const double* lo, const double* ext, int m)
{
  const int bits = m == 3 ? 10 : 15;
  std::uint32_t code = 0;
  std::uint32_t q[3] = { 0, 0, 0 };
  for (int d = 0; d < m; ++d)
  {
    const double t = ext[d] > 0.0 ? (p[d] - lo[d]) / ext[d] : 0.0;
    q[d] = static_cast<std::uint32_t>(std::clamp(t, 0.0, 1.0) * ((1u << bits) - 1));
  }
  for (int b = bits - 1; b >= 0; --b)
    for (int d = 0; d < m; ++d)
      code = (code << 1) | ((q[d] >> b) & 1u);
  return code;
}

/// The cells in the Morton order of their input-space centroids (ties by cell id).
std::vector<std::size_t> MortonCellOrder(const SimplexMesh& mesh)
{
  const int nv = mesh.VerticesPerCell(), m = mesh.AmbientDim;
  const std::size_t nc = mesh.NumCells();
  double lo[3], hi[3], ext[3] = { 0, 0, 0 };
  PointBounds(mesh, lo, hi);
  for (int d = 0; d < m; ++d)
    ext[d] = hi[d] - lo[d];
  std::vector<std::pair<std::uint32_t, std::size_t>> keys(nc);
  for (std::size_t c = 0; c < nc; ++c)
  {
    const std::int32_t* ids = mesh.Cell(c);
    double p[3] = { 0, 0, 0 };
    for (int j = 0; j < nv; ++j)
      for (int d = 0; d < m; ++d)
        p[d] += mesh.Point(ids[j])[d] / nv;
    keys[c] = { Morton(p, lo, ext, m), c };
  }
  std::sort(keys.begin(), keys.end());
  std::vector<std::size_t> order(nc);
  for (std::size_t c = 0; c < nc; ++c)
    order[c] = keys[c].second;
  return order;
}

/**
 * Jittered stratified draw of `count` items with probability proportional to `weight`, in
 * the given item order: the i-th draw falls in the i-th of `count` equal slices of the
 * cumulative weight, so every run of consecutive items holding weight W receives W / w̄ ± 1
 * draws (items sorted along a space-filling curve: no large-scale density fluctuations).
 * Random mode draws i.i.d. instead. Returns item indices (into `order`'s values).
 */
std::vector<std::size_t> StratifiedDraw(const std::vector<std::size_t>& order,
  const std::vector<double>& weight,
  std::size_t count,
  bool stratified,
  Rng& rng)
{
  std::vector<double> cdf(order.size());
  double total = 0.0;
  for (std::size_t i = 0; i < order.size(); ++i)
    cdf[i] = (total += weight[order[i]]);
  std::vector<std::size_t> out(count);
  for (std::size_t i = 0; i < count; ++i)
  {
    const double u = stratified
      ? (static_cast<double>(i) + rng.Uniform()) / static_cast<double>(count) * total
      : rng.Uniform() * total;
    auto j = static_cast<std::size_t>(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin());
    j = std::min(j, order.size() - 1);
    while (weight[order[j]] <= 0.0 && j > 0) // never a degenerate item
      --j;
    out[i] = order[j];
  }
  return out;
}

/// Copies site j of `from` (barycentrics and coordinates) to site i of `to`.
void CopySite(const SiteSet& from, std::size_t j, SiteSet& to, std::size_t i)
{
  std::copy_n(from.Bary.data() + 4 * j, 4, to.Bary.data() + 4 * i);
  std::copy_n(from.At(j), from.Dim, to.Coords.data() + i * static_cast<std::size_t>(to.Dim));
}

} // namespace

void DrawInitialSites(const SimplexMesh& mesh,
  const Embedding& emb,
  const std::vector<double>& meas,
  const ParticleSamplerOptions& opt,
  const FeatureSitePlacement& placed,
  ParticleSamplerResult& res)
{
  const int nv = mesh.VerticesPerCell(), dim = emb.Dim;
  const std::size_t nc = mesh.NumCells(), n = opt.NumSites;
  const std::size_t nfixed = placed.Sites.NumSites(), nfree = n - nfixed;
  std::vector<std::size_t> cellOrder(nc);
  for (std::size_t c = 0; c < nc; ++c)
    cellOrder[c] = c;
  if (opt.StratifiedInitialSites)
    cellOrder = MortonCellOrder(mesh);

  Rng rng(opt.Seed);
  // Best-candidate start: the free sites placed around the feature sites, merged in below.
  const bool bestCandidate = opt.InitialCandidates > 1;
  SiteSet best;
  if (bestCandidate)
    best = BestCandidateSites(mesh, emb, meas, n, opt.InitialCandidates, rng, placed.Sites);
  std::vector<std::pair<std::size_t, std::size_t>> draws(n); // (cell, draw index)
  if (bestCandidate)
    for (std::size_t i = 0; i < nfree; ++i)
      draws[i] = { static_cast<std::size_t>(best.CellIds[i]), i };
  else
  {
    const std::vector<std::size_t> chosen =
      StratifiedDraw(cellOrder, meas, nfree, opt.StratifiedInitialSites, rng);
    for (std::size_t i = 0; i < nfree; ++i)
      draws[i] = { chosen[i], i };
  }
  // Feature sites after the free draws (indices nfree..n-1), sorted in with them.
  for (std::size_t j = 0; j < nfixed; ++j)
    draws[nfree + j] = { static_cast<std::size_t>(placed.Sites.CellIds[j]), nfree + j };
  // Particles in cell order: neighboring cells are usually close in memory, which makes the
  // walks, list builds and energy sums cache friendly (ties keep draw order).
  std::sort(draws.begin(), draws.end());
  SiteSet& s = res.Sites;
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::size_t c = draws[i].first;
    s.CellIds[i] = static_cast<std::int32_t>(c);
    if (draws[i].second >= nfree)
    {
      const std::size_t j = draws[i].second - nfree;
      CopySite(placed.Sites, j, s, i);
      res.FeatureEdge[i] = placed.Edge[j];
      res.FeatureKind[i] = static_cast<std::int8_t>(placed.Edge[j] < 0 ? 2 : 1);
      continue;
    }
    if (bestCandidate)
    {
      CopySite(best, draws[i].second, s, i);
      continue;
    }
    double* b = s.Bary.data() + 4 * i;
    UniformBary(rng, nv, b);
    const std::int32_t* ids = mesh.Cell(c);
    for (int j = 0; j < nv; ++j)
      for (int d = 0; d < dim; ++d)
        s.Coords[i * static_cast<std::size_t>(dim) + static_cast<std::size_t>(d)] +=
          b[j] * emb.At(static_cast<std::size_t>(ids[j]))[d];
  }
}

} // namespace sampling
} // namespace av
