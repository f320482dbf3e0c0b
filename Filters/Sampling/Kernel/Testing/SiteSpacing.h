// SPDX-License-Identifier: BSD-3-Clause
// SiteSpacing: nearest-neighbor distances of a site set and their coefficient of variation, the
// spacing measure of the sampling tests (brute force: small test inputs only).
#ifndef av_SiteSpacing_h
#define av_SiteSpacing_h

#include "SimplexMesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace av_test
{

/// Nearest-neighbor distance of every site, measured on the first `cols` coordinates.
inline std::vector<double> NearestDistances(const av::SiteSet& s, int cols, int offset = 0)
{
  const std::size_t n = s.NumSites();
  std::vector<double> nn(n, std::numeric_limits<double>::infinity());
  for (std::size_t p = 0; p < n; ++p)
    for (std::size_t q = 0; q < n; ++q)
      if (p != q)
      {
        double d2 = 0.0;
        for (int d = offset; d < offset + cols; ++d)
        {
          const double v = s.At(p)[d] - s.At(q)[d];
          d2 += v * v;
        }
        nn[p] = std::min(nn[p], std::sqrt(d2));
      }
  return nn;
}

inline double CoefficientOfVariation(const std::vector<double>& v)
{
  double m = 0.0, m2 = 0.0;
  for (double x : v)
    m += x;
  m /= static_cast<double>(v.size());
  for (double x : v)
    m2 += (x - m) * (x - m);
  return std::sqrt(m2 / static_cast<double>(v.size())) / m;
}

} // namespace av_test

#endif
