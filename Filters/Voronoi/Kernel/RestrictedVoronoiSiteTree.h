// SPDX-License-Identifier: BSD-3-Clause
// Internal to the Voronoi kernel: the kd-tree over the sites (nanoflann) and the prefetched
// nearest-neighbor lists of every site.
#ifndef av_RestrictedVoronoiSiteTree_h
#define av_RestrictedVoronoiSiteTree_h

#include "SimplexMesh.h"

#include <nanoflann.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{
namespace rvd
{

/// nanoflann's view of a point array (DIM > 0: compile-time dimension, -1: runtime).
template <int DIM>
struct SiteCloud
{
  const double* Pts;
  std::size_t N;
  int D;
  std::size_t kdtree_get_point_count() const { return N; }
  double kdtree_get_pt(std::size_t i, std::size_t d) const
  {
    return Pts[i * (DIM > 0 ? DIM : D) + d];
  }
  template <class B>
  bool kdtree_get_bbox(B&) const
  {
    return false;
  }
};
template <int DIM>
using SiteTree = nanoflann::KDTreeSingleIndexAdaptor<
  nanoflann::L2_Simple_Adaptor<double, SiteCloud<DIM>>, SiteCloud<DIM>, DIM, std::uint32_t>;

/// The K nearest other sites of every site, by distance: NumSites x K ids and squared
/// distances (K = 0 with a single site).
struct SiteNeighbors
{
  std::vector<std::uint32_t> Ids;
  std::vector<double> Dist2;
  int K = 0;
};

/// One k-NN query per site (TBB). With duplicate sites a list may come up short: its last
/// entry is then repeated.
template <int DIM>
SiteNeighbors PrefetchNeighbors(const SiteTree<DIM>& tree, const SiteSet& sites, int k)
{
  const std::size_t ns = sites.NumSites();
  SiteNeighbors out;
  out.K = k;
  out.Ids.resize(ns * k);
  out.Dist2.resize(ns * k);
  if (k <= 0)
    return out;
  std::vector<std::uint32_t>& nbr = out.Ids;
  std::vector<double>& nbrd2 = out.Dist2;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, ns), [&](const tbb::blocked_range<std::size_t>& r) {
    std::vector<std::uint32_t> idx(k + 1);
    std::vector<double> d2(k + 1);
    for (std::size_t s = r.begin(); s != r.end(); ++s)
    {
      const std::size_t got = tree.knnSearch(sites.At(s), k + 1, idx.data(), d2.data());
      std::size_t w = 0;
      for (std::size_t q = 0; q < got && w < static_cast<std::size_t>(k); ++q)
        if (idx[q] != s)
        {
          nbr[s * k + w] = idx[q];
          nbrd2[s * k + w] = d2[q];
          ++w;
        }
      for (; w < static_cast<std::size_t>(k); ++w) // only with duplicates: repeat last
      {
        nbr[s * k + w] = nbr[s * k + w - 1];
        nbrd2[s * k + w] = nbrd2[s * k + w - 1];
      }
    }
  });
  return out;
}

} // namespace rvd
} // namespace av

#endif
