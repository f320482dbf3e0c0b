// SPDX-License-Identifier: BSD-3-Clause
// Internal to the Voronoi kernel: CandidateFinder, the site nearest to the current element's
// centroid and the candidate sites whose cells can meet the element.
#ifndef av_RestrictedVoronoiCandidates_h
#define av_RestrictedVoronoiCandidates_h

#include "RestrictedVoronoiContext.h"
#include "RestrictedVoronoiElementFrame.h"
#include "RestrictedVoronoiPrimitives.h"
#include "RestrictedVoronoiSiteTree.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

namespace av
{
namespace rvd
{

template <int K, int DIM>
class CandidateFinder
{
public:
  static constexpr int NV = K + 1;

  CandidateFinder(const ElementFrame<K, DIM>& frame, const SiteTree<DIM>& tree,
    const SiteNeighbors& neighbors, std::size_t numSites)
    : F(frame)
    , Tree(tree)
    , Nbr(neighbors.Ids.data())
    , NbrD2(neighbors.Dist2.data())
    , NbrK(neighbors.K)
    , NumSites(numSites)
  {
  }

  /// Walk start for the next element (any site is correct); after GatherCandidates, the
  /// current element's nearest site.
  std::int32_t LastNearest = -1;

  /**
   * Candidates of the current element (C.Cand, C.CandDist): every site whose cell can meet
   * it. With n the site nearest to the centroid, every x of the element has a site within
   * U = max_a |v_a - p_n| (the distance to a fixed site is convex, so its maximum is at a
   * vertex). A site farther than U + Rho from the centroid is farther than U from every x: it
   * owns nothing here, and its bisector with an owner cannot cut that owner's piece. The set
   * is taken from n's neighbor list (|p_j - p_n| <= |c - p_n| + U + Rho), or a kd-tree query
   * when the list is too short, and sorted by (distance to the centroid, id): it is the same
   * whatever path found it, so the output does not depend on the previous element or the
   * thread. C.Cand[0] is n.
   */
  void GatherCandidates(Context<K>& C)
  {
    const std::int32_t n = NearestSite(C);
    LastNearest = n;
    // A copy: DRow / DCentroid of new sites grow the slot arrays (pointers would dangle).
    double dn[NV];
    std::copy_n(F.DRow(C, n), NV, dn);
    double u2 = 0.0;
    for (int a = 0; a < NV; ++a)
      u2 = std::max(u2, dn[a]);
    const double bound = (std::sqrt(u2) + F.Rho) * (1.0 + 1e-9);
    CollectWithin(C, n, bound);
    KeepCloserThanNearest(C, n, dn);
    std::sort(C.CandOrder.begin(), C.CandOrder.end());
    C.CandOrder.erase(std::unique(C.CandOrder.begin(), C.CandOrder.end()), C.CandOrder.end());
    DropCoincidentSites(C);
    C.Cand.clear();
    C.CandDist.clear();
    for (const auto& c : C.CandOrder)
    {
      C.Cand.push_back(c.second);
      C.CandDist.push_back(c.first);
    }
  }

private:
  const ElementFrame<K, DIM>& F;
  const SiteTree<DIM>& Tree;
  const std::uint32_t* Nbr; // NumSites x NbrK, by distance
  const double* NbrD2;
  int NbrK;
  std::size_t NumSites;

  // Distance centroid -> site j, the same value as DCentroid, without a slot for the many
  // sites that are too far.
  double CentroidDistance(std::int32_t j) const
  {
    return std::sqrt(Dist2<DIM>(F.Centroid.data(), F.SiteP(j), F.Dim));
  }

  // C.CandOrder = n and the sites within `bound` of the centroid, from n's neighbor list or,
  // when it is too short, a kd-tree radius query.
  void CollectWithin(Context<K>& C, std::int32_t n, double bound) const
  {
    const double bound2 = bound * bound;
    C.CandOrder.clear();
    C.CandOrder.push_back({ F.DCentroid(C, n), n });
    const double reach = F.DCentroid(C, n) + bound;
    const double reach2 = reach * reach * (1.0 + 1e-9);
    const std::uint32_t* idx = Nbr + std::size_t(n) * NbrK;
    const double* d2 = NbrD2 + std::size_t(n) * NbrK;
    int t = 0;
    for (; t < NbrK && d2[t] <= reach2; ++t)
    {
      const std::int32_t j = static_cast<std::int32_t>(idx[t]);
      const double dj = CentroidDistance(j);
      if (dj <= bound)
        C.CandOrder.push_back({ dj, j });
    }
    if (t == NbrK && static_cast<std::size_t>(NbrK) < NumSites - 1)
    {
      RadiusQuery(C, bound2);
      C.CandOrder.clear();
      for (const auto& r : C.Radius)
      {
        const std::int32_t j = static_cast<std::int32_t>(r.first);
        const double dj = CentroidDistance(j);
        if (dj <= bound || j == n)
          C.CandOrder.push_back({ dj, j });
      }
    }
  }

