// SPDX-License-Identifier: BSD-3-Clause
// Internal to the Voronoi kernel: the small inline helpers every part of the RVD shares
// (squared distance, tiny sorts, float round-up, plane labels, simplex measure).
#ifndef av_RestrictedVoronoiPrimitives_h
#define av_RestrictedVoronoiPrimitives_h

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

namespace av
{
namespace rvd
{

/// Squared distance in R^dim; DIM > 0: compile-time dimension, -1: runtime `dim`.
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

/// Insertion sort for the tiny label arrays (std::sort trips GCC 12's -Warray-bounds here).
template <class It>
inline void SortSmall(It b, It e)
{
  for (It i = b; i != e; ++i)
    for (It j = i; j != b && *j < *(j - 1); --j)
      std::iter_swap(j, j - 1);
}

/// Sorting network for 4 labels (branch-free min/max).
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

/// float not below x (compact per-piece bounds).
inline float RoundUp(double x)
{
  float f = static_cast<float>(x);
  if (static_cast<double>(f) < x)
    f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

/// Plane labels: s >= 0 is the bisector with site s, -(a+1) the facet opposite vertex a.
inline bool IsFacet(std::int32_t label) { return label < 0; }
inline int FacetOf(std::int32_t label) { return -label - 1; }

/// Measure of a k-simplex (k = 2 or 3) with vertices v[0..k] in R^dim: sqrt of the Gram
/// determinant of the edge vectors / k!, in closed form (no Eigen dynamic LU per element).
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

} // namespace rvd
} // namespace av

#endif
