// SPDX-License-Identifier: BSD-3-Clause
// Internal to the Voronoi kernel: PolytopeClipper, the piece of one site in the current element,
// clipped by the bisectors of the element's candidates in barycentric coordinates.
#ifndef av_RestrictedVoronoiClipper_h
#define av_RestrictedVoronoiClipper_h

#include "RestrictedVoronoiContext.h"
#include "RestrictedVoronoiElementFrame.h"
#include "RestrictedVoronoiPrimitives.h"
#include "RestrictedVoronoiVertexSolver.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>

namespace av
{
namespace rvd
{

/**
 * Polytopes in the element's barycentric coordinates (k = 2: polygon with per-edge planes,
 * Sutherland-Hodgman; k = 3: polyhedron as faces with vertex loops, a cut makes one vertex per
 * crossing edge and a cap face). Every decision about a vertex is taken from its symbolic
 * labels, so all pieces of the element agree bit for bit.
 */
template <int K, int DIM>
class PolytopeClipper
{
public:
  static constexpr int NV = K + 1;

  explicit PolytopeClipper(const ElementFrame<K, DIM>& frame)
    : F(frame)
    , Solver(frame)
  {
  }

  /// Computes the piece of `site` in the current element; false if empty. Only the element's
  /// candidates (C.Cand, see CandidateFinder) can cut it; they are sorted by distance to the
  /// centroid, so |p_m - p_site| >= dc(m) - dc(site) gives the security radius stop.
  /// Leaves C.PieceR2 and C.PieceLastCut for the incremental update.
  bool ComputePiece(Context<K>& C, std::int32_t site) const
  {
    InitPolytope(C);
    double r2 = Radius2(C, site);
    double rr = std::sqrt(r2);
    C.PieceLastCut = -1.0;
    const double dci = F.DCentroid(C, site);
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
      if (dcm > (rr + F.Rho) * (1.0 + 1e-9))
        break;
      // Cheap reject: the element's bounding ball is entirely on site's side.
      if (dcm - F.Rho > dci + F.Rho)
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

  /// The piece of `site` when it is the whole element (no candidate can cut it), with the
  /// C.PieceR2 / C.PieceLastCut that ComputePiece would leave. Needs only the frame's
  /// vertices (LoadVertices).
  void WholeElement(Context<K>& C, std::int32_t site) const
  {
    InitPolytope(C);
    // Radius2 of the unit lambdas, without L: each vertex's sum is 1 x D[b] plus exact zeros
    // (0 x D[a], 0 x 0 x L), so it is D[b] to the bit and the maximum is the same.
    const double* di = F.DRow(C, site);
    double r2 = 0.0;
    for (int b = 0; b < NV; ++b)
      r2 = std::max(r2, di[b]);
    C.PieceR2 = r2;
    C.PieceLastCut = -1.0;
  }

  /// The whole element: its K+1 vertices, facets as planes.
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

  /// Clips the current polytope of piece `site` by the bisector with m.
  /// Returns 0: unchanged, 1: cut, -1: empty.
  int Clip(Context<K>& C, std::int32_t site, std::int32_t m) const
  {
    // Copies: DRow of a new site grows the slot array (pointers would dangle).
    double dm[NV], di[NV];
    std::copy_n(F.DRow(C, m), NV, dm);
    std::copy_n(F.DRow(C, site), NV, di);
    if (ClearlyInside(C, dm, di))
      return 0;
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
      ClipPolygon(C, site, m);
    else
      ClipPolyhedron(C, site, m);
    UpdateAlive(C, oldSize);
    return 1;
  }

private:
  const ElementFrame<K, DIM>& F;
  VertexSolver<K, DIM> Solver;

  // Fast path: with the piece's own site as reference, every vertex is clearly on the site's
  // side (margin far above round-off), so the exact classification would keep all.
  bool ClearlyInside(const Context<K>& C, const double* dm, const double* di) const
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
      return true;
    double gmin = std::numeric_limits<double>::infinity();
    for (const std::int32_t id : C.Alive)
    {
      const Vert<K>& v = C.V[id];
      double g = 0.0;
      for (int a = 0; a < NV; ++a)
        g += v.Lam[a] * (dm[a] - di[a]);
      gmin = std::min(gmin, g);
    }
    return gmin > 1e-9 * scale;
  }

