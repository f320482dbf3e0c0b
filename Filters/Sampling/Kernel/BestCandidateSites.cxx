// SPDX-License-Identifier: BSD-3-Clause
// BestCandidateSites: dart throwing with a best-of-m fallback on the embedded mesh, with a grid
// of the placed sites over their principal coordinates.
#include "BestCandidateSites.h"

#include "PrincipalGridInternal.h"
#include "SamplerDimensions.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

namespace av
{
namespace sampling
{
namespace
{

// Stack-sized vectors and matrices: no allocation per vertex.
using VecD = PointVector<Eigen::Dynamic>;
using MatD =
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, kMaxDim, kMaxDim>;

/// The placed sites in a uniform grid over the principal coordinates of the embedded vertices,
/// a linked list per grid cell.
class SiteGrid
{
public:
  SiteGrid(const Embedding& emb, double r, std::size_t maxSites)
    : Dim(emb.Dim)
  {
    const std::size_t np = emb.NumPoints();
    const auto at = [&](std::size_t v) { return emb.At(v); };
    Axes = PrincipalAxes<Eigen::Dynamic, MatD>(np, Dim, at);
    double hi[3];
    ProjectedBounds<Eigen::Dynamic>(Axes, np, Dim, at, Lo, hi);
    H = GridCellSide(Lo, hi, r, maxSites, G);
    Head.assign(static_cast<std::size_t>(G[0] * G[1] * G[2]), -1);
    Next.assign(maxSites, -1);
  }

  /// Grid cell of the point px (Dim values): its coordinates q and (returned) its index.
  long long Key(const double* px, long long q[3]) const
  {
    const Eigen::Vector3d y = Axes * Eigen::Map<const VecD>(px, Dim);
    for (int a = 0; a < 3; ++a)
      q[a] = std::clamp(static_cast<long long>((y[a] - Lo[a]) / H), 0LL, G[a] - 1);
    return (q[0] * G[1] + q[1]) * G[2] + q[2];
  }

  void Insert(std::size_t site, long long key)
  {
    Next[site] = Head[static_cast<std::size_t>(key)];
    Head[static_cast<std::size_t>(key)] = static_cast<std::int32_t>(site);
  }

