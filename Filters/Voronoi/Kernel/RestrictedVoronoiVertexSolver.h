// SPDX-License-Identifier: BSD-3-Clause
// Internal to the Voronoi kernel: VertexSolver, the barycentric coordinates of a piece vertex
// from its symbolic labels (facets + equidistant sites), cached per element.
#ifndef av_RestrictedVoronoiVertexSolver_h
#define av_RestrictedVoronoiVertexSolver_h

#include "RestrictedVoronoiContext.h"
#include "RestrictedVoronoiElementFrame.h"
#include "RestrictedVoronoiPrimitives.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

namespace av
{
namespace rvd
{

template <int K, int DIM>
class VertexSolver
{
public:
  static constexpr int NV = K + 1;

  explicit VertexSolver(const ElementFrame<K, DIM>& frame)
    : F(frame)
  {
  }

  /// Barycentric coordinates of the vertex of piece `site` with labels `pl`, computed from the
  /// sorted labels only, so every piece of the element gets the same bits. False if singular;
  /// s0out: the smallest site of the label set.
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

  /// The smallest site label (INT32_MAX if all are facets): the classification reference.
  static std::int32_t MinSiteLabel(const std::array<std::int32_t, K>& pl)
  {
    std::int32_t s0 = std::numeric_limits<std::int32_t>::max();
    for (int a = 0; a < K; ++a)
      if (!IsFacet(pl[a]))
        s0 = std::min(s0, pl[a]);
    return s0;
  }

private:
  const ElementFrame<K, DIM>& F;

  // Solves the vertex of a sorted key (site + K labels): sum of the free lambdas = 1 and
  // equal distance to every site of the key.
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
    const double* d0 = F.DRow(C, S[0]);
    for (int r = 1; r < ns; ++r)
    {
      const double* dr = F.DRow(C, S[r]);
      for (int c = 0; c < n; ++c)
        M[r][c] = d0[fr[c]] - dr[fr[c]];
      M[r][n] = 0.0;
    }
    double x[4];
    if (!SolveLinear(M, n, x))
      return false;
    for (int c = 0; c < n; ++c)
    {
      if (!std::isfinite(x[c]))
        return false;
      lam[fr[c]] = x[c];
    }
    return true;
  }

  // Gaussian elimination with partial pivoting (deterministic for given input) of the n x n
  // system M (right-hand side in column n). False if a pivot is zero.
  static bool SolveLinear(double (&M)[4][5], int n, double (&x)[4])
  {
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
    for (int c = n - 1; c >= 0; --c)
    {
      double s = M[c][n];
      for (int cc = c + 1; cc < n; ++cc)
        s -= M[c][cc] * x[cc];
      x[c] = s / M[c][c];
    }
    return true;
  }
};

} // namespace rvd
} // namespace av

#endif
