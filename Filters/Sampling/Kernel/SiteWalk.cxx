// SPDX-License-Identifier: BSD-3-Clause
// Walk of a site over an embedded simplicial mesh.
#include "SiteWalk.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <string>

namespace av
{

void WalkSiteOnMesh(const SimplexMesh& mesh, const Embedding& emb,
  const std::vector<std::int32_t>& adj, SiteSet& sites, std::size_t s, const double* d)
{
  const int dim = emb.Dim;
  const int k = mesh.SimplexDim;
  const int nv = k + 1;
  double left = 1.0; // the part of d still to walk
  std::int32_t c = sites.CellIds[s];
  double* b = sites.Bary.data() + 4 * s;
  for (int step = 0; step < 64 && left > 0.0; ++step)
  {
    const std::int32_t* cell = mesh.Cell(c);
    const double* v0 = emb.At(cell[0]);
    // Normal equations of the edge frame E (Dim x k) in a fixed 3x3 system (identity rows
    // pad triangles), so the walk allocates nothing.
    Eigen::Matrix3d g = Eigen::Matrix3d::Identity();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    for (int i = 0; i < k; ++i)
    {
      const double* vi = emb.At(cell[i + 1]);
      for (int j = 0; j <= i; ++j)
      {
        const double* vj = emb.At(cell[j + 1]);
        double dot = 0.0;
        for (int q = 0; q < dim; ++q)
          dot += (vi[q] - v0[q]) * (vj[q] - v0[q]);
        g(i, j) = g(j, i) = dot;
      }
      double dot = 0.0;
      for (int q = 0; q < dim; ++q)
        dot += (vi[q] - v0[q]) * d[q];
      rhs[i] = left * dot;
    }
    const Eigen::Vector3d x = g.ldlt().solve(rhs);
    if (!x.allFinite())
      break;
    double dl[4] = { -(x[0] + x[1] + (k == 3 ? x[2] : 0.0)), x[0], x[1], x[2] };
    // A component that is round-off while the site is on that face (moving within the face)
    // must not cross it: crossing back and forth would stall the walk.
    double big = 0.0;
    for (int a = 0; a < nv; ++a)
      big = std::max(big, std::abs(dl[a]));
    for (int a = 0; a < nv; ++a)
      if (b[a] <= 0.0 && dl[a] < 0.0 && dl[a] > -1e-12 * big)
        dl[a] = 0.0;
    double t = 1.0;
    int hit = -1;
    for (int a = 0; a < nv; ++a)
      if (dl[a] < 0.0 && b[a] + t * dl[a] < 0.0)
      {
        t = -b[a] / dl[a];
        hit = a;
      }
    for (int a = 0; a < nv; ++a)
      b[a] += t * dl[a];
    if (hit < 0)
      break;
    b[hit] = 0.0;
    left *= 1.0 - t;
    const std::int32_t nb = adj[static_cast<std::size_t>(c) * nv + hit];
    if (nb < 0)
      break; // domain boundary: the site stays on it
    const std::int32_t* ncell = mesh.Cell(nb);
    double nbary[4] = { 0.0, 0.0, 0.0, 0.0 };
    for (int a = 0; a < nv; ++a)
      for (int q = 0; q < nv; ++q)
        if (ncell[q] == cell[a])
          nbary[q] = b[a];
    c = nb;
    std::copy(nbary, nbary + 4, b);
  }
  double sum = 0.0;
  for (int a = 0; a < nv; ++a)
  {
    b[a] = std::max(0.0, b[a]);
    sum += b[a];
  }
  for (int a = 0; a < nv; ++a)
    b[a] /= sum;
  sites.CellIds[s] = c;
  const std::int32_t* cell = mesh.Cell(c);
  for (int q = 0; q < dim; ++q)
  {
    double v = 0.0;
    for (int a = 0; a < nv; ++a)
      v += b[a] * emb.At(cell[a])[q];
    sites.Coords[s * dim + q] = v;
  }
}

} // namespace av