  // Keeps only sites closer than n to some vertex of the element: otherwise the element lies
  // on n's side of their bisector, they own nothing here, and (as above) cannot cut any
  // owner's piece. The margin is that of Clip's fast path, so near-ties are kept.
  void KeepCloserThanNearest(Context<K>& C, std::int32_t n, const double* dn) const
  {
    std::size_t w = 0;
    for (const auto& c : C.CandOrder)
    {
      const double* dj = F.DRow(C, c.second);
      double scale = 0.0, gmin = std::numeric_limits<double>::infinity();
      for (int a = 0; a < NV; ++a)
      {
        scale = std::max(scale, std::max(dj[a], dn[a]));
        gmin = std::min(gmin, dj[a] - dn[a]);
      }
      if (c.second == n || !(gmin > 1e-9 * scale))
        C.CandOrder[w++] = c;
    }
    C.CandOrder.resize(w);
  }

  // A site at exactly the position of a lower-id site owns nothing (ties go to the lower id),
  // and its bisector with that site is the whole space: the sign tests of the clipping cannot
  // decide it consistently (each vertex is classified against its own reference site), and
  // the pieces of both stop being a partition. Such sites leave the candidate list. The
  // sampler can place two particles on one mesh vertex (a feature-line particle that walked
  // onto a corner, say) and users may give duplicate sites. Equal coordinates give equal
  // centroid distances, so coincident sites are neighbors in the (distance, id) order.
  void DropCoincidentSites(Context<K>& C) const
  {
    std::size_t w = 0, run = 0; // run: first kept entry of the current equal-distance run
    for (std::size_t r = 0; r < C.CandOrder.size(); ++r)
    {
      const auto c = C.CandOrder[r];
      if (w == 0 || C.CandOrder[run].first != c.first)
        run = w;
      bool coincident = false;
      for (std::size_t q = run; q < w && !coincident; ++q)
        coincident = SamePosition(C.CandOrder[q].second, c.second);
      if (!coincident)
        C.CandOrder[w++] = c;
    }
    C.CandOrder.resize(w);
  }

  bool SamePosition(std::int32_t a, std::int32_t b) const
  {
    const double* pa = F.SiteP(a);
    const double* pb = F.SiteP(b);
    for (int d = 0; d < F.Dim; ++d)
      if (pa[d] != pb[d])
        return false;
    return true;
  }

  // All sites within sqrt(r2) of the centroid (inclusive, up to round-off) from the kd-tree.
  void RadiusQuery(Context<K>& C, double r2) const
  {
    C.Radius.clear();
    Tree.radiusSearch(F.Centroid.data(), r2 * (1.0 + 1e-9) + 1e-300, C.Radius,
      nanoflann::SearchParams(32, 0.0, false));
  }

  // The site nearest to the centroid (ties: lowest id). Greedy walk on the prefetched
  // neighbor lists from the previous element's nearest site: a site j closer to the centroid
  // than s satisfies |p_j - p_s| <= 2 |c - p_s|, so when s's list covers that radius and holds
  // no closer site, s is the nearest. Otherwise (list too short) a kd-tree radius query decides.
  std::int32_t NearestSite(Context<K>& C) const
  {
    std::int32_t s = LastNearest;
    if (s < 0 || static_cast<std::size_t>(s) >= NumSites)
    {
      std::uint32_t first = 0;
      double fd = 0.0;
      Tree.knnSearch(F.Centroid.data(), 1, &first, &fd);
      s = static_cast<std::int32_t>(first);
    }
    double ds = F.DCentroid2(C, s);
    for (;;)
    {
      const std::uint32_t* idx = Nbr + std::size_t(s) * NbrK;
      const double* d2 = NbrD2 + std::size_t(s) * NbrK;
      const double lim = 4.0 * ds * (1.0 + 1e-9);
      bool moved = false;
      int t = 0;
      for (; t < NbrK && d2[t] <= lim; ++t)
      {
        const std::int32_t j = static_cast<std::int32_t>(idx[t]);
        const double dj = F.DCentroid2(C, j);
        if (dj < ds || (dj == ds && j < s))
        {
          s = j;
          ds = dj;
          moved = true;
          break;
        }
      }
      if (moved)
        continue;
      if (t == NbrK && static_cast<std::size_t>(NbrK) < NumSites - 1)
      {
        RadiusQuery(C, ds);
        for (const auto& r : C.Radius)
        {
          const std::int32_t j = static_cast<std::int32_t>(r.first);
          const double dj = F.DCentroid2(C, j);
          if (dj < ds || (dj == ds && j < s))
          {
            s = j;
            ds = dj;
          }
        }
      }
      return s;
    }
  }
};

} // namespace rvd
} // namespace av

#endif
