// Restricted Voronoi diagram in R^Dim, clipped element by element in barycentric coordinates.
//
// Per element, pieces are found by a flood fill over sites: start with the site nearest to the
// element centroid (its piece is not empty), clip the element by the bisectors of that site's
// neighbours in distance order until the security radius test passes, then visit the sites
// across the bisector faces of the piece. Pieces of one convex element are face-connected, so
// this finds them all.
//
// Robustness: every vertex is (re)computed from its sorted symbolic labels (facets and the
// sites it is equidistant from) and classified against a new site m by comparing its distance
// to m with its distance to the smallest site of its label set. Every piece of an element
// therefore takes bit-identical decisions about a shared vertex; ties go to the lower site id.
#include "RestrictedVoronoi.h"

#include <nanoflann.hpp>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

namespace av
{
namespace
{

// ---------------------------------------------------------------------------------------------
// kd-tree over the sites (nanoflann; DIM > 0: compile-time dimension, -1: runtime).
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

template <int DIM>
inline double Dist2(const double* a, const double* b, int dim)
{
  double s = 0.0;
  if constexpr (DIM > 0)
  {
    for (int d = 0; d < DIM; ++d)
    {
      const double t = a[d] - b[d];
      s += t * t;
    }
  }
  else
  {
    for (int d = 0; d < dim; ++d)
    {
      const double t = a[d] - b[d];
      s += t * t;
    }
  }
  return s;
}

// Insertion sort for the tiny label arrays (std::sort trips GCC 12's -Warray-bounds here).
template <class It>
inline void SortSmall(It b, It e)
{
  for (It i = b; i != e; ++i)
    for (It j = i; j != b && *j < *(j - 1); --j)
      std::iter_swap(j, j - 1);
}

// Sorting network for 4 labels (branch-free min/max).
inline void Sort4(std::array<std::int32_t, 4>& k)
{
  auto cs = [&](int i, int j) {
    const std::int32_t a = std::min(k[i], k[j]), b = std::max(k[i], k[j]);
    k[i] = a;
    k[j] = b;
  };
  cs(0, 1);
  cs(2, 3);
  cs(0, 2);
  cs(1, 3);
  cs(1, 2);
}

// float not below x (compact per-piece bounds).
inline float RoundUp(double x)
{
  float f = static_cast<float>(x);
  if (static_cast<double>(f) < x)
    f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

inline bool IsFacet(std::int32_t label) { return label < 0; }
inline int FacetOf(std::int32_t label) { return -label - 1; }

// Measure of a k-simplex (k = 2 or 3) with vertices v[0..k] in R^dim: sqrt of the Gram
// determinant of the edge vectors / k!, in closed form (no Eigen dynamic LU per element).
template <int DIM>
double SimplexMeasureT(const double* const* v, int k, int dim)
{
  const int n = DIM > 0 ? DIM : dim;
  double g[3][3] = { { 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 } };
  for (int d = 0; d < n; ++d)
  {
    double e[3];
    for (int c = 0; c < k; ++c)
      e[c] = v[c + 1][d] - v[0][d];
    for (int a = 0; a < k; ++a)
      for (int b = a; b < k; ++b)
        g[a][b] += e[a] * e[b];
  }
  double det;
  if (k == 2)
    det = g[0][0] * g[1][1] - g[0][1] * g[0][1];
  else
    det = g[0][0] * (g[1][1] * g[2][2] - g[1][2] * g[1][2]) -
      g[0][1] * (g[0][1] * g[2][2] - g[1][2] * g[0][2]) +
      g[0][2] * (g[0][1] * g[1][2] - g[1][1] * g[0][2]);
  return std::sqrt(std::max(0.0, det)) / (k == 2 ? 2.0 : 6.0);
}
inline double SimplexMeasure(const double* const* v, int k, int dim)
{
  return SimplexMeasureT<-1>(v, k, dim);
}

// ---------------------------------------------------------------------------------------------
// Per-thread working state: per-site cache for the current element and the clipping buffers.
template <int K>
struct Vert
{
  std::array<std::int32_t, K> Pl;
  std::array<double, K + 1> Lam;
  double G;
  std::int32_t MinSite; // smallest site label (INT32_MAX if none): the classification reference
  bool Out;
};

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
  std::vector<std::int32_t> Queue;
  std::vector<std::uint32_t> NbrIdx;
  std::vector<double> NbrDist;

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

// Output of a block of elements, concatenated at the end.
struct Chunk
{
  std::vector<std::int32_t> PieceSite, PieceElement;
  std::vector<double> PieceMeasure, PieceEmbeddedMeasure;
  std::vector<std::int64_t> PieceVertexCount, PieceFaceCount;
  std::vector<double> Points, EmbeddedPoints;
  std::vector<std::int32_t> VertexPlanes;
  std::vector<std::int64_t> FaceSize;
  std::vector<std::int32_t> FaceVertices; // local to the chunk
  std::vector<RVDFaceKind> FaceKind;
  std::vector<std::int32_t> FaceNeighbor;
  std::vector<std::int32_t> VoronoiVertexSites, VoronoiVertexElement, BoundaryDualFaces;
  // Per processed element: nearest site, pieces / Voronoi vertex / boundary records emitted.
  std::vector<std::int32_t> ElemNearest, ElemPieces, ElemVV, ElemBD;
  std::vector<std::uint8_t> ElemEmptyVisit; // a visited site had an empty piece
  std::vector<float> PieceRadius2, PieceLastCut; // rounded up
};

// ---------------------------------------------------------------------------------------------
template <int K, int DIM>
class Worker
{
public:
  static constexpr int NV = K + 1;

  const SimplexMesh& Mesh;
  const Embedding& Emb;
  const SiteSet& Sites;
  const RestrictedVoronoiOptions& Opt;
  const SiteTree<DIM>& Tree;
  const std::vector<std::int32_t>& Adj;
  const std::vector<std::uint32_t>& Nbr; // NumSites x NbrK, by distance
  const std::vector<double>& NbrD2;
  int NbrK;
  int Dim;
  std::size_t NumSites;

  // Current element.
  std::int32_t Elem = -1;
  const double* EV[4];
  const double* XV[4];
  double L[4][4];
  std::vector<double> Centroid;
  double Rho = 0.0;

  Worker(const SimplexMesh& m, const Embedding& e, const SiteSet& s,
    const RestrictedVoronoiOptions& o, const SiteTree<DIM>& t, const std::vector<std::int32_t>& adj,
    const std::vector<std::uint32_t>& nbr, const std::vector<double>& nbrd2, int nbrk)
    : Mesh(m)
    , Emb(e)
    , Sites(s)
    , Opt(o)
    , Tree(t)
    , Adj(adj)
    , Nbr(nbr)
    , NbrD2(nbrd2)
    , NbrK(nbrk)
    , Dim(e.Dim)
    , NumSites(s.NumSites())
  {
  }

  const double* SiteP(std::int32_t s) const { return Sites.Coords.data() + std::size_t(s) * Dim; }

  // Squared distances element vertices -> site s (cached per element).
  const double* DRow(Context<K>& C, std::int32_t s) const
  {
    const int sl = C.SlotOf(s);
    auto& ss = C.Slots[sl];
    if (!ss.HasD)
    {
      const double* p = SiteP(s);
      for (int a = 0; a < NV; ++a)
        ss.D[a] = Dist2<DIM>(EV[a], p, Dim);
      ss.HasD = true;
    }
    return ss.D;
  }

  double DCentroid(Context<K>& C, std::int32_t s) const
  {
    const int sl = C.SlotOf(s);
    auto& ss = C.Slots[sl];
    if (ss.Dc < 0.0)
      ss.Dc = std::sqrt(Dist2<DIM>(Centroid.data(), SiteP(s), Dim));
    return ss.Dc;
  }

  // Barycentric coordinates of the vertex with these labels, computed from the sorted labels
  // only, so every piece of the element gets the same bits. Returns false if singular.
  bool SolveVertex(Context<K>& C, std::int32_t site, const std::array<std::int32_t, K>& pl,
    std::array<double, K + 1>& lam, std::int32_t& s0out) const
  {
    // Key: site and labels sorted (facets, being negative, first); K = 2 pads with INT32_MAX.
    std::array<std::int32_t, 4> key;
    key[0] = site;
    for (int a = 0; a < K; ++a)
      key[a + 1] = pl[a];
    if constexpr (K == 2)
      key[3] = std::numeric_limits<std::int32_t>::max();
    Sort4(key);
    // Per-element cache: a vertex is shared by up to K+1 pieces and solved once.
    std::uint32_t h = (static_cast<std::uint32_t>(key[0]) * 0x9E3779B1u) ^
      (static_cast<std::uint32_t>(key[1]) * 0x85EBCA77u) ^
      (static_cast<std::uint32_t>(key[2]) * 0xC2B2AE3Du) ^ (static_cast<std::uint32_t>(key[3]) * 0x27D4EB2Fu);
    h = (h ^ (h >> 15)) & (Context<K>::CacheSize - 1);
    for (;;)
    {
      auto& e = C.Cache[h];
      if (e.Gen != C.Gen)
        break;
      if (e.Key == key)
      {
        lam = e.Lam;
        s0out = e.S0;
        return e.Ok;
      }
      h = (h + 1) & (Context<K>::CacheSize - 1);
    }
    const bool ok = SolveVertexKey(C, key, lam, s0out);
    if (C.CacheUsed < Context<K>::CacheSize / 2)
    {
      auto& e = C.Cache[h];
      e.Gen = C.Gen;
      e.Key = key;
      e.Lam = lam;
      e.S0 = s0out;
      e.Ok = ok;
      ++C.CacheUsed;
    }
    return ok;
  }

  bool SolveVertexKey(Context<K>& C, const std::array<std::int32_t, 4>& key,
    std::array<double, K + 1>& lam, std::int32_t& s0out) const
  {
    std::array<std::int32_t, K + 1> S;
    int ns = 0;
    bool facet[4] = { false, false, false, false };
    for (int a = 0; a < NV; ++a)
    {
      if (IsFacet(key[a]))
        facet[FacetOf(key[a])] = true;
      else
        S[ns++] = key[a];
    }
    s0out = S[0];
    int fr[4];
    int n = 0;
    for (int a = 0; a < NV; ++a)
      if (!facet[a])
        fr[n++] = a;
    lam.fill(0.0);
    if (n == 1)
    {
      lam[fr[0]] = 1.0;
      return true;
    }
    // Rows: sum of free lambdas = 1, then (D[s0] - D[s]) . lambda = 0 for s in S[1..].
    double M[4][5];
    for (int c = 0; c < n; ++c)
      M[0][c] = 1.0;
    M[0][n] = 1.0;
    const double* d0 = DRow(C, S[0]);
    for (int r = 1; r < ns; ++r)
    {
      const double* dr = DRow(C, S[r]);
      for (int c = 0; c < n; ++c)
        M[r][c] = d0[fr[c]] - dr[fr[c]];
      M[r][n] = 0.0;
    }
    // Gaussian elimination with partial pivoting (deterministic for given input).
    for (int c = 0; c < n; ++c)
    {
      int piv = c;
      for (int r = c + 1; r < n; ++r)
        if (std::abs(M[r][c]) > std::abs(M[piv][c]))
          piv = r;
      if (!(std::abs(M[piv][c]) > 0.0))
        return false;
      if (piv != c)
        for (int cc = 0; cc <= n; ++cc)
          std::swap(M[c][cc], M[piv][cc]);
      for (int r = c + 1; r < n; ++r)
      {
        const double f = M[r][c] / M[c][c];
        for (int cc = c; cc <= n; ++cc)
          M[r][cc] -= f * M[c][cc];
      }
    }
    double x[4];
    for (int c = n - 1; c >= 0; --c)
    {
      double s = M[c][n];
      for (int cc = c + 1; cc < n; ++cc)
        s -= M[c][cc] * x[cc];
      x[c] = s / M[c][c];
    }
    for (int c = 0; c < n; ++c)
    {
      if (!std::isfinite(x[c]))
        return false;
      lam[fr[c]] = x[c];
    }
    return true;
  }

  static std::int32_t MinSiteLabel(const std::array<std::int32_t, K>& pl)
  {
    std::int32_t s0 = std::numeric_limits<std::int32_t>::max();
    for (int a = 0; a < K; ++a)
      if (!IsFacet(pl[a]))
        s0 = std::min(s0, pl[a]);
    return s0;
  }

  // Classification of vertex v of piece `site` against the bisector with site m (dm, di: the
  // rows of m and site): the reference is the smallest site of v's labels and `site`.
  void Classify(Context<K>& C, std::int32_t site, Vert<K>& v, std::int32_t m, const double* dm,
    const double* di) const
  {
    const std::int32_t s0 = std::min(site, v.MinSite);
    const double* d0 = s0 == site ? di : DRow(C, s0);
    double g = 0.0;
    for (int a = 0; a < NV; ++a)
      g += v.Lam[a] * (dm[a] - d0[a]);
    v.G = g;
    v.Out = g < 0.0 || (g == 0.0 && m < s0);
  }

  // New vertex on the edge u-v (labels: the two common planes + the new one).
  std::int32_t NewVertex(Context<K>& C, std::int32_t site, std::int32_t u, std::int32_t w,
    const std::array<std::int32_t, K - 1>& common, std::int32_t m) const
  {
    Vert<K> nv;
    for (int a = 0; a < K - 1; ++a)
      nv.Pl[a] = common[a];
    nv.Pl[K - 1] = m;
    std::int32_t s0;
    if (!SolveVertex(C, site, nv.Pl, nv.Lam, s0))
    {
      // Parallel planes (degenerate): interpolate along the edge instead. An edge lying in
      // the bisector (both G exactly 0, sides set by the symbolic tie-break) has no single
      // crossing: any point of it is on the plane, take its middle (not 0 / 0).
      const Vert<K>& a = C.V[u];
      const Vert<K>& b = C.V[w];
      const double denom = a.G - b.G;
      const double t = denom != 0.0 ? std::min(1.0, std::max(0.0, a.G / denom)) : 0.5;
      for (int c = 0; c < NV; ++c)
        nv.Lam[c] = a.Lam[c] + t * (b.Lam[c] - a.Lam[c]);
    }
    nv.G = 0.0;
    nv.Out = false;
    nv.MinSite = MinSiteLabel(nv.Pl);
    C.V.push_back(nv);
    return static_cast<std::int32_t>(C.V.size() - 1);
  }

  void InitPolytope(Context<K>& C) const
  {
    C.V.clear();
    C.Alive.clear();
    for (int b = 0; b < NV; ++b)
      C.Alive.push_back(b);
    C.FacePlane.clear();
    C.FaceStart.clear();
    C.FaceCount.clear();
    C.Loops.clear();
    C.EdgePlane.clear();
    for (int b = 0; b < NV; ++b)
    {
      Vert<K> v;
      int n = 0;
      for (int a = 0; a < NV; ++a)
        if (a != b)
          v.Pl[n++] = -(a + 1);
      v.Lam.fill(0.0);
      v.Lam[b] = 1.0;
      v.G = 0.0;
      v.Out = false;
      v.MinSite = std::numeric_limits<std::int32_t>::max();
      C.V.push_back(v);
    }
    if constexpr (K == 2)
    {
      // Counter-clockwise in (lambda1, lambda2): 0 -> 1 on facet 2, 1 -> 2 on facet 0, 2 -> 0 on 1.
      C.Loops = { 0, 1, 2 };
      C.EdgePlane = { -3, -1, -2 };
    }
    else
    {
      static const int faces[4][3] = { { 1, 2, 3 }, { 0, 3, 2 }, { 0, 1, 3 }, { 0, 2, 1 } };
      for (int f = 0; f < 4; ++f)
      {
        C.FacePlane.push_back(-(f + 1));
        C.FaceStart.push_back(static_cast<std::int32_t>(C.Loops.size()));
        C.FaceCount.push_back(3);
        for (int t = 0; t < 3; ++t)
          C.Loops.push_back(faces[f][t]);
      }
    }
  }

  // Clips the current polytope of piece `site` by the bisector with m.
  // Returns 0: unchanged, 1: cut, -1: empty.
  int Clip(Context<K>& C, std::int32_t site, std::int32_t m) const
  {
    // Copies: DRow of a new site grows the slot array (pointers would dangle).
    double dm[NV], di[NV];
    std::copy_n(DRow(C, m), NV, dm);
    std::copy_n(DRow(C, site), NV, di);
    // Fast path: with the piece's own site as reference, every vertex is clearly on the
    // site's side (margin far above round-off), so the exact classification would keep all.
    {
      double scale = 0.0, emin = std::numeric_limits<double>::infinity();
      double diff[NV];
      for (int a = 0; a < NV; ++a)
      {
        scale = std::max(scale, std::max(dm[a], di[a]));
        diff[a] = dm[a] - di[a];
        emin = std::min(emin, diff[a]);
      }
      // The piece's vertices are convex combinations of the element's: when all element
      // vertices pass with twice the margin, so do they (no loop over the piece).
      if (emin > 2e-9 * scale)
        return 0;
      double gmin = std::numeric_limits<double>::infinity();
      for (const std::int32_t id : C.Alive)
      {
        const Vert<K>& v = C.V[id];
        double g = 0.0;
        for (int a = 0; a < NV; ++a)
          g += v.Lam[a] * (dm[a] - di[a]);
        gmin = std::min(gmin, g);
      }
      if (gmin > 1e-9 * scale)
        return 0;
    }
    int nout = 0;
    const int nalive = static_cast<int>(C.Alive.size());
    const std::size_t oldSize = C.V.size();
    for (const std::int32_t id : C.Alive)
    {
      Vert<K>& v = C.V[id];
      Classify(C, site, v, m, dm, di);
      nout += v.Out;
    }
    if (nout == 0)
      return 0;
    if (nout == nalive)
      return -1;
    if constexpr (K == 2)
    {
      C.NLoops.clear();
      C.NEdgePlane.clear();
      const int n = static_cast<int>(C.Loops.size());
      for (int t = 0; t < n; ++t)
      {
        const std::int32_t u = C.Loops[t], w = C.Loops[t + 1 == n ? 0 : t + 1];
        const bool uo = C.V[u].Out, wo = C.V[w].Out;
        if (!uo)
        {
          C.NLoops.push_back(u);
          C.NEdgePlane.push_back(C.EdgePlane[t]);
          if (wo)
          {
            C.NEdgePlane.back() = C.EdgePlane[t];
            const std::int32_t x = NewVertex(C, site, u, w, { C.EdgePlane[t] }, m);
            C.NLoops.push_back(x);
            C.NEdgePlane.push_back(m);
          }
        }
        else if (!wo)
        {
          const std::int32_t x = NewVertex(C, site, u, w, { C.EdgePlane[t] }, m);
          C.NLoops.push_back(x);
          C.NEdgePlane.push_back(C.EdgePlane[t]);
        }
      }
      std::swap(C.Loops, C.NLoops);
      std::swap(C.EdgePlane, C.NEdgePlane);
    }
    else
    {
      C.NFacePlane.clear();
      C.NFaceStart.clear();
      C.NFaceCount.clear();
      C.EdgeCache.clear();
      C.CapNext.clear();
      const int nf = static_cast<int>(C.FacePlane.size());
      // New loops written through a raw pointer (no push_back in the inner loop). Bound: a
      // face keeps at most its n vertices plus one new per edge; the cap has at most nf.
      const std::size_t cap = 2 * C.Loops.size() + static_cast<std::size_t>(nf) + 4;
      if (C.NLoops.size() < cap)
        C.NLoops.resize(cap);
      std::int32_t* nl = C.NLoops.data();
      std::int32_t nn = 0;
      for (int f = 0; f < nf; ++f)
      {
        const int st = C.FaceStart[f], n = C.FaceCount[f];
        const std::int32_t start = nn;
        std::int32_t exitW = -1, enterW = -1;
        const std::int32_t* loop = C.Loops.data() + st;
        bool uo = C.V[loop[0]].Out;
        for (int t = 0; t < n; ++t)
        {
          const std::int32_t u = loop[t], w = loop[t + 1 == n ? 0 : t + 1];
          const bool wo = C.V[w].Out;
          if (!uo)
            nl[nn++] = u;
          if (uo != wo)
          {
            const std::int32_t x = EdgeVertex(C, site, u, w, m);
            nl[nn++] = x;
            if (!uo)
              exitW = x;
            else
              enterW = x;
          }
          uo = wo;
        }
        const std::int32_t cnt = nn - start;
        if (cnt >= 3)
        {
          C.NFacePlane.push_back(C.FacePlane[f]);
          C.NFaceStart.push_back(start);
          C.NFaceCount.push_back(cnt);
        }
        else
          nn = start;
        if (exitW >= 0 && enterW >= 0)
          C.CapNext.push_back({ enterW, exitW });
      }
      // Cap face on the new plane: walk enter -> exit links (reverse of the faces' direction).
      if (C.CapNext.size() >= 3)
      {
        const std::int32_t start = nn;
        std::int32_t cur = C.CapNext[0][0];
        for (std::size_t it = 0; it < C.CapNext.size(); ++it)
        {
          nl[nn++] = cur;
          std::int32_t next = -1;
          for (const auto& e : C.CapNext)
            if (e[0] == cur)
            {
              next = e[1];
              break;
            }
          if (next < 0 || next == C.CapNext[0][0])
            break;
          cur = next;
        }
        C.NFacePlane.push_back(m);
        C.NFaceStart.push_back(start);
        C.NFaceCount.push_back(nn - start);
      }
      C.NLoops.resize(static_cast<std::size_t>(nn));
      std::swap(C.FacePlane, C.NFacePlane);
      std::swap(C.FaceStart, C.NFaceStart);
      std::swap(C.FaceCount, C.NFaceCount);
      std::swap(C.Loops, C.NLoops);
    }
    std::size_t w = 0;
    for (const std::int32_t id : C.Alive)
      if (!C.V[id].Out)
        C.Alive[w++] = id;
    C.Alive.resize(w);
    for (std::size_t id = oldSize; id < C.V.size(); ++id)
      C.Alive.push_back(static_cast<std::int32_t>(id));
    return 1;
  }

  // 3D: the new vertex on edge u-w, shared by the two faces of that edge.
  std::int32_t EdgeVertex(Context<K>& C, std::int32_t site, std::int32_t u, std::int32_t w,
    std::int32_t m) const
  {
    const std::int32_t a = std::min(u, w), b = std::max(u, w);
    for (const auto& e : C.EdgeCache)
      if (e[0] == a && e[1] == b)
        return e[2];
    std::array<std::int32_t, K - 1> common{};
    int nc = 0;
    for (int i = 0; i < K; ++i)
      for (int j = 0; j < K; ++j)
        if (C.V[u].Pl[i] == C.V[w].Pl[j] && nc < K - 1)
          common[nc++] = C.V[u].Pl[i];
    const std::int32_t x = NewVertex(C, site, u, w, common, m);
    C.EdgeCache.push_back({ a, b, x });
    return x;
  }

  double Radius2(Context<K>& C, std::int32_t site) const
  {
    const double* di = DRow(C, site);
    double r2 = 0.0;
    for (const std::int32_t id : C.Alive)
    {
      const Vert<K>& v = C.V[id];
      double s = 0.0;
      for (int a = 0; a < NV; ++a)
        s += v.Lam[a] * di[a];
      for (int a = 0; a < NV; ++a)
        for (int b = a + 1; b < NV; ++b)
          s -= v.Lam[a] * v.Lam[b] * L[a][b];
      r2 = std::max(r2, s);
    }
    return r2;
  }

  // Computes the piece of `site` in the current element; false if empty. Only the element's
  // candidates can cut it (see GatherCandidates); they are sorted by distance to the centroid,
  // so |p_m - p_site| >= dc(m) - dc(site) gives the security radius stop.
  bool ComputePiece(Context<K>& C, std::int32_t site) const
  {
    InitPolytope(C);
    double r2 = Radius2(C, site);
    double rr = std::sqrt(r2);
    C.PieceLastCut = -1.0;
    const double dci = DCentroid(C, site);
    const std::size_t nc = C.Cand.size();
    for (std::size_t t = 0; t < nc; ++t)
    {
      const std::int32_t m = C.Cand[t];
      if (m == site)
        continue;
      const double dcm = C.CandDist[t];
      const double gap = dcm - dci;
      if (gap > 0.0 && gap * gap > 4.0 * r2 * (1.0 + 1e-12))
        break; // security radius: no farther candidate can cut
      // Same through the element's ball: every x of the piece has |x - p_m| >= dcm - Rho,
      // more than |x - p_site| <= sqrt(r2) (better when the element is large for its pieces).
      if (dcm > (rr + Rho) * (1.0 + 1e-9))
        break;
      // Cheap reject: the element's bounding ball is entirely on site's side.
      if (dcm - Rho > dci + Rho)
        continue;
      const int r = Clip(C, site, m);
      if (r < 0)
        return false;
      if (r > 0)
      {
        r2 = Radius2(C, site);
        rr = std::sqrt(r2);
        C.PieceLastCut = dcm;
      }
    }
    C.PieceR2 = r2;
    return true;
  }

  // Squared distance centroid -> site, cached per element.
  double DCentroid2(Context<K>& C, std::int32_t s) const
  {
    const double d = DCentroid(C, s);
    return d * d;
  }

  // All sites within sqrt(r2) of the centroid (inclusive, up to round-off) from the kd-tree.
  void RadiusQuery(Context<K>& C, double r2) const
  {
    C.Radius.clear();
    Tree.radiusSearch(Centroid.data(), r2 * (1.0 + 1e-9) + 1e-300, C.Radius, nanoflann::SearchParams(32, 0.0, false));
  }

  // The site nearest to the centroid (ties: lowest id). Greedy walk on the prefetched
  // neighbour lists from the previous element's nearest site: a site j closer to the centroid
  // than s satisfies |p_j - p_s| <= 2 |c - p_s|, so when s's list covers that radius and holds
  // no closer site, s is the nearest. Otherwise (list too short) a kd-tree radius query decides.
  std::int32_t NearestSite(Context<K>& C) const
  {
    std::int32_t s = LastNearest;
    if (s < 0 || static_cast<std::size_t>(s) >= NumSites)
    {
      std::uint32_t first = 0;
      double fd = 0.0;
      Tree.knnSearch(Centroid.data(), 1, &first, &fd);
      s = static_cast<std::int32_t>(first);
    }
    double ds = DCentroid2(C, s);
    for (;;)
    {
      const std::uint32_t* idx = Nbr.data() + std::size_t(s) * NbrK;
      const double* d2 = NbrD2.data() + std::size_t(s) * NbrK;
      const double lim = 4.0 * ds * (1.0 + 1e-9);
      bool moved = false;
      int t = 0;
      for (; t < NbrK && d2[t] <= lim; ++t)
      {
        const std::int32_t j = static_cast<std::int32_t>(idx[t]);
        const double dj = DCentroid2(C, j);
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
          const double dj = DCentroid2(C, j);
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

  // Candidates of the current element: every site whose cell can meet it. With n the site
  // nearest to the centroid, every x of the element has a site within U = max_a |v_a - p_n|
  // (the distance to a fixed site is convex, so its maximum is at a vertex). A site farther
  // than U + Rho from the centroid is farther than U from every x: it owns nothing here, and
  // its bisector with an owner cannot cut that owner's piece. The set is taken from n's
  // neighbour list (|p_j - p_n| <= |c - p_n| + U + Rho), or a kd-tree query when the list is
  // too short, and sorted by (distance to the centroid, id): it is the same whatever path
  // found it, so the output does not depend on the previous element or the thread.
  void GatherCandidates(Context<K>& C)
  {
    const std::int32_t n = NearestSite(C);
    LastNearest = n;
    // A copy: DRow / DCentroid of new sites grow the slot arrays (pointers would dangle).
    double dn[NV];
    std::copy_n(DRow(C, n), NV, dn);
    double u2 = 0.0;
    for (int a = 0; a < NV; ++a)
      u2 = std::max(u2, dn[a]);
    const double bound = (std::sqrt(u2) + Rho) * (1.0 + 1e-9);
    const double bound2 = bound * bound;
    C.CandOrder.clear();
    C.CandOrder.push_back({ DCentroid(C, n), n });
    const double reach = DCentroid(C, n) + bound;
    const double reach2 = reach * reach * (1.0 + 1e-9);
    const std::uint32_t* idx = Nbr.data() + std::size_t(n) * NbrK;
    const double* d2 = NbrD2.data() + std::size_t(n) * NbrK;
    int t = 0;
    for (; t < NbrK && d2[t] <= reach2; ++t)
    {
      // Same value as DCentroid, without a slot for the many sites that are too far.
      const std::int32_t j = static_cast<std::int32_t>(idx[t]);
      const double dj = std::sqrt(Dist2<DIM>(Centroid.data(), SiteP(j), Dim));
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
        const double dj = std::sqrt(Dist2<DIM>(Centroid.data(), SiteP(j), Dim));
        if (dj <= bound || j == n)
          C.CandOrder.push_back({ dj, j });
      }
    }
    // Keep only sites closer than n to some vertex of the element: otherwise the element lies
    // on n's side of their bisector, they own nothing here, and (as above) cannot cut any
    // owner's piece. The margin is that of Clip's fast path, so near-ties are kept.
    std::size_t w = 0;
    for (const auto& c : C.CandOrder)
    {
      const double* dj = DRow(C, c.second);
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
    std::sort(C.CandOrder.begin(), C.CandOrder.end());
    C.CandOrder.erase(std::unique(C.CandOrder.begin(), C.CandOrder.end()), C.CandOrder.end());
    C.Cand.clear();
    C.CandDist.clear();
    for (const auto& c : C.CandOrder)
    {
      C.Cand.push_back(c.second);
      C.CandDist.push_back(c.first);
    }
  }

  std::int32_t LastNearest = -1; // walk start for the next element (any site is correct)

  // Appends the current piece to the chunk.
  void Emit(Context<K>& C, Chunk& out, std::int32_t site) const
  {
    const int adim = Mesh.AmbientDim;
    // Relative measure in barycentric coordinates (fraction of the element).
    double rel = 0.0;
    if constexpr (K == 2)
    {
      const int n = static_cast<int>(C.Loops.size());
      for (int t = 0; t < n; ++t)
      {
        const auto& a = C.V[C.Loops[t]].Lam;
        const auto& b = C.V[C.Loops[(t + 1) % n]].Lam;
        rel += a[1] * b[2] - a[2] * b[1];
      }
    }
    else
    {
      const auto& o = C.V[C.Loops[C.FaceStart[0]]].Lam;
      for (std::size_t f = 0; f < C.FacePlane.size(); ++f)
      {
        const int st = C.FaceStart[f], n = C.FaceCount[f];
        const auto& a = C.V[C.Loops[st]].Lam;
        for (int t = 1; t + 1 < n; ++t)
        {
          const auto& b = C.V[C.Loops[st + t]].Lam;
          const auto& c = C.V[C.Loops[st + t + 1]].Lam;
          const double ax = a[1] - o[1], ay = a[2] - o[2], az = a[3] - o[3];
          const double bx = b[1] - o[1], by = b[2] - o[2], bz = b[3] - o[3];
          const double cx = c[1] - o[1], cy = c[2] - o[2], cz = c[3] - o[3];
          rel += ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx);
        }
      }
    }
    rel = std::max(0.0, rel);
    out.PieceSite.push_back(site);
    out.PieceElement.push_back(Elem);
    out.PieceMeasure.push_back(rel * ElemMeasure);
    out.PieceEmbeddedMeasure.push_back(rel * ElemEmbMeasure);
    out.PieceRadius2.push_back(RoundUp(C.PieceR2));
    out.PieceLastCut.push_back(RoundUp(C.PieceLastCut));

    // Voronoi vertices and boundary dual faces (symbolic).
    auto visitVertex = [&](const Vert<K>& v) {
      int nfac = 0, fac = -1;
      std::array<std::int32_t, K + 1> s;
      int ns = 0;
      s[ns++] = site;
      for (int a = 0; a < K; ++a)
      {
        if (IsFacet(v.Pl[a]))
        {
          ++nfac;
          fac = FacetOf(v.Pl[a]);
        }
        else
          s[ns++] = v.Pl[a];
      }
      if (nfac > 1 || (nfac == 1 && Adj[std::size_t(Elem) * NV + fac] >= 0))
        return; // neither a Voronoi vertex nor on the domain boundary: nothing to record
      SortSmall(s.begin(), s.begin() + ns);
      if (nfac == 0)
      {
        out.VoronoiVertexSites.insert(out.VoronoiVertexSites.end(), s.begin(), s.begin() + ns);
        out.VoronoiVertexElement.push_back(Elem);
      }
      else if (nfac == 1 && Adj[std::size_t(Elem) * NV + fac] < 0)
        out.BoundaryDualFaces.insert(out.BoundaryDualFaces.end(), s.begin(), s.begin() + ns);
    };

    auto planeKind = [&](std::int32_t pl, RVDFaceKind& kind, std::int32_t& nbr) {
      if (!IsFacet(pl))
      {
        kind = RVDFaceKind::Bisector;
        nbr = pl;
      }
      else
      {
        nbr = Adj[std::size_t(Elem) * NV + FacetOf(pl)];
        kind = nbr < 0 ? RVDFaceKind::DomainBoundary : RVDFaceKind::ElementFace;
      }
    };

    // Collect alive vertices referenced by the faces (local numbering).
    C.Remap.assign(C.V.size(), -1);
    std::vector<std::int32_t>& order = C.NLoops; // scratch
    order.clear();
    for (std::int32_t id : C.Loops)
      if (C.Remap[id] < 0)
      {
        C.Remap[id] = static_cast<std::int32_t>(order.size());
        order.push_back(id);
      }
    for (std::int32_t id : order)
      visitVertex(C.V[id]);
    if (!Opt.ComputeGeometry)
      return;

    const std::int32_t base = static_cast<std::int32_t>(out.Points.size() / adim);
    for (std::int32_t id : order)
    {
      const auto& v = C.V[id];
      for (int d = 0; d < adim; ++d)
      {
        double x = 0.0;
        for (int a = 0; a < NV; ++a)
          x += v.Lam[a] * XV[a][d];
        out.Points.push_back(x);
      }
      if (Opt.KeepEmbeddedPoints)
        for (int d = 0; d < Dim; ++d)
        {
          double x = 0.0;
          for (int a = 0; a < NV; ++a)
            x += v.Lam[a] * EV[a][d];
          out.EmbeddedPoints.push_back(x);
        }
      for (int a = 0; a < K; ++a)
        out.VertexPlanes.push_back(v.Pl[a]);
    }
    out.PieceVertexCount.push_back(static_cast<std::int64_t>(order.size()));
    std::int64_t nfaces = 0;
    if constexpr (K == 2)
    {
      const int n = static_cast<int>(C.Loops.size());
      for (int t = 0; t < n; ++t)
      {
        RVDFaceKind kind;
        std::int32_t nbr;
        planeKind(C.EdgePlane[t], kind, nbr);
        if (Opt.MergeBySite && kind == RVDFaceKind::ElementFace)
          continue;
        out.FaceVertices.push_back(base + C.Remap[C.Loops[t]]);
        out.FaceVertices.push_back(base + C.Remap[C.Loops[(t + 1) % n]]);
        out.FaceSize.push_back(2);
        out.FaceKind.push_back(kind);
        out.FaceNeighbor.push_back(nbr);
        ++nfaces;
      }
    }
    else
    {
      for (std::size_t f = 0; f < C.FacePlane.size(); ++f)
      {
        RVDFaceKind kind;
        std::int32_t nbr;
        planeKind(C.FacePlane[f], kind, nbr);
        if (Opt.MergeBySite && kind == RVDFaceKind::ElementFace)
          continue;
        const int st = C.FaceStart[f], n = C.FaceCount[f];
        for (int t = 0; t < n; ++t)
          out.FaceVertices.push_back(base + C.Remap[C.Loops[st + t]]);
        out.FaceSize.push_back(n);
        out.FaceKind.push_back(kind);
        out.FaceNeighbor.push_back(nbr);
        ++nfaces;
      }
    }
    out.PieceFaceCount.push_back(nfaces);
  }

  double ElemMeasure = 0.0, ElemEmbMeasure = 0.0;

  void ProcessElement(Context<K>& C, std::int32_t e, Chunk& out)
  {
    Elem = e;
    const std::int32_t* cell = Mesh.Cell(e);
    for (int a = 0; a < NV; ++a)
    {
      EV[a] = Emb.At(cell[a]);
      XV[a] = Mesh.Point(cell[a]);
    }
    for (int a = 0; a < NV; ++a)
      for (int b = 0; b < NV; ++b)
        L[a][b] = Dist2<DIM>(EV[a], EV[b], Dim);
    Centroid.assign(Dim, 0.0);
    for (int a = 0; a < NV; ++a)
      for (int d = 0; d < Dim; ++d)
        Centroid[d] += EV[a][d] / NV;
    Rho = 0.0;
    for (int a = 0; a < NV; ++a)
      Rho = std::max(Rho, std::sqrt(Dist2<DIM>(EV[a], Centroid.data(), Dim)));
    Rho *= 1.0 + 1e-12;
    ElemMeasure = SimplexMeasure(XV, K, Mesh.AmbientDim);
    ElemEmbMeasure = SimplexMeasureT<DIM>(EV, K, Dim);

    GatherCandidates(C);
    const std::size_t p0 = out.PieceSite.size(), v0 = out.VoronoiVertexElement.size(),
                      b0 = out.BoundaryDualFaces.size();
    C.Queue.clear();
    C.Queue.push_back(C.Cand[0]);
    C.Slots[C.SlotOf(C.Cand[0])].Visited = true;
    std::size_t nextStart = 1;
    bool any = false, emptyVisit = false;
    for (std::size_t q = 0; q < C.Queue.size(); ++q)
    {
      const std::int32_t site = C.Queue[q];
      if (!ComputePiece(C, site))
      {
        emptyVisit = true;
        // Tie at the centroid: try the next nearest candidates until one has a piece.
        while (!any && q + 1 == C.Queue.size() && nextStart < C.Cand.size())
        {
          const std::int32_t s = C.Cand[nextStart++];
          const int sl = C.SlotOf(s);
          if (!C.Slots[sl].Visited)
          {
            C.Slots[sl].Visited = true;
            C.Queue.push_back(s);
          }
        }
        continue;
      }
      any = true;
      // Neighbours across bisector faces / edges also have pieces here.
      const std::vector<std::int32_t>& planes = (K == 2) ? C.EdgePlane : C.FacePlane;
      for (std::int32_t pl : planes)
        if (!IsFacet(pl))
        {
          const int sl = C.SlotOf(pl);
          if (!C.Slots[sl].Visited)
          {
            C.Slots[sl].Visited = true;
            C.Queue.push_back(pl);
          }
        }
      Emit(C, out, site);
    }
    out.ElemNearest.push_back(LastNearest);
    out.ElemEmptyVisit.push_back(emptyVisit);
    out.ElemPieces.push_back(static_cast<std::int32_t>(out.PieceSite.size() - p0));
    out.ElemVV.push_back(static_cast<std::int32_t>(out.VoronoiVertexElement.size() - v0));
    out.ElemBD.push_back(static_cast<std::int32_t>((out.BoundaryDualFaces.size() - b0) / K));
    C.ResetSites();
  }
};

template <int K, int DIM>
void RunBlocks(const SimplexMesh& mesh, const Embedding& emb, const SiteSet& sites,
  const RestrictedVoronoiOptions& opt, const std::vector<std::int32_t>& adj,
  std::vector<Chunk>& chunks, std::size_t blockSize, std::size_t first, std::size_t last,
  const std::int32_t* list)
{
  const std::size_t ns = sites.NumSites();
  SiteCloud<DIM> cloud{ sites.Coords.data(), ns, sites.Dim };
  SiteTree<DIM> tree(sites.Dim, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  int nbrk = opt.NumNeighbors > 0 ? opt.NumNeighbors : (K == 2 ? 32 : 64);
  nbrk = static_cast<int>(std::min<std::size_t>(nbrk, ns - 1));
  std::vector<std::uint32_t> nbr(ns * nbrk);
  std::vector<double> nbrd2(ns * nbrk);
  if (nbrk > 0)
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, ns), [&](const tbb::blocked_range<std::size_t>& r) {
      std::vector<std::uint32_t> idx(nbrk + 1);
      std::vector<double> d2(nbrk + 1);
      for (std::size_t s = r.begin(); s != r.end(); ++s)
      {
        const std::size_t got = tree.knnSearch(sites.At(s), nbrk + 1, idx.data(), d2.data());
        std::size_t w = 0;
        for (std::size_t q = 0; q < got && w < static_cast<std::size_t>(nbrk); ++q)
          if (idx[q] != s)
          {
            nbr[s * nbrk + w] = idx[q];
            nbrd2[s * nbrk + w] = d2[q];
            ++w;
          }
        for (; w < static_cast<std::size_t>(nbrk); ++w) // only with duplicates: repeat last
        {
          nbr[s * nbrk + w] = nbr[s * nbrk + w - 1];
          nbrd2[s * nbrk + w] = nbrd2[s * nbrk + w - 1];
        }
      }
    });

  tbb::enumerable_thread_specific<Context<K>> contexts;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks.size()),
    [&](const tbb::blocked_range<std::size_t>& r) {
      Context<K>& C = contexts.local();
      C.Init(sites.NumSites());
      Worker<K, DIM> w(mesh, emb, sites, opt, tree, adj, nbr, nbrd2, nbrk);
      for (std::size_t b = r.begin(); b != r.end(); ++b)
      {
        const std::size_t e0 = first + b * blockSize, e1 = std::min(last, e0 + blockSize);
        for (std::size_t e = e0; e < e1; ++e)
          w.ProcessElement(C, list ? list[e] : static_cast<std::int32_t>(e), chunks[b]);
      }
    });
}

template <int K>
void RunDim(int dim, const SimplexMesh& mesh, const Embedding& emb, const SiteSet& sites,
  const RestrictedVoronoiOptions& opt, const std::vector<std::int32_t>& adj,
  std::vector<Chunk>& chunks, std::size_t bs, std::size_t e0, std::size_t e1,
  const std::int32_t* list = nullptr)
{
  switch (dim)
  {
    case 2: RunBlocks<K, 2>(mesh, emb, sites, opt, adj, chunks, bs, e0, e1, list); break;
    case 3: RunBlocks<K, 3>(mesh, emb, sites, opt, adj, chunks, bs, e0, e1, list); break;
    case 4: RunBlocks<K, 4>(mesh, emb, sites, opt, adj, chunks, bs, e0, e1, list); break;
    case 5: RunBlocks<K, 5>(mesh, emb, sites, opt, adj, chunks, bs, e0, e1, list); break;
    case 6: RunBlocks<K, 6>(mesh, emb, sites, opt, adj, chunks, bs, e0, e1, list); break;
    case 8: RunBlocks<K, 8>(mesh, emb, sites, opt, adj, chunks, bs, e0, e1, list); break;
    default: RunBlocks<K, -1>(mesh, emb, sites, opt, adj, chunks, bs, e0, e1, list);
  }
}

// Throws when one of the elements (list, or [0, n) when list is null) is degenerate in the
// embedding: it cannot be clipped in barycentric coordinates.
void CheckDegenerateElements(const SimplexMesh& mesh, const Embedding& embedding,
  const std::int32_t* list, std::size_t n)
{
  const int K = mesh.SimplexDim, nv = K + 1;
  std::vector<char> bad(n, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i)
    {
      const std::size_t c = list ? static_cast<std::size_t>(list[i]) : i;
      const double* v[4];
      const std::int32_t* cell = mesh.Cell(c);
      double h2 = 0.0;
      for (int a = 0; a < nv; ++a)
        v[a] = embedding.At(cell[a]);
      const bool d8 = embedding.Dim == 8; // the usual embedding: compile-time loops
      for (int a = 0; a < nv; ++a)
        for (int b = a + 1; b < nv; ++b)
          h2 = std::max(h2, d8 ? Dist2<8>(v[a], v[b], 8) : Dist2<-1>(v[a], v[b], embedding.Dim));
      const double m = d8 ? SimplexMeasureT<8>(v, K, 8) : SimplexMeasure(v, K, embedding.Dim);
      bad[i] = !(m > 1e-12 * std::pow(std::sqrt(h2), K));
    }
  });
  for (std::size_t i = 0; i < n; ++i)
    if (bad[i])
      throw InputError("RestrictedVoronoi: embedded element " +
        std::to_string(list ? static_cast<std::size_t>(list[i]) : i) +
        " is degenerate (zero area/volume)");
}

} // namespace