  /// min(r2, squared distance from cx to the sites of x (Dim values each) listed in the
  /// 3 x 3 x 3 grid cells around q).
  double NearestSquared(const std::vector<double>& x,
    const double* cx,
    const long long q[3],
    double r2) const
  {
    const auto ud = static_cast<std::size_t>(Dim);
    double dmin = r2;
    for (long long a0 = std::max(0LL, q[0] - 1); a0 <= std::min(G[0] - 1, q[0] + 1); ++a0)
      for (long long a1 = std::max(0LL, q[1] - 1); a1 <= std::min(G[1] - 1, q[1] + 1); ++a1)
        for (long long a2 = std::max(0LL, q[2] - 1); a2 <= std::min(G[2] - 1, q[2] + 1); ++a2)
          for (std::int32_t t = Head[static_cast<std::size_t>((a0 * G[1] + a1) * G[2] + a2)];
               t >= 0;
               t = Next[static_cast<std::size_t>(t)])
          {
            const double* xt = x.data() + static_cast<std::size_t>(t) * ud;
            double d2 = 0.0;
            for (int d = 0; d < Dim; ++d)
            {
              const double w = xt[d] - cx[d];
              d2 += w * w;
            }
            dmin = std::min(dmin, d2);
          }
    return dmin;
  }

private:
  const int Dim;
  AxesMatrix<Eigen::Dynamic> Axes;
  double Lo[3];
  double H = 1.0;
  long long G[3];
  std::vector<std::int32_t> Head, Next;
};

/// One candidate: a cell drawn proportionally to its measure (cumulative `cdf`, never a
/// degenerate cell), uniform barycentrics b in it and the embedded point cx. Returns the cell.
std::size_t DrawCandidate(const SimplexMesh& mesh,
  const Embedding& emb,
  const std::vector<double>& meas,
  const std::vector<double>& cdf,
  Rng& rng,
  double* b,
  std::vector<double>& cx)
{
  const int nv = mesh.VerticesPerCell();
  const std::size_t nc = mesh.NumCells();
  auto c = static_cast<std::size_t>(
    std::upper_bound(cdf.begin(), cdf.end(), rng.Uniform() * cdf.back()) - cdf.begin());
  c = std::min(c, nc - 1);
  while (meas[c] <= 0.0 && c > 0)
    --c;
  UniformBary(rng, nv, b);
  const std::int32_t* ids = mesh.Cell(c);
  std::fill(cx.begin(), cx.end(), 0.0);
  for (int v = 0; v < nv; ++v)
  {
    const double* e = emb.At(static_cast<std::size_t>(ids[v]));
    for (int d = 0; d < emb.Dim; ++d)
      cx[static_cast<std::size_t>(d)] += b[v] * e[d];
  }
  return c;
}

} // namespace

SiteSet BestCandidateSites(const SimplexMesh& mesh,
  const Embedding& emb,
  const std::vector<double>& meas,
  std::size_t count,
  int candidates,
  Rng& rng,
  const SiteSet& placed)
{
  const int k = mesh.SimplexDim, dim = emb.Dim;
  // Sites 0..nf-1 of the search are the already placed (feature) ones, not output.
  const std::size_t nf = placed.NumSites();
  const std::size_t nc = mesh.NumCells(), n = count;
  const auto ud = static_cast<std::size_t>(dim);
  std::vector<double> cdf(nc);
  double total = 0.0;
  for (std::size_t c = 0; c < nc; ++c)
    cdf[c] = (total += meas[c]);
  const double r = std::pow(total / static_cast<double>(n), 1.0 / k);
  const double r2 = r * r;
  SiteGrid grid(emb, r, n);

  std::vector<double> x(n * ud), bary(4 * n);
  std::vector<std::int32_t> cell(n);
  std::vector<double> cx(ud);
  double bx[kMaxDim], bb[4] = { 0, 0, 0, 0 };
  long long q[3];
  for (std::size_t i = 0; i < nf; ++i)
  {
    std::copy_n(placed.At(i), ud, x.data() + i * ud);
    grid.Insert(i, grid.Key(placed.At(i), q));
  }
  for (std::size_t i = nf; i < n; ++i)
  {
    double best = -1.0;
    std::size_t bestCell = 0;
    long long bestKey = 0;
    for (int j = 0; j < candidates; ++j)
    {
      double b[4] = { 0, 0, 0, 0 };
      const std::size_t c = DrawCandidate(mesh, emb, meas, cdf, rng, b, cx);
      const long long key = grid.Key(cx.data(), q);
      const double dmin = grid.NearestSquared(x, cx.data(), q, r2);
      if (dmin > best)
      {
        best = dmin;
        bestCell = c;
        bestKey = key;
        std::copy(cx.begin(), cx.end(), bx);
        std::copy(b, b + 4, bb);
      }
      if (dmin >= r2) // nothing within r: accept (dart throwing)
        break;
    }
    std::copy(bx, bx + dim, x.data() + i * ud);
    std::copy(bb, bb + 4, bary.data() + 4 * i);
    cell[i] = static_cast<std::int32_t>(bestCell);
    grid.Insert(i, bestKey);
  }
  // The new sites in cell order (cache-friendly walks; ties keep placement order).
  std::vector<std::pair<std::int32_t, std::size_t>> order(n - nf);
  for (std::size_t i = nf; i < n; ++i)
    order[i - nf] = { cell[i], i };
  std::sort(order.begin(), order.end());
  SiteSet s;
  s.Dim = dim;
  s.CellIds.resize(n - nf);
  s.Bary.assign(4 * (n - nf), 0.0);
  s.Coords.assign((n - nf) * ud, 0.0);
  for (std::size_t i = 0; i < n - nf; ++i)
  {
    const std::size_t o = order[i].second;
    s.CellIds[i] = cell[o];
    std::copy_n(bary.data() + 4 * o, 4, s.Bary.data() + 4 * i);
    std::copy_n(x.data() + o * ud, ud, s.Coords.data() + i * ud);
  }
  return s;
}

} // namespace sampling
} // namespace av
