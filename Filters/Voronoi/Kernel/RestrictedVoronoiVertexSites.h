// SPDX-License-Identifier: BSD-3-Clause
// Internal to the Voronoi kernel: the clear nearest site of every mesh vertex, which lets an
// element whose vertices all have the same one skip the clipping (ElementWorker's fast path).
#ifndef av_RestrictedVoronoiVertexSites_h
#define av_RestrictedVoronoiVertexSites_h

#include "RestrictedVoronoiPrimitives.h"
#include "RestrictedVoronoiSiteTree.h"
#include "SimplexMesh.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace av
{
namespace rvd
{

/// Relative margin on squared distances: far above the round-off of any distance in the
/// clipping (about Dim x 1e-16), so that the clipping's own decisions agree (see below).
constexpr double WholeElementMargin = 1e-6;

/**
 * The clear nearest site of point x (see ClearNearestSites), or -1. A greedy walk on the
 * prefetched neighbor lists from `start` (updated to the nearest site): a site closer to x
 * than s lies within 2 |x - p_s| of s, so s's list, when it covers that radius, decides.
 * The margin is checked on the same list: a site j that breaks it has |x - p_j| <
 * |x - p_n| / sqrt(1 - margin), hence |p_j - p_n|^2 < 4 |x - p_n|^2 (1 + margin), which the
 * scan covers. A list too short for the radius: a kd-tree query (2 nearest) instead. The
 * answer depends on x and the sites only, not on the start.
 */
template <int DIM>
std::int32_t ClearNearestSite(const SiteTree<DIM>& tree,
  const SiteNeighbors& nbr,
  const SiteSet& sites,
  const double* x,
  std::int32_t& start)
{
  const std::size_t ns = sites.NumSites();
  const int dim = sites.Dim;
  const int k = nbr.K;
  auto siteAt = [&](std::int32_t j) { return sites.Coords.data() + std::size_t(j) * dim; };
  std::int32_t s = start;
  if (s < 0)
  {
    std::uint32_t first = 0;
    double fd = 0.0;
    tree.knnSearch(x, 1, &first, &fd);
    s = static_cast<std::int32_t>(first);
  }
  double ds = Dist2<DIM>(x, siteAt(s), dim);
  for (;;)
  {
    const std::uint32_t* idx = nbr.Ids.data() + std::size_t(s) * k;
    const double* d2 = nbr.Dist2.data() + std::size_t(s) * k;
    const double lim = 4.0 * ds * (1.0 + 4.0 * WholeElementMargin);
    double second = std::numeric_limits<double>::infinity();
    bool moved = false;
    int t = 0;
    for (; t < k && d2[t] <= lim; ++t)
    {
      const std::int32_t j = static_cast<std::int32_t>(idx[t]);
      const double dj = Dist2<DIM>(x, siteAt(j), dim);
      if (dj < ds || (dj == ds && j < s))
      {
        s = j;
        ds = dj;
        moved = true;
        break;
      }
      second = std::min(second, dj);
    }
    if (moved)
      continue;
    start = s;
    if (t == k && static_cast<std::size_t>(k) < ns - 1)
    {
      // The list does not cover the radius: the two nearest from the kd-tree.
      std::uint32_t id2[2];
      double dd2[2];
      const std::size_t got = tree.knnSearch(x, 2, id2, dd2);
      if (got < 2)
        return -1;
      start = static_cast<std::int32_t>(id2[0]);
      return dd2[0] < (1.0 - WholeElementMargin) * dd2[1] ? start : -1;
    }
    return ds < (1.0 - WholeElementMargin) * second ? s : -1;
  }
}

/**
 * Per mesh vertex v used by elements first..last-1 (or list[first..last-1]): the site n
 * nearest to v in the embedding when every other site j satisfies
 * |v - p_n|^2 < (1 - WholeElementMargin) |v - p_j|^2, else -1 (a near tie, or v not used).
 *
 * Why this is enough for an element whose K+1 vertices all have the same n: g_j(x) =
 * |x - p_j|^2 - |x - p_n|^2 is affine and > margin x |x - p_j|^2 at every vertex, so it is at
 * every point (convex combination, and |x - p_j|^2 is convex): the element is in n's cell,
 * n is the nearest site to its centroid and no bisector can classify one of its vertices out,
 * not even with the tie-break (that needs g_j <= 0 in floating point). The clipping would
 * therefore keep n's piece whole and find no other site: one piece, the whole element.
 * One walk per vertex, not per element: a vertex is shared by many elements (about 24 in a
 * Kuhn grid). The value depends on v and the sites only, so the output does not depend on
 * the threads or the element range.
 */
template <int DIM>
std::vector<std::int32_t> ClearNearestSites(const SiteTree<DIM>& tree,
  const SiteNeighbors& neighbors,
  const SimplexMesh& mesh,
  const Embedding& embedding,
  const SiteSet& sites,
  std::size_t first,
  std::size_t last,
  const std::int32_t* list)
{
  const std::size_t np = mesh.NumPoints();
  const int nv = mesh.SimplexDim + 1;
  std::vector<std::int32_t> out(np, -1);
  // Mark the vertices in use (-2), then answer them in parallel (each slot written once).
  for (std::size_t i = first; i < last; ++i)
  {
    const std::int32_t* cell = mesh.Cell(list ? static_cast<std::size_t>(list[i]) : i);
    for (int a = 0; a < nv; ++a)
      out[cell[a]] = -2;
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, np),
    [&](const tbb::blocked_range<std::size_t>& r)
    {
      std::int32_t start = -1; // the previous vertex's nearest site: the walk's start
      for (std::size_t v = r.begin(); v != r.end(); ++v)
        if (out[v] == -2)
          out[v] = ClearNearestSite<DIM>(tree, neighbors, sites, embedding.At(v), start);
    });
  return out;
}

} // namespace rvd
} // namespace av

#endif
