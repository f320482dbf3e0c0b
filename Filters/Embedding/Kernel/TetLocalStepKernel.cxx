// SPDX-License-Identifier: BSD-3-Clause
#include "TetLocalStepKernel.h"

#include "SimdClones.h"

#include <algorithm>
#include <cmath>

// The 256-bit vector helpers below are always inlined into the kernels, so the ABI note GCC
// gives for passing them by value without AVX does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace av
{
namespace
{
// Four elements, one per lane; no alignment assumed.
typedef double V4 __attribute__((vector_size(32), aligned(8)));

// Symmetric 3x3 as 6 lanes-vectors: 00, 11, 22, 01, 12, 02.
struct Sym
{
  V4 v[6];
  V4 operator()(int r, int c) const
  {
    static constexpr int idx[3][3] = { { 0, 3, 5 }, { 3, 1, 4 }, { 5, 4, 2 } };
    return v[idx[r][c]];
  }
};

/// S = X Y X for symmetric X, Y (the result is symmetric).
inline __attribute__((always_inline)) Sym Sandwich(const Sym& x, const Sym& y)
{
  V4 m[3][3]; // X Y
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      m[r][c] = x(r, 0) * y(0, c) + x(r, 1) * y(1, c) + x(r, 2) * y(2, c);
    }
  }
  const auto at = [&](int r, int c) { return m[r][0] * x(0, c) + m[r][1] * x(1, c) + m[r][2] * x(2, c); };
  return Sym{ { at(0, 0), at(1, 1), at(2, 2), at(0, 1), at(1, 2), at(0, 2) } };
}

inline __attribute__((always_inline)) V4 Sqrt(V4 v)
{
  return V4{ std::sqrt(v[0]), std::sqrt(v[1]), std::sqrt(v[2]), std::sqrt(v[3]) };
}

// The steps of the kernel, force-inlined into each clone-dispatched entry point: one loop body
// per clone, so splitting the kernel changes neither the instructions nor the results.
#define AV_INLINE inline __attribute__((always_inline))

/// Gathers G, A and w of the four elements e[0..3] into lanes.
AV_INLINE void LoadElements(
  const TetLocalStepData& d, const std::size_t (&e)[4], V4 (&g)[4][3], Sym& a, V4& w)
{
  for (int q = 0; q < 4; ++q)
  {
    const double* gq = d.Gt + e[q] * 12;
    for (int l = 0; l < 4; ++l)
    {
      for (int c = 0; c < 3; ++c)
      {
        g[l][c][q] = gq[l * 3 + c];
      }
    }
    const double* aq = d.A + e[q] * 9;
    a.v[0][q] = aq[0];
    a.v[1][q] = aq[4];
    a.v[2][q] = aq[8];
    a.v[3][q] = aq[3];
    a.v[4][q] = aq[7];
    a.v[5][q] = aq[6];
    w[q] = d.W[e[q]];
  }
}

/// Free rows of T: tf[f][c] = sum_l x_l^(3+f) g_l[c].
template <int FT>
AV_INLINE void FreeRows(const TetLocalStepData& d, std::size_t stride, const std::size_t (&e)[4],
  const V4 (&g)[4][3], V4 (&tf)[FT][3])
{
  for (int l = 0; l < 4; ++l)
  {
    const double* xq[4];
    for (int q = 0; q < 4; ++q)
    {
      xq[q] = d.X + static_cast<std::size_t>(d.Cells[e[q] * 4 + l]) * stride + 3;
    }
    for (int f = 0; f < FT; ++f)
    {
      const V4 xv = { xq[0][f], xq[1][f], xq[2][f], xq[3][f] };
      for (int c = 0; c < 3; ++c)
      {
        tf[f][c] += xv * g[l][c];
      }
    }
  }
}

/// I + T_fᵀT_f.
template <int FT>
AV_INLINE Sym IdentityPlusGram(const V4 (&tf)[FT][3])
{
  Sym p = {};
  for (int f = 0; f < FT; ++f)
  {
    p.v[0] += tf[f][0] * tf[f][0];
    p.v[1] += tf[f][1] * tf[f][1];
    p.v[2] += tf[f][2] * tf[f][2];
    p.v[3] += tf[f][0] * tf[f][1];
    p.v[4] += tf[f][1] * tf[f][2];
    p.v[5] += tf[f][0] * tf[f][2];
  }
  p.v[0] += 1.0;
  p.v[1] += 1.0;
  p.v[2] += 1.0;
  return p;
}

