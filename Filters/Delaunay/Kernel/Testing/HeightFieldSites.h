// SPDX-License-Identifier: BSD-3-Clause
// HeightFieldSites: sites placed on a triangle surface that is a height field over the xy
// plane (a roof, a flat strip), for the surface dual tests.
#ifndef av_HeightFieldSites_h
#define av_HeightFieldSites_h

#include "SimplexMesh.h"

#include <Eigen/Dense>

#include <cmath>
#include <cstdint>

namespace av_test
{

/// Appends the site over (x, y) at height z: the triangle whose xy projection holds it and its
/// barycentric coordinates there, exact zeros on the triangle's edges (as the sampler puts its
/// feature and boundary sites). Nothing when no triangle holds (x, y).
inline void AddSiteOverXY(const av::SimplexMesh& m, double x, double y, double z, av::SiteSet& sites)
{
  for (std::size_t c = 0; c < m.NumCells(); ++c)
  {
    const std::int32_t* v = m.Cell(c);
    const double* p0 = m.Point(v[0]);
    Eigen::Matrix2d e;
    for (int k = 0; k < 2; ++k)
      for (int d = 0; d < 2; ++d)
        e(d, k) = m.Point(v[k + 1])[d] - p0[d];
    const Eigen::Vector2d l = e.inverse() * Eigen::Vector2d(x - p0[0], y - p0[1]);
    const double b[3] = { 1.0 - l[0] - l[1], l[0], l[1] };
    if (b[0] < -1e-12 || b[1] < -1e-12 || b[2] < -1e-12)
      continue;
    sites.CellIds.push_back(static_cast<std::int32_t>(c));
    for (double bi : b)
      sites.Bary.push_back(std::abs(bi) < 1e-12 ? 0.0 : bi);
    sites.Bary.push_back(0.0);
    sites.Coords.insert(sites.Coords.end(), { x, y, z });
    return;
  }
}

} // namespace av_test

#endif
