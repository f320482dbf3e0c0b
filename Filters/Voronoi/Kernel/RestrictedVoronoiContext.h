// SPDX-License-Identifier: BSD-3-Clause
// Internal to the Voronoi kernel: the per-thread working state of the clipping (per-site cache
// of the current element, vertex-solve cache, polytope buffers, candidate list).
#ifndef av_RestrictedVoronoiContext_h
#define av_RestrictedVoronoiContext_h

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace av
{
namespace rvd
{

/// A vertex of the piece being clipped: K plane labels, barycentric coordinates in the element.
template <int K>
struct Vert
{
  std::array<std::int32_t, K> Pl;
  std::array<double, K + 1> Lam;
  double G;
  std::int32_t MinSite; // smallest site label (INT32_MAX if none): the classification reference
  bool Out;
};

/// Per-thread working state: per-site cache for the current element and the clipping buffers.
template <int K>
struct Context
{
  // Per-element cache of solved vertices (SolveVertex), invalidated by bumping Gen.
  static constexpr std::uint32_t CacheSize = 256;
  struct CacheEntry
  {
    std::array<std::int32_t, 4> Key;
    std::array<double, K + 1> Lam;
    std::uint32_t Gen = 0;
    std::int32_t S0;
    bool Ok;
  };
  std::vector<CacheEntry> Cache = std::vector<CacheEntry>(CacheSize);
  std::uint32_t Gen = 1;
  std::uint32_t CacheUsed = 0;

  // Site cache for the current element (indexed by site id, reset after each element).
  std::vector<std::int32_t> Slot;
  std::vector<std::int32_t> Touched;
  struct SiteSlot
  {
    double Dc;           // distance centroid -> site (< 0: not yet computed)
    double D[K + 1];     // squared distances element vertex -> site
    bool HasD, Visited;
  };
  std::vector<SiteSlot> Slots;
  std::vector<std::int32_t> Queue; // flood fill over the sites of the element

  // Polytope (shared layout for K = 2 and 3): vertices, faces as loops.
  // K = 2: one face (the polygon), EdgePlane[t] = plane of edge Loop[t] -> Loop[t+1].
  // K = 3: faces with a plane each; loops of vertex ids.
  std::vector<Vert<K>> V;
  std::vector<std::int32_t> Alive; // ids of the live vertices of V
  std::vector<std::int32_t> FacePlane, FaceStart, FaceCount, Loops, EdgePlane;
  std::vector<std::int32_t> NFacePlane, NFaceStart, NFaceCount, NLoops, NEdgePlane;
  std::vector<std::array<std::int32_t, 3>> EdgeCache; // u, v, new vertex
  std::vector<std::array<std::int32_t, 2>> CapNext;   // from, to
  std::vector<std::int32_t> Remap;
  // Candidate sites of the current element, sorted by (distance to the centroid, id).
  std::vector<std::int32_t> Cand;
  std::vector<double> CandDist;
  std::vector<std::pair<double, std::int32_t>> CandOrder;
  std::vector<std::pair<std::uint32_t, double>> Radius; // kd-tree radius query result
  // Of the last ComputePiece: final squared security radius, centroid distance of the last
  // candidate that cut the piece (-1: none).
  double PieceR2 = 0.0, PieceLastCut = -1.0;

  void Init(std::size_t nsites)
  {
    if (Slot.size() != nsites)
    {
      Slot.assign(nsites, -1);
    }
  }
  int SlotOf(std::int32_t s)
  {
    int sl = Slot[s];
    if (sl < 0)
    {
      sl = static_cast<int>(Touched.size());
      Slot[s] = sl;
      Touched.push_back(s);
      SiteSlot ss;
      ss.Dc = -1.0;
      ss.HasD = false;
      ss.Visited = false;
      Slots.push_back(ss);
    }
    return sl;
  }
  void ResetSites()
  {
    ++Gen;
    CacheUsed = 0;
    for (std::int32_t s : Touched)
      Slot[s] = -1;
    Touched.clear();
    Slots.clear();
  }
};

} // namespace rvd
} // namespace av

#endif