// ---------------------------------------------------------------------------------------------
void ValidateRestrictedVoronoiInput(
  const SimplexMesh& mesh, const Embedding& emb, const SiteSet& sites)
{
  auto fail = [](const std::string& s) { throw InputError("RestrictedVoronoi: " + s); };
  if (mesh.SimplexDim != 2 && mesh.SimplexDim != 3)
    fail("the mesh must be made of triangles (SimplexDim 2) or tetrahedra (SimplexDim 3)");
  if (mesh.AmbientDim < mesh.SimplexDim || mesh.AmbientDim > 3)
    fail("AmbientDim must be between SimplexDim and 3");
  if (mesh.Points.empty() || mesh.Points.size() % mesh.AmbientDim != 0)
    fail("mesh points are empty or not a multiple of AmbientDim");
  if (mesh.Cells.empty() || mesh.Cells.size() % (mesh.SimplexDim + 1) != 0)
    fail("mesh cells are empty or not a multiple of SimplexDim+1");
  const std::size_t np = mesh.NumPoints();
  for (std::int32_t id : mesh.Cells)
    if (id < 0 || static_cast<std::size_t>(id) >= np)
      fail("a cell refers to a point id out of range");
  if (emb.Dim < mesh.AmbientDim)
    fail("embedding dimension is smaller than the mesh's AmbientDim");
  if (emb.Coords.size() != np * static_cast<std::size_t>(emb.Dim))
    fail("embedding has " + std::to_string(emb.Coords.size()) + " values, expected NumPoints x Dim = " +
      std::to_string(np * emb.Dim));
  for (double x : emb.Coords)
    if (!std::isfinite(x))
      fail("embedding contains NaN or infinite coordinates");
  const std::size_t ns = sites.NumSites();
  if (ns == 0)
    fail("no sites");
  if (sites.Dim != emb.Dim)
    fail("sites have dimension " + std::to_string(sites.Dim) + " but the embedding has " +
      std::to_string(emb.Dim));
  if (sites.Coords.size() != ns * static_cast<std::size_t>(sites.Dim) || sites.Bary.size() != 4 * ns)
    fail("site arrays have inconsistent sizes (Coords NumSites x Dim, Bary NumSites x 4)");
  if (ns > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    fail("too many sites");
  // Scale for the "site lies in its cell" test.
  double scale = 0.0;
  for (double x : emb.Coords)
    scale = std::max(scale, std::abs(x));
  scale = std::max(scale, 1e-300);
  const int nv = mesh.SimplexDim + 1;
  for (std::size_t s = 0; s < ns; ++s)
  {
    const std::int32_t c = sites.CellIds[s];
    if (c < 0 || static_cast<std::size_t>(c) >= mesh.NumCells())
      fail("site " + std::to_string(s) + " has a cell id out of range");
    const double* b = sites.Bary.data() + 4 * s;
    double sum = 0.0;
    for (int a = 0; a < 4; ++a)
    {
      if (!std::isfinite(b[a]))
        fail("site " + std::to_string(s) + " has NaN barycentric weights");
      if (a < nv && b[a] < -1e-8)
        fail("site " + std::to_string(s) + " has a negative barycentric weight (outside its cell)");
      if (a >= nv && b[a] != 0.0)
        fail("site " + std::to_string(s) + ": the 4th barycentric weight must be 0 on triangles");
      sum += b[a];
    }
    if (std::abs(sum - 1.0) > 1e-8)
      fail("site " + std::to_string(s) + " has barycentric weights that do not sum to 1");
    const std::int32_t* cell = mesh.Cell(c);
    for (int d = 0; d < emb.Dim; ++d)
    {
      double x = 0.0;
      for (int a = 0; a < nv; ++a)
        x += b[a] * emb.At(cell[a])[d];
      const double y = sites.Coords[s * emb.Dim + d];
      if (!std::isfinite(y))
        fail("site " + std::to_string(s) + " has NaN coordinates");
      if (std::abs(x - y) > 1e-6 * scale)
        fail("site " + std::to_string(s) +
          " is not at the barycentric position in its cell (site outside the mesh?)");
    }
  }
}

RestrictedVoronoiDiagram UpdateRestrictedVoronoi(const SimplexMesh& mesh,
  const Embedding& embedding, const SiteSet& sites, const RestrictedVoronoiDiagram& previous,
  const SiteSet& previousSites, const RestrictedVoronoiOptions& options)
{
  ValidateRestrictedVoronoiInput(mesh, embedding, sites);
  const int K = mesh.SimplexDim, nv = K + 1, dim = embedding.Dim;
  const std::size_t ns = sites.NumSites(), ns0 = previousSites.NumSites(), nc = mesh.NumCells();
  if (previous.NumSites != ns0 || previousSites.Dim != sites.Dim || ns0 > ns ||
    previousSites.Coords.size() != ns0 * static_cast<std::size_t>(dim))
    throw InputError("RestrictedVoronoi update: the previous diagram does not belong to the "
                     "previous sites, or the sites are not the previous ones followed by new ones");
  const auto& P = previous;
  const bool usable = !options.ComputeGeometry && !options.MergeBySite &&
    options.ElementBegin == 0 && options.ElementEnd < 0 && P.SimplexDim == K && P.Dim == dim &&
    P.AmbientDim == mesh.AmbientDim && P.ElementPieceOffsets.size() == nc + 1 &&
    P.ElementVoronoiVertexOffsets.size() == nc + 1 &&
    P.ElementBoundaryDualFaceOffsets.size() == nc + 1 && P.ElementNearestSite.size() == nc &&
    P.ElementBoundaryFacets.size() == nc && P.ElementEmptyVisit.size() == nc &&
    P.PieceSecurityRadius2.size() == P.NumPieces() && P.PieceLastCutDistance.size() == P.NumPieces() &&
    P.ElementPieceOffsets[nc] == static_cast<std::int64_t>(P.NumPieces()) &&
    P.PieceElement.size() == P.NumPieces() && P.PieceMeasure.size() == P.NumPieces() &&
    P.PieceEmbeddedMeasure.size() == P.NumPieces() &&
    P.ElementVoronoiVertexOffsets[nc] == static_cast<std::int64_t>(P.VoronoiVertexElement.size()) &&
    P.VoronoiVertexSites.size() == P.VoronoiVertexElement.size() * nv &&
    P.ElementBoundaryDualFaceOffsets[nc] * K == static_cast<std::int64_t>(P.BoundaryDualFaces.size());
  if (!usable)
    return ComputeRestrictedVoronoi(mesh, embedding, sites, options);

  // Changed sites: moved ones (old and new positions both matter) and appended ones.
  std::vector<char> moved(ns0, 0);
  std::vector<double> pts;
  for (std::size_t s = 0; s < ns; ++s)
  {
    const double* q = sites.At(s);
    if (s < ns0)
    {
      const double* o = previousSites.At(s);
      if (std::equal(q, q + dim, o))
        continue;
      moved[s] = 1;
      pts.insert(pts.end(), o, o + dim);
    }
    pts.insert(pts.end(), q, q + dim);
  }
  const std::size_t npts = pts.size() / dim;
  if (2 * npts > ns + ns0)
    return ComputeRestrictedVoronoi(mesh, embedding, sites, options);

  // Affected elements. A site j is a candidate of element e (GatherCandidates) unless it is
  // farther than e's nearest site n from every vertex of e, with a relative margin of 1e-9
  // (of the squared distances). An element whose candidates and nearest site are unchanged is
  // processed by exactly the same operations, hence copied. Here a changed position counts as
  // harmless only with a 100x larger margin, so that round-off cannot decide differently.
  std::vector<char> affected(nc, 0);
  if (npts > 0)
  {
    SiteCloud<-1> cloud{ pts.data(), npts, dim };
    SiteTree<-1> tree(dim, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nc), [&](const tbb::blocked_range<std::size_t>& r) {
      std::vector<std::pair<std::uint32_t, double>> hits;
      std::vector<double> c(dim);
      for (std::size_t e = r.begin(); e != r.end(); ++e)
      {
        const std::int32_t n = P.ElementNearestSite[e];
        if (n < 0 || static_cast<std::size_t>(n) >= ns0 || moved[n])
        {
          affected[e] = 1;
          continue;
        }
        const std::int32_t* cell = mesh.Cell(e);
        const double* v[4];
        for (int a = 0; a < nv; ++a)
          v[a] = embedding.At(cell[a]);
        std::fill(c.begin(), c.end(), 0.0);
        for (int a = 0; a < nv; ++a)
          for (int d = 0; d < dim; ++d)
            c[d] += v[a][d] / nv;
        double rho = 0.0;
        for (int a = 0; a < nv; ++a)
          rho = std::max(rho, Dist2<-1>(v[a], c.data(), dim));
        rho = std::sqrt(rho) * (1.0 + 1e-12);
        const double* pn = sites.At(n);
        // A position farther than R from c is farther than n from every vertex, by far more
        // than the margin (R(1 + 1e-6) against the 1e-9 of the test).
        const double R = (std::sqrt(Dist2<-1>(c.data(), pn, dim)) + 2.0 * rho) * (1.0 + 1e-6);
        hits.clear();
        tree.radiusSearch(c.data(), R * R, hits, nanoflann::SearchParams(32, 0.0, false));
        if (hits.empty())
          continue;
        double dn[4];
        for (int a = 0; a < nv; ++a)
          dn[a] = Dist2<-1>(v[a], pn, dim);
        const std::int64_t p0 = P.ElementPieceOffsets[e], p1 = P.ElementPieceOffsets[e + 1];
        for (const auto& h : hits)
        {
          const double* q = pts.data() + std::size_t(h.first) * dim;
          double scale = 0.0, gmin = std::numeric_limits<double>::infinity();
          for (int a = 0; a < nv; ++a)
          {
            const double dq = Dist2<-1>(v[a], q, dim);
            scale = std::max(scale, std::max(dq, dn[a]));
            gmin = std::min(gmin, dq - dn[a]);
          }
          if (gmin > 1e-7 * scale)
            continue; // not a candidate
          // A candidate: harmless if every piece (all visited sites have one) was final when
          // q came (q farther from the centroid than the piece's last cut) and the final piece
          // lies, with margin, on its site's side of the bisector: with D = |q - p_i| and R
          // the piece's security radius, |x - q|^2 - |x - p_i|^2 >= D (D - 2R) on the piece,
          // against Clip's fast-path margin 1e-9 (max_a |v_a - p_i| + D)^2.
          bool harmless = !P.ElementEmptyVisit[e] && p1 > p0;
          const double dqc = std::sqrt(Dist2<-1>(c.data(), q, dim));
          for (std::int64_t p = p0; p < p1 && harmless; ++p)
          {
            const std::int32_t i = P.PieceSite[p];
            if (static_cast<std::size_t>(i) >= ns0 || moved[i])
            {
              harmless = false;
              break;
            }
            const double last = P.PieceLastCutDistance[p];
            if (!(dqc > last * (1.0 + 1e-9) + 1e-300))
            {
              harmless = false;
              break;
            }
            const double* pi = sites.At(i);
            double rho2 = 0.0;
            for (int a = 0; a < nv; ++a)
              rho2 = std::max(rho2, Dist2<-1>(v[a], pi, dim));
            const double D = std::sqrt(Dist2<-1>(q, pi, dim));
            const double R = std::sqrt(static_cast<double>(P.PieceSecurityRadius2[p])) * (1.0 + 1e-9);
            const double bound = std::sqrt(rho2) + D;
            harmless = D > 2.0 * R && D * (D - 2.0 * R) > 1e-7 * bound * bound;
          }
          if (!harmless)
          {
            affected[e] = 1;
            break;
          }
        }
      }
    });
  }
  std::vector<std::int32_t> list;
  for (std::size_t e = 0; e < nc; ++e)
    if (affected[e])
      list.push_back(static_cast<std::int32_t>(e));
  if (10 * list.size() > 7 * nc)
    return ComputeRestrictedVoronoi(mesh, embedding, sites, options);
  CheckDegenerateElements(mesh, embedding, list.data(), list.size());

  // Clip the affected elements. Without geometry the kernel only asks whether a facet is on
  // the domain boundary: the boundary bits stand in for the adjacency.
  const std::size_t blockSize = 64;
  std::vector<Chunk> chunks((list.size() + blockSize - 1) / blockSize);
  if (!list.empty())
  {
    std::vector<std::int32_t> adj(nc * nv, 0);
    for (const std::int32_t e : list)
      for (int a = 0; a < nv; ++a)
        if (P.ElementBoundaryFacets[e] & (1u << a))
          adj[std::size_t(e) * nv + a] = -1;
    if (K == 2)
      RunDim<2>(dim, mesh, embedding, sites, options, adj, chunks, blockSize, 0, list.size(), list.data());
    else
      RunDim<3>(dim, mesh, embedding, sites, options, adj, chunks, blockSize, 0, list.size(), list.data());
  }

  // Where each recomputed element's output starts in its chunk.
  struct Src
  {
    std::int64_t P, V, B;
  };
  std::vector<Src> src(list.size());
  std::vector<std::int32_t> slot(nc, -1);
  for (std::size_t b = 0; b < chunks.size(); ++b)
  {
    Src o{ 0, 0, 0 };
    const Chunk& ch = chunks[b];
    for (std::size_t i = 0; i < ch.ElemNearest.size(); ++i)
    {
      const std::size_t k = b * blockSize + i;
      src[k] = o;
      slot[list[k]] = static_cast<std::int32_t>(k);
      o.P += ch.ElemPieces[i];
      o.V += ch.ElemVV[i];
      o.B += ch.ElemBD[i];
    }
  }

  RestrictedVoronoiDiagram out;
  out.SimplexDim = K;
  out.AmbientDim = mesh.AmbientDim;
  out.Dim = dim;
  out.NumSites = ns;
  out.NumRecomputedElements = list.size();
  out.ElementPieceOffsets.resize(nc + 1);
  out.ElementVoronoiVertexOffsets.resize(nc + 1);
  out.ElementBoundaryDualFaceOffsets.resize(nc + 1);
  out.ElementNearestSite.resize(nc);
  out.ElementEmptyVisit.resize(nc);
  out.ElementBoundaryFacets = P.ElementBoundaryFacets;
  out.ElementPieceOffsets[0] = out.ElementVoronoiVertexOffsets[0] =
    out.ElementBoundaryDualFaceOffsets[0] = 0;
  for (std::size_t e = 0; e < nc; ++e)
  {
    std::int64_t np, nvv, nbd;
    const std::int32_t k = slot[e];
    if (k < 0)
    {
      np = P.ElementPieceOffsets[e + 1] - P.ElementPieceOffsets[e];
      nvv = P.ElementVoronoiVertexOffsets[e + 1] - P.ElementVoronoiVertexOffsets[e];
      nbd = P.ElementBoundaryDualFaceOffsets[e + 1] - P.ElementBoundaryDualFaceOffsets[e];
      out.ElementNearestSite[e] = P.ElementNearestSite[e];
      out.ElementEmptyVisit[e] = P.ElementEmptyVisit[e];
    }
    else
    {
      const Chunk& ch = chunks[k / blockSize];
      const std::size_t i = k % blockSize;
      np = ch.ElemPieces[i];
      nvv = ch.ElemVV[i];
      nbd = ch.ElemBD[i];
      out.ElementNearestSite[e] = ch.ElemNearest[i];
      out.ElementEmptyVisit[e] = ch.ElemEmptyVisit[i];
    }
    out.ElementPieceOffsets[e + 1] = out.ElementPieceOffsets[e] + np;
    out.ElementVoronoiVertexOffsets[e + 1] = out.ElementVoronoiVertexOffsets[e] + nvv;
    out.ElementBoundaryDualFaceOffsets[e + 1] = out.ElementBoundaryDualFaceOffsets[e] + nbd;
  }
  const std::size_t np = out.ElementPieceOffsets[nc];
  out.PieceSite.resize(np);
  out.PieceElement.resize(np);
  out.PieceMeasure.resize(np);
  out.PieceEmbeddedMeasure.resize(np);
  out.PieceSecurityRadius2.resize(np);
  out.PieceLastCutDistance.resize(np);
  out.VoronoiVertexSites.resize(out.ElementVoronoiVertexOffsets[nc] * nv);
  out.VoronoiVertexElement.resize(out.ElementVoronoiVertexOffsets[nc]);
  out.BoundaryDualFaces.resize(out.ElementBoundaryDualFaceOffsets[nc] * K);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nc, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t e = r.begin(); e != r.end(); ++e)
    {
      const std::int64_t p1 = out.ElementPieceOffsets[e], v1 = out.ElementVoronoiVertexOffsets[e],
                         b1 = out.ElementBoundaryDualFaceOffsets[e];
      const std::int64_t pn = out.ElementPieceOffsets[e + 1] - p1,
                         vn = out.ElementVoronoiVertexOffsets[e + 1] - v1,
                         bn = out.ElementBoundaryDualFaceOffsets[e + 1] - b1;
      const std::int32_t k = slot[e];
      const std::int32_t *ps, *pe, *vs, *ve, *bd;
      const double *pm, *pem;
      const float *pr, *pl;
      if (k < 0)
      {
        const std::int64_t p0 = P.ElementPieceOffsets[e], v0 = P.ElementVoronoiVertexOffsets[e],
                           b0 = P.ElementBoundaryDualFaceOffsets[e];
        ps = P.PieceSite.data() + p0;
        pe = P.PieceElement.data() + p0;
        pm = P.PieceMeasure.data() + p0;
        pem = P.PieceEmbeddedMeasure.data() + p0;
        pr = P.PieceSecurityRadius2.data() + p0;
        pl = P.PieceLastCutDistance.data() + p0;
        vs = P.VoronoiVertexSites.data() + v0 * nv;
        ve = P.VoronoiVertexElement.data() + v0;
        bd = P.BoundaryDualFaces.data() + b0 * K;
      }
      else
      {
        const Chunk& ch = chunks[k / blockSize];
        const Src& o = src[k];
        ps = ch.PieceSite.data() + o.P;
        pe = ch.PieceElement.data() + o.P;
        pm = ch.PieceMeasure.data() + o.P;
        pem = ch.PieceEmbeddedMeasure.data() + o.P;
        pr = ch.PieceRadius2.data() + o.P;
        pl = ch.PieceLastCut.data() + o.P;
        vs = ch.VoronoiVertexSites.data() + o.V * nv;
        ve = ch.VoronoiVertexElement.data() + o.V;
        bd = ch.BoundaryDualFaces.data() + o.B * K;
      }
      std::copy_n(ps, pn, out.PieceSite.begin() + p1);
      std::copy_n(pe, pn, out.PieceElement.begin() + p1);
      std::copy_n(pm, pn, out.PieceMeasure.begin() + p1);
      std::copy_n(pem, pn, out.PieceEmbeddedMeasure.begin() + p1);
      std::copy_n(pr, pn, out.PieceSecurityRadius2.begin() + p1);
      std::copy_n(pl, pn, out.PieceLastCutDistance.begin() + p1);
      std::copy_n(vs, vn * nv, out.VoronoiVertexSites.begin() + v1 * nv);
      std::copy_n(ve, vn, out.VoronoiVertexElement.begin() + v1);
      std::copy_n(bd, bn * K, out.BoundaryDualFaces.begin() + b1 * K);
    }
  });
  // Same summation order as ComputeRestrictedVoronoi (bit-identical sums).
  out.SiteMeasure.assign(ns, 0.0);
  out.SiteEmbeddedMeasure.assign(ns, 0.0);
  for (std::size_t p = 0; p < np; ++p)
  {
    out.SiteMeasure[out.PieceSite[p]] += out.PieceMeasure[p];
    out.SiteEmbeddedMeasure[out.PieceSite[p]] += out.PieceEmbeddedMeasure[p];
  }
  return out;
}