/// tr C^{1/2} per lane from the invariants of C (and i3 = √ic3): Newton on
/// (s² − ic1)² − 8 √ic3 s − 4 ic2 from an upper bound; ok[q] is false for lanes that are
/// ill-conditioned or do not converge.
AV_INLINE V4 TraceOfSqrt(V4 ic1, V4 ic2, V4 ic3, V4& i3, bool (&ok)[4])
{
  for (int q = 0; q < 4; ++q)
  {
    ok[q] = ic3[q] > 1e-8 * ic1[q] * ic2[q] && ic2[q] > 0.0;
  }
  i3 = Sqrt(ic3);
  V4 s = Sqrt(ic1 + 2.0 * Sqrt(3.0 * ic2));
  bool done[4] = { !ok[0], !ok[1], !ok[2], !ok[3] };
  for (int it = 0; it < 60 && !(done[0] && done[1] && done[2] && done[3]); ++it)
  {
    const V4 qv = s * s - ic1;
    const V4 ds = (qv * qv - 8.0 * i3 * s - 4.0 * ic2) / (4.0 * s * qv - 8.0 * i3);
    for (int q = 0; q < 4; ++q)
    {
      if (!done[q])
      {
        s[q] -= ds[q];
        done[q] = std::abs(ds[q]) <= 1e-7 * s[q];
      }
    }
  }
  for (int q = 0; q < 4; ++q)
  {
    ok[q] = ok[q] && done[q] && std::isfinite(s[q]);
  }
  return s;
}

/// C^{-1/2} per lane by Cayley–Hamilton from the invariants of U = C^{1/2}; ok as TraceOfSqrt.
AV_INLINE Sym InverseSqrt(const Sym& cm, bool (&ok)[4])
{
  const V4 c00 = cm.v[0], c11 = cm.v[1], c22 = cm.v[2], c01 = cm.v[3], c12 = cm.v[4],
           c02 = cm.v[5];
  const V4 ic1 = c00 + c11 + c22;
  const V4 ic2 = c00 * c11 + c11 * c22 + c00 * c22 - c01 * c01 - c12 * c12 - c02 * c02;
  const V4 ic3 = c00 * (c11 * c22 - c12 * c12) - c01 * (c01 * c22 - c12 * c02) +
    c02 * (c01 * c12 - c11 * c02);
  V4 i3;
  const V4 s = TraceOfSqrt(ic1, ic2, ic3, i3, ok);
  const V4 i1 = s, i2 = 0.5 * (s * s - ic1);
  // U = ((i1² − i2) C − C² + i1 i3 I) / (i1 i2 − i3); C^{-1/2} = (C − i1 U + i2 I) / i3.
  Sym c2;
  c2.v[0] = c00 * c00 + c01 * c01 + c02 * c02;
  c2.v[1] = c01 * c01 + c11 * c11 + c12 * c12;
  c2.v[2] = c02 * c02 + c12 * c12 + c22 * c22;
  c2.v[3] = c00 * c01 + c01 * c11 + c02 * c12;
  c2.v[4] = c01 * c02 + c11 * c12 + c12 * c22;
  c2.v[5] = c00 * c02 + c01 * c12 + c02 * c22;
  const V4 ru = 1.0 / (i1 * i2 - i3), ri3 = 1.0 / i3, k2 = i1 * i1 - i2;
  Sym cinv;
  for (int k = 0; k < 6; ++k)
  {
    V4 u = k2 * cm.v[k] - c2.v[k];
    if (k < 3)
    {
      u += i1 * i3;
    }
    u *= ru;
    V4 ci = cm.v[k] - i1 * u;
    if (k < 3)
    {
      ci += i2;
    }
    cinv.v[k] = ci * ri3;
  }
  return cinv;
}

/// R_f = T_f N and the (unweighted) element energy ‖I − N‖² + ‖T_f − R_f‖².
template <int FT>
AV_INLINE V4 Rotate(const V4 (&tf)[FT][3], const Sym& n, V4 (&rf)[FT][3])
{
  V4 eb = (1.0 - n.v[0]) * (1.0 - n.v[0]) + (1.0 - n.v[1]) * (1.0 - n.v[1]) +
    (1.0 - n.v[2]) * (1.0 - n.v[2]) + 2.0 * (n.v[3] * n.v[3] + n.v[4] * n.v[4] + n.v[5] * n.v[5]);
  for (int f = 0; f < FT; ++f)
  {
    for (int c = 0; c < 3; ++c)
    {
      rf[f][c] = tf[f][0] * n(0, c) + tf[f][1] * n(1, c) + tf[f][2] * n(2, c);
      const V4 dlt = tf[f][c] - rf[f][c];
      eb += dlt * dlt;
    }
  }
  return eb;
}

