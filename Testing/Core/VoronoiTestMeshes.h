// SPDX-License-Identifier: BSD-3-Clause
// Small meshes, embeddings and site sets for the RVD / RDT tests (self-contained, seeded).
#ifndef av_VoronoiTestMeshes_h
#define av_VoronoiTestMeshes_h

#include "RestrictedDelaunay.h"
#include "RestrictedVoronoi.h"
#include "SimplexMesh.h"
#include "StructuredMeshes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <vector>

namespace av_test
{

/// nx x ny vertices on [x0,x1]x[y0,y1], two triangles per quad, counter-clockwise.
inline av::SimplexMesh TriGrid(int nx, int ny, double x0, double y0, double x1, double y1)
{
  const double lo[2] = { x0, y0 }, hi[2] = { x1, y1 };
  return av::MakeTriangleGrid(nx, ny, lo, hi);
}

/// Determinant of a 3x3 matrix.
inline double Det3(const double M[3][3])
{
  return M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) -
    M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
    M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
}

/// Solves the k x k system M x = r (k = 2 or 3) by Cramer's rule and returns det M (x is
/// inf / NaN when it is 0: callers check it).
inline double SolveCramer(int k, const double M[3][3], const double r[3], double x[3])
{
  if (k == 2)
  {
    const double det = M[0][0] * M[1][1] - M[0][1] * M[1][0];
    x[0] = (r[0] * M[1][1] - M[0][1] * r[1]) / det;
    x[1] = (M[0][0] * r[1] - r[0] * M[1][0]) / det;
    return det;
  }
  const double det = Det3(M);
  for (int a = 0; a < 3; ++a)
  {
    double B[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        B[i][j] = j == a ? r[i] : M[i][j];
    x[a] = Det3(B) / det;
  }
  return det;
}

/// nx x ny x nz vertices on the box, 6 Kuhn tets per cube, positively oriented.
inline av::SimplexMesh KuhnGrid(int nx, int ny, int nz, const double lo[3], const double hi[3])
{
  av::SimplexMesh m;
  m.AmbientDim = 3;
  m.SimplexDim = 3;
  auto id = [&](int i, int j, int k) { return (k * ny + j) * nx + i; };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
      {
        m.Points.push_back(lo[0] + (hi[0] - lo[0]) * i / (nx - 1));
        m.Points.push_back(lo[1] + (hi[1] - lo[1]) * j / (ny - 1));
        m.Points.push_back(lo[2] + (hi[2] - lo[2]) * k / (nz - 1));
      }
  const int perms[6][3] = { { 0, 1, 2 }, { 0, 2, 1 }, { 1, 0, 2 }, { 1, 2, 0 }, { 2, 0, 1 },
    { 2, 1, 0 } };
  for (int k = 0; k + 1 < nz; ++k)
    for (int j = 0; j + 1 < ny; ++j)
      for (int i = 0; i + 1 < nx; ++i)
        for (const auto& p : perms)
        {
          int c[3] = { i, j, k };
          std::array<int, 4> t;
          t[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s)
          {
            ++c[p[s]];
            t[s + 1] = id(c[0], c[1], c[2]);
          }
          const double* a = m.Point(t[0]);
          double e[3][3];
          for (int s = 0; s < 3; ++s)
            for (int d = 0; d < 3; ++d)
              e[s][d] = m.Point(t[s + 1])[d] - a[d];
          if (Det3(e) < 0)
            std::swap(t[2], t[3]);
          m.Cells.insert(m.Cells.end(), t.begin(), t.end());
        }
  return m;
}

/// Measure of cell c with its vertices at `pts` (NumPoints x dim, dim <= 16) through the Gram
/// determinant: independent of the kernels' measures.
inline double GramCellMeasure(const av::SimplexMesh& m, const double* pts, int dim, std::size_t c)
{
  const int k = m.SimplexDim;
  const std::int32_t* cell = m.Cell(c);
  double e[3][16] = {};
  for (int a = 0; a < k; ++a)
    for (int d = 0; d < dim; ++d)
      e[a][d] = pts[cell[a + 1] * dim + d] - pts[cell[0] * dim + d];
  double G[3][3];
  for (int a = 0; a < k; ++a)
    for (int b = 0; b < k; ++b)
    {
      G[a][b] = 0.0;
      for (int d = 0; d < dim; ++d)
        G[a][b] += e[a][d] * e[b][d];
    }
  const double det = k == 2 ? G[0][0] * G[1][1] - G[0][1] * G[1][0]
                            : G[0][0] * (G[1][1] * G[2][2] - G[1][2] * G[2][1]) -
      G[0][1] * (G[1][0] * G[2][2] - G[1][2] * G[2][0]) +
      G[0][2] * (G[1][0] * G[2][1] - G[1][1] * G[2][0]);
  return std::sqrt(std::max(0.0, det)) / (k == 2 ? 2.0 : 6.0);
}

/// Embedding: input coordinates, then extra(x, column) for columns AmbientDim..dim-1.
inline av::Embedding MakeEmbedding(const av::SimplexMesh& m, int dim,
  const std::function<double(const double*, int)>& extra)
{
  av::Embedding e;
  e.Dim = dim;
  for (std::size_t i = 0; i < m.NumPoints(); ++i)
  {
    for (int d = 0; d < m.AmbientDim; ++d)
      e.Coords.push_back(m.Point(i)[d]);
    for (int d = m.AmbientDim; d < dim; ++d)
      e.Coords.push_back(extra ? extra(m.Point(i), d) : 0.0);
  }
  return e;
}

/// A smooth synthetic map: (x, [y, z], 0.3 sin(3x), 0.2 cos(2y + z), 0.25 sin(2x + y), ...).
inline double SmoothExtra(const double* x, int col)
{
  const double y = x[1], z = 0.0;
  switch (col % 5)
  {
    case 0: return 0.3 * std::sin(3 * x[0]);
    case 1: return 0.2 * std::cos(2 * y + z);
    case 2: return 0.25 * std::sin(2 * x[0] + y);
    case 3: return 0.15 * std::cos(x[0] * y * 3);
    default: return 0.1 * std::sin(4 * y);
  }
}
inline double SmoothExtra3(const double* x, int col)
{
  switch (col % 5)
  {
    case 0: return 0.3 * std::sin(3 * x[0]);
    case 1: return 0.2 * std::cos(2 * x[1] + x[2]);
    case 2: return 0.25 * std::sin(2 * x[0] + x[2]);
    case 3: return 0.15 * std::cos(3 * x[1] * x[2]);
    default: return 0.1 * std::sin(4 * x[2]);
  }
}

/// Site at barycentric `b` in `cell`.
inline void AddSite(av::SiteSet& s, const av::SimplexMesh& m, const av::Embedding& e,
  std::int32_t cell, const double b[4])
{
  const int nv = m.SimplexDim + 1;
  for (int d = 0; d < e.Dim; ++d)
  {
    double x = 0.0;
    for (int a = 0; a < nv; ++a)
      x += b[a] * e.At(m.Cell(cell)[a])[d];
    s.Coords.push_back(x);
  }
  s.CellIds.push_back(cell);
  for (int a = 0; a < 4; ++a)
    s.Bary.push_back(a < nv ? b[a] : 0.0);
}

/// n random sites (random element, random barycentric weights).
inline av::SiteSet RandomSites(const av::SimplexMesh& m, const av::Embedding& e, int n, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  av::SiteSet s;
  s.Dim = e.Dim;
  const int nv = m.SimplexDim + 1;
  for (int i = 0; i < n; ++i)
  {
    const auto c = static_cast<std::int32_t>(rng() % m.NumCells());
    double b[4] = { 0, 0, 0, 0 }, sum = 0.0;
    for (int a = 0; a < nv; ++a)
      sum += (b[a] = -std::log(1.0 - u(rng)) + 1e-3);
    for (int a = 0; a < nv; ++a)
      b[a] /= sum;
    b[nv - 1] = 1.0;
    for (int a = 0; a + 1 < nv; ++a)
      b[nv - 1] -= b[a];
    AddSite(s, m, e, c, b);
  }
  return s;
}

/// Site at input position x (brute-force point location in a flat mesh, AmbientDim == SimplexDim).
inline bool SiteAt(av::SiteSet& s, const av::SimplexMesh& m, const av::Embedding& e, const double* x)
{
  const int k = m.SimplexDim, nv = k + 1;
  for (std::size_t c = 0; c < m.NumCells(); ++c)
  {
    const std::int32_t* cell = m.Cell(c);
    // Solve x = v0 + sum b_a (v_a - v0) by Cramer's rule.
    double A[3][3], r[3];
    for (int d = 0; d < k; ++d)
    {
      for (int a = 0; a < k; ++a)
        A[d][a] = m.Point(cell[a + 1])[d] - m.Point(cell[0])[d];
      r[d] = x[d] - m.Point(cell[0])[d];
    }
    double b[4] = { 0, 0, 0, 0 };
    SolveCramer(k, A, r, b + 1);
    b[0] = 1.0;
    for (int a = 1; a < nv; ++a)
      b[0] -= b[a];
    bool in = true;
    for (int a = 0; a < nv; ++a)
      in = in && b[a] >= -1e-12;
    if (in)
    {
      for (int a = 0; a < nv; ++a)
        b[a] = std::max(0.0, b[a]);
      double sum = 0.0;
      for (int a = 0; a < nv; ++a)
        sum += b[a];
      for (int a = 0; a < nv; ++a)
        b[a] /= sum;
      AddSite(s, m, e, static_cast<std::int32_t>(c), b);
      return true;
    }
  }
  return false;
}

/// Cells of a dual mesh whose input-space signed area / volume is not positive (flat domains).
inline int NegativeCells(const av::RestrictedDelaunayMesh& d)
{
  int neg = 0;
  const int k = d.SimplexDim, ad = d.AmbientDim;
  for (std::size_t c = 0; c < d.NumCells(); ++c)
  {
    const double* p[4];
    for (int a = 0; a <= k; ++a)
      p[a] = &d.Points[d.Cells[c * (k + 1) + a] * ad];
    double v;
    if (k == 2)
      v = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
    else
    {
      double e[3][3];
      for (int a = 0; a < 3; ++a)
        for (int q = 0; q < 3; ++q)
          e[a][q] = p[a + 1][q] - p[0][q];
      v = Det3(e);
    }
    neg += v <= 0.0;
  }
  return neg;
}

/// The boundary triangles of a tet mesh as a triangle surface (same points).
inline av::SimplexMesh BoundaryTriangles(const av::SimplexMesh& tets)
{
  const std::vector<std::int32_t> adjacency = av::ComputeElementAdjacency(tets);
  av::SimplexMesh s;
  s.AmbientDim = 3;
  s.SimplexDim = 2;
  s.Points = tets.Points;
  for (std::size_t c = 0; c < tets.NumCells(); ++c)
    for (int i = 0; i < 4; ++i)
      if (adjacency[4 * c + static_cast<std::size_t>(i)] < 0)
        for (int j = 0; j < 4; ++j)
          if (j != i)
            s.Cells.push_back(tets.Cell(c)[j]);
  return s;
}

} // namespace av_test

#endif