RestrictedVoronoiDiagram ComputeRestrictedVoronoi(const SimplexMesh& mesh,
  const Embedding& embedding, const SiteSet& sites, const RestrictedVoronoiOptions& options)
{
  ValidateRestrictedVoronoiInput(mesh, embedding, sites);
  const int K = mesh.SimplexDim;
  const int nv = K + 1;
  const std::size_t ns = sites.NumSites();
  const std::size_t nc = mesh.NumCells();
  CheckDegenerateElements(mesh, embedding, nullptr, nc);
  std::vector<std::int32_t> ownAdjacency;
  if (!options.ElementAdjacency)
    ownAdjacency = ComputeElementAdjacency(mesh);
  else if (options.ElementAdjacency->size() != nc * static_cast<std::size_t>(nv))
    throw InputError("RestrictedVoronoi: ElementAdjacency has " +
      std::to_string(options.ElementAdjacency->size()) + " entries, expected NumCells x (SimplexDim+1) = " +
      std::to_string(nc * static_cast<std::size_t>(nv)) + " (pass ComputeElementAdjacency of this mesh)");
  const std::vector<std::int32_t>& adj = options.ElementAdjacency ? *options.ElementAdjacency : ownAdjacency;

  // Element range (a distributed run clips one block per process).
  if (options.ElementBegin < 0 || options.ElementBegin > static_cast<std::int64_t>(nc) ||
    (options.ElementEnd >= 0 &&
      (options.ElementEnd < options.ElementBegin || options.ElementEnd > static_cast<std::int64_t>(nc))))
    throw InputError("RestrictedVoronoi: element range [" + std::to_string(options.ElementBegin) +
      ", " + std::to_string(options.ElementEnd) + ") is not inside [0, " + std::to_string(nc) + ")");
  const std::size_t first = static_cast<std::size_t>(options.ElementBegin);
  const std::size_t last = options.ElementEnd < 0 ? nc : static_cast<std::size_t>(options.ElementEnd);
  const std::size_t blockSize = 256;
  std::vector<Chunk> chunks((last - first + blockSize - 1) / blockSize);
  if (K == 2)
    RunDim<2>(embedding.Dim, mesh, embedding, sites, options, adj, chunks, blockSize, first, last);
  else
    RunDim<3>(embedding.Dim, mesh, embedding, sites, options, adj, chunks, blockSize, first, last);

  // Concatenate the chunks in order (deterministic).
  RestrictedVoronoiDiagram out;
  out.SimplexDim = K;
  out.AmbientDim = mesh.AmbientDim;
  out.Dim = embedding.Dim;
  out.NumSites = ns;
  const std::size_t nchunk = chunks.size();
  std::vector<std::size_t> pOff(nchunk + 1, 0), vOff(nchunk + 1, 0), fOff(nchunk + 1, 0),
    fvOff(nchunk + 1, 0), vvOff(nchunk + 1, 0), bdOff(nchunk + 1, 0);
  for (std::size_t c = 0; c < nchunk; ++c)
  {
    pOff[c + 1] = pOff[c] + chunks[c].PieceSite.size();
    vOff[c + 1] = vOff[c] + chunks[c].VertexPlanes.size() / K;
    fOff[c + 1] = fOff[c] + chunks[c].FaceKind.size();
    fvOff[c + 1] = fvOff[c] + chunks[c].FaceVertices.size();
    vvOff[c + 1] = vvOff[c] + chunks[c].VoronoiVertexElement.size();
    bdOff[c + 1] = bdOff[c] + chunks[c].BoundaryDualFaces.size();
  }
  const std::size_t np = pOff[nchunk], nvx = vOff[nchunk], nf = fOff[nchunk];
  out.NumRecomputedElements = last - first;
  if (first == 0 && last == nc && !options.MergeBySite)
  {
    // Per-element ranges and references, for UpdateRestrictedVoronoi.
    out.ElementPieceOffsets.resize(nc + 1);
    out.ElementVoronoiVertexOffsets.resize(nc + 1);
    out.ElementBoundaryDualFaceOffsets.resize(nc + 1);
    out.ElementNearestSite.resize(nc);
    out.ElementEmptyVisit.resize(nc);
    out.PieceSecurityRadius2.resize(np);
    out.PieceLastCutDistance.resize(np);
    out.ElementPieceOffsets[0] = out.ElementVoronoiVertexOffsets[0] =
      out.ElementBoundaryDualFaceOffsets[0] = 0;
    std::size_t e = 0;
    for (const Chunk& ch : chunks)
      for (std::size_t i = 0; i < ch.ElemNearest.size(); ++i, ++e)
      {
        out.ElementNearestSite[e] = ch.ElemNearest[i];
        out.ElementEmptyVisit[e] = ch.ElemEmptyVisit[i];
        out.ElementPieceOffsets[e + 1] = out.ElementPieceOffsets[e] + ch.ElemPieces[i];
        out.ElementVoronoiVertexOffsets[e + 1] = out.ElementVoronoiVertexOffsets[e] + ch.ElemVV[i];
        out.ElementBoundaryDualFaceOffsets[e + 1] =
          out.ElementBoundaryDualFaceOffsets[e] + ch.ElemBD[i];
      }
    out.ElementBoundaryFacets.assign(nc, 0);
    for (std::size_t c = 0; c < nc; ++c)
      for (int a = 0; a < nv; ++a)
        if (adj[c * nv + a] < 0)
          out.ElementBoundaryFacets[c] |= static_cast<std::uint8_t>(1u << a);
  }
  const bool geom = options.ComputeGeometry;
  const bool emb = geom && options.KeepEmbeddedPoints;
  const int adim = mesh.AmbientDim, dim = embedding.Dim;
  out.PieceSite.resize(np);
  out.PieceElement.resize(np);
  out.PieceMeasure.resize(np);
  out.PieceEmbeddedMeasure.resize(np);
  out.VoronoiVertexSites.resize(vvOff[nchunk] * nv);
  out.VoronoiVertexElement.resize(vvOff[nchunk]);
  out.BoundaryDualFaces.resize(bdOff[nchunk]);
  std::vector<std::int64_t> pvCount, pfCount, fSize;
  if (geom)
  {
    out.Points.resize(nvx * adim);
    if (emb)
      out.EmbeddedPoints.resize(nvx * dim);
    out.VertexPlanes.resize(nvx * K);
    out.FaceVertices.resize(fvOff[nchunk]);
    out.FaceKind.resize(nf);
    out.FaceNeighbor.resize(nf);
    pvCount.resize(np);
    pfCount.resize(np);
    fSize.resize(nf);
  }
  tbb::parallel_for(std::size_t(0), nchunk, [&](std::size_t c) {
    Chunk& ch = chunks[c];
    std::copy(ch.PieceSite.begin(), ch.PieceSite.end(), out.PieceSite.begin() + pOff[c]);
    std::copy(ch.PieceElement.begin(), ch.PieceElement.end(), out.PieceElement.begin() + pOff[c]);
    std::copy(ch.PieceMeasure.begin(), ch.PieceMeasure.end(), out.PieceMeasure.begin() + pOff[c]);
    std::copy(ch.PieceEmbeddedMeasure.begin(), ch.PieceEmbeddedMeasure.end(),
      out.PieceEmbeddedMeasure.begin() + pOff[c]);
    if (!out.PieceSecurityRadius2.empty())
    {
      std::copy(ch.PieceRadius2.begin(), ch.PieceRadius2.end(), out.PieceSecurityRadius2.begin() + pOff[c]);
      std::copy(ch.PieceLastCut.begin(), ch.PieceLastCut.end(), out.PieceLastCutDistance.begin() + pOff[c]);
    }
    std::copy(ch.VoronoiVertexSites.begin(), ch.VoronoiVertexSites.end(),
      out.VoronoiVertexSites.begin() + vvOff[c] * nv);
    std::copy(ch.VoronoiVertexElement.begin(), ch.VoronoiVertexElement.end(),
      out.VoronoiVertexElement.begin() + vvOff[c]);
    std::copy(ch.BoundaryDualFaces.begin(), ch.BoundaryDualFaces.end(),
      out.BoundaryDualFaces.begin() + bdOff[c]);
    if (geom)
    {
      std::copy(ch.Points.begin(), ch.Points.end(), out.Points.begin() + vOff[c] * adim);
      if (emb)
        std::copy(ch.EmbeddedPoints.begin(), ch.EmbeddedPoints.end(),
          out.EmbeddedPoints.begin() + vOff[c] * dim);
      std::copy(ch.VertexPlanes.begin(), ch.VertexPlanes.end(), out.VertexPlanes.begin() + vOff[c] * K);
      for (std::size_t i = 0; i < ch.FaceVertices.size(); ++i)
        out.FaceVertices[fvOff[c] + i] = ch.FaceVertices[i] + static_cast<std::int32_t>(vOff[c]);
      std::copy(ch.FaceKind.begin(), ch.FaceKind.end(), out.FaceKind.begin() + fOff[c]);
      std::copy(ch.FaceNeighbor.begin(), ch.FaceNeighbor.end(), out.FaceNeighbor.begin() + fOff[c]);
      std::copy(ch.PieceVertexCount.begin(), ch.PieceVertexCount.end(), pvCount.begin() + pOff[c]);
      std::copy(ch.PieceFaceCount.begin(), ch.PieceFaceCount.end(), pfCount.begin() + pOff[c]);
      std::copy(ch.FaceSize.begin(), ch.FaceSize.end(), fSize.begin() + fOff[c]);
    }
    ch = Chunk(); // release memory early
  });
  if (nvx > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    throw InputError("RestrictedVoronoi: output too large (more than 2^31 vertices)");
  if (geom)
  {
    out.PieceVertexOffsets.resize(np + 1, 0);
    out.PieceFaceOffsets.resize(np + 1, 0);
    out.FaceOffsets.resize(nf + 1, 0);
    for (std::size_t p = 0; p < np; ++p)
    {
      out.PieceVertexOffsets[p + 1] = out.PieceVertexOffsets[p] + pvCount[p];
      out.PieceFaceOffsets[p + 1] = out.PieceFaceOffsets[p] + pfCount[p];
    }
    for (std::size_t f = 0; f < nf; ++f)
      out.FaceOffsets[f + 1] = out.FaceOffsets[f] + fSize[f];
  }
  out.SiteMeasure.assign(ns, 0.0);
  out.SiteEmbeddedMeasure.assign(ns, 0.0);
  for (std::size_t p = 0; p < np; ++p)
  {
    out.SiteMeasure[out.PieceSite[p]] += out.PieceMeasure[p];
    out.SiteEmbeddedMeasure[out.PieceSite[p]] += out.PieceEmbeddedMeasure[p];
  }

  if (options.MergeBySite)
  {
    // Reorder pieces by site (stable: elements stay in order). Vertices are renumbered so that
    // every piece's vertices stay contiguous.
    std::vector<std::size_t> perm(np);
    std::iota(perm.begin(), perm.end(), 0);
    std::stable_sort(perm.begin(), perm.end(),
      [&](std::size_t a, std::size_t b) { return out.PieceSite[a] < out.PieceSite[b]; });
    RestrictedVoronoiDiagram m;
    m.SimplexDim = out.SimplexDim;
    m.AmbientDim = out.AmbientDim;
    m.Dim = out.Dim;
    m.NumSites = out.NumSites;
    m.NumRecomputedElements = out.NumRecomputedElements;
    m.SiteMeasure = std::move(out.SiteMeasure);
    m.SiteEmbeddedMeasure = std::move(out.SiteEmbeddedMeasure);
    m.VoronoiVertexSites = std::move(out.VoronoiVertexSites);
    m.VoronoiVertexElement = std::move(out.VoronoiVertexElement);
    m.BoundaryDualFaces = std::move(out.BoundaryDualFaces);
    m.PieceVertexOffsets.push_back(0);
    m.PieceFaceOffsets.push_back(0);
    m.FaceOffsets.push_back(0);
    for (std::size_t q = 0; q < np; ++q)
    {
      const std::size_t p = perm[q];
      m.PieceSite.push_back(out.PieceSite[p]);
      m.PieceElement.push_back(out.PieceElement[p]);
      m.PieceMeasure.push_back(out.PieceMeasure[p]);
      m.PieceEmbeddedMeasure.push_back(out.PieceEmbeddedMeasure[p]);
      if (!geom)
        continue;
      const std::int64_t v0 = out.PieceVertexOffsets[p], v1 = out.PieceVertexOffsets[p + 1];
      const std::int64_t shift = static_cast<std::int64_t>(m.VertexPlanes.size() / K) - v0;
      m.Points.insert(m.Points.end(), out.Points.begin() + v0 * adim, out.Points.begin() + v1 * adim);
      if (emb)
        m.EmbeddedPoints.insert(m.EmbeddedPoints.end(), out.EmbeddedPoints.begin() + v0 * dim,
          out.EmbeddedPoints.begin() + v1 * dim);
      m.VertexPlanes.insert(m.VertexPlanes.end(), out.VertexPlanes.begin() + v0 * K,
        out.VertexPlanes.begin() + v1 * K);
      for (std::int64_t f = out.PieceFaceOffsets[p]; f < out.PieceFaceOffsets[p + 1]; ++f)
      {
        for (std::int64_t i = out.FaceOffsets[f]; i < out.FaceOffsets[f + 1]; ++i)
          m.FaceVertices.push_back(static_cast<std::int32_t>(out.FaceVertices[i] + shift));
        m.FaceOffsets.push_back(static_cast<std::int64_t>(m.FaceVertices.size()));
        m.FaceKind.push_back(out.FaceKind[f]);
        m.FaceNeighbor.push_back(out.FaceNeighbor[f]);
      }
      m.PieceVertexOffsets.push_back(static_cast<std::int64_t>(m.VertexPlanes.size() / K));
      m.PieceFaceOffsets.push_back(static_cast<std::int64_t>(m.FaceKind.size()));
    }
    if (!geom)
    {
      m.PieceVertexOffsets.clear();
      m.PieceFaceOffsets.clear();
      m.FaceOffsets.clear();
    }
    return m;
  }
  return out;
}

} // namespace av