/// C = w G R_fᵀ for the `count` real lanes whose element succeeded.
template <int FT>
AV_INLINE void StoreRightHandSides(const TetLocalStepData& d, const std::size_t (&e)[4], int count,
  const bool (&ok)[4], const V4 (&g)[4][3], V4 w, const V4 (&rf)[FT][3])
{
  for (int l = 0; l < 4; ++l)
  {
    for (int f = 0; f < FT; ++f)
    {
      const V4 cv = w * (g[l][0] * rf[f][0] + g[l][1] * rf[f][1] + g[l][2] * rf[f][2]);
      for (int q = 0; q < count; ++q)
      {
        if (ok[q])
        {
          d.C[(e[q] * 4 + static_cast<std::size_t>(l)) * FT + static_cast<std::size_t>(f)] = cv[q];
        }
      }
    }
  }
}

template <int FT>
AV_INLINE double Kernel(
  const TetLocalStepData& d, std::size_t j0, std::size_t j1, std::vector<std::int32_t>& failed)
{
  double energy = 0.0;
  const std::size_t stride = static_cast<std::size_t>(d.Stride);
  for (std::size_t j = j0; j < j1; j += 4)
  {
    const int count = static_cast<int>(std::min<std::size_t>(4, j1 - j));
    std::size_t e[4];
    for (int q = 0; q < 4; ++q)
    {
      e[q] = j + static_cast<std::size_t>(std::min(q, count - 1)); // pad with the last element
    }
    V4 g[4][3], w;
    Sym a;
    LoadElements(d, e, g, a, w);
    V4 tf[FT][3] = {};
    FreeRows<FT>(d, stride, e, g, tf);
    const Sym cm = Sandwich(a, IdentityPlusGram<FT>(tf)); // BᵀB
    bool ok[4];
    const Sym n = Sandwich(a, InverseSqrt(cm, ok));
    V4 rf[FT][3];
    V4 eb = Rotate<FT>(tf, n, rf);
    eb *= w;
    for (int q = 0; q < count; ++q)
    {
      if (!ok[q])
      {
        failed.push_back(static_cast<std::int32_t>(j + static_cast<std::size_t>(q)));
        continue;
      }
      energy += eb[q];
    }
    StoreRightHandSides<FT>(d, e, count, ok, g, w, rf);
  }
  return energy;
}

#undef AV_INLINE

// One clone-dispatched entry point per free-dimension count.
#define AV_TET_KERNEL(FT)                                                                         \
  AV_SIMD_CLONES double Kernel##FT(const TetLocalStepData& d, std::size_t j0, std::size_t j1,    \
    std::vector<std::int32_t>& failed)                                                            \
  {                                                                                               \
    return Kernel<FT>(d, j0, j1, failed);                                                         \
  }
AV_TET_KERNEL(1)
AV_TET_KERNEL(2)
AV_TET_KERNEL(3)
AV_TET_KERNEL(5)
AV_TET_KERNEL(7)
#undef AV_TET_KERNEL
} // namespace

bool HasTetLocalStepKernel(int targetDim)
{
  const int ft = targetDim - 3;
  return ft == 1 || ft == 2 || ft == 3 || ft == 5 || ft == 7;
}

double TetLocalStepRange(
  const TetLocalStepData& d, std::size_t j0, std::size_t j1, std::vector<std::int32_t>& failed)
{
  switch (d.Stride - 3)
  {
    case 1:
      return Kernel1(d, j0, j1, failed);
    case 2:
      return Kernel2(d, j0, j1, failed);
    case 3:
      return Kernel3(d, j0, j1, failed);
    case 5:
      return Kernel5(d, j0, j1, failed);
    case 7:
      return Kernel7(d, j0, j1, failed);
    default:
      for (std::size_t j = j0; j < j1; ++j)
      {
        failed.push_back(static_cast<std::int32_t>(j)); // no kernel: the caller's path
      }
      return 0.0;
  }
}

} // namespace av