  // Classification of vertex v of piece `site` against the bisector with site m (dm, di: the
  // rows of m and site): the reference is the smallest site of v's labels and `site`.
  void Classify(Context<K>& C, std::int32_t site, Vert<K>& v, std::int32_t m, const double* dm,
    const double* di) const
  {
    const std::int32_t s0 = std::min(site, v.MinSite);
    const double* d0 = s0 == site ? di : F.DRow(C, s0);
    double g = 0.0;
    for (int a = 0; a < NV; ++a)
      g += v.Lam[a] * (dm[a] - d0[a]);
    v.G = g;
    v.Out = g < 0.0 || (g == 0.0 && m < s0);
  }

  // K = 2: Sutherland-Hodgman step on the loop, the new edge carries plane m.
  void ClipPolygon(Context<K>& C, std::int32_t site, std::int32_t m) const
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

  // K = 3: every face keeps its inside part (a new vertex per crossing edge, shared by the
  // edge's two faces), then the cap face on plane m closes the polyhedron.
  void ClipPolyhedron(Context<K>& C, std::int32_t site, std::int32_t m) const
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
    AppendCap(C, nl, nn, m);
    C.NLoops.resize(static_cast<std::size_t>(nn));
    std::swap(C.FacePlane, C.NFacePlane);
    std::swap(C.FaceStart, C.NFaceStart);
    std::swap(C.FaceCount, C.NFaceCount);
    std::swap(C.Loops, C.NLoops);
  }

  // Cap face on the new plane: walk enter -> exit links (reverse of the faces' direction).
  void AppendCap(Context<K>& C, std::int32_t* nl, std::int32_t& nn, std::int32_t m) const
  {
    if (C.CapNext.size() < 3)
      return;
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

  // Live vertices: the kept ones, then the new ones.
  void UpdateAlive(Context<K>& C, std::size_t oldSize) const
  {
    std::size_t w = 0;
    for (const std::int32_t id : C.Alive)
      if (!C.V[id].Out)
        C.Alive[w++] = id;
    C.Alive.resize(w);
    for (std::size_t id = oldSize; id < C.V.size(); ++id)
      C.Alive.push_back(static_cast<std::int32_t>(id));
  }

  // New vertex on the edge u-w (labels: the K-1 common planes + the new one).
  std::int32_t NewVertex(Context<K>& C, std::int32_t site, std::int32_t u, std::int32_t w,
    const std::array<std::int32_t, K - 1>& common, std::int32_t m) const
  {
    Vert<K> nv;
    for (int a = 0; a < K - 1; ++a)
      nv.Pl[a] = common[a];
    nv.Pl[K - 1] = m;
    std::int32_t s0;
    if (!Solver.SolveVertex(C, site, nv.Pl, nv.Lam, s0))
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
    nv.MinSite = VertexSolver<K, DIM>::MinSiteLabel(nv.Pl);
    C.V.push_back(nv);
    return static_cast<std::int32_t>(C.V.size() - 1);
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

  // Squared security radius: the largest squared embedding distance from a live vertex to
  // the site, from the barycentric coordinates and the squared edge lengths.
  double Radius2(Context<K>& C, std::int32_t site) const
  {
    const double* di = F.DRow(C, site);
    double r2 = 0.0;
    for (const std::int32_t id : C.Alive)
    {
      const Vert<K>& v = C.V[id];
      double s = 0.0;
      for (int a = 0; a < NV; ++a)
        s += v.Lam[a] * di[a];
      for (int a = 0; a < NV; ++a)
        for (int b = a + 1; b < NV; ++b)
          s -= v.Lam[a] * v.Lam[b] * F.L[a][b];
      r2 = std::max(r2, s);
    }
    return r2;
  }
};

} // namespace rvd
} // namespace av

#endif
