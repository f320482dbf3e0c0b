// SPDX-License-Identifier: BSD-3-Clause
// FoldedTestCases: a unit square / cube folded by an 8D embedding, with random sites, whose
// restricted Delaunay mesh has inverted elements (the repair and pipeline tests' hard cases).
#ifndef av_FoldedTestCases_h
#define av_FoldedTestCases_h

#include "VoronoiTestMeshes.h"

#include <cmath>

namespace av_test
{

/// Input coordinates, then 8 - AmbientDim waves of amplitude `amp` and frequency `w`.
inline av::Embedding FoldedEmbedding(const av::SimplexMesh& m, double amp, double w)
{
  const int k = m.SimplexDim;
  return MakeEmbedding(m,
    8,
    [=](const double* x, int col)
    {
      const double z = k == 3 ? x[2] : 0.0;
      switch (col % 3)
      {
        case 0:
          return amp * std::sin(w * x[0] + 0.3 * col);
        case 1:
          return amp * std::cos(w * x[1] + 0.7 * z);
        default:
          return amp * std::sin(w * (x[0] + x[1] + z));
      }
    });
}

/// A mesh, its folded embedding and `n` random sites (RandomSites with `seed`).
struct FoldedCase
{
  av::SimplexMesh Mesh;
  av::Embedding Embedding;
  av::SiteSet Sites;
};

inline FoldedCase MakeFoldedCase(av::SimplexMesh mesh, double amp, double w, int n, unsigned seed)
{
  FoldedCase c;
  c.Mesh = std::move(mesh);
  c.Embedding = FoldedEmbedding(c.Mesh, amp, w);
  c.Sites = RandomSites(c.Mesh, c.Embedding, n, seed);
  return c;
}

/// The unit square, 33 x 33 vertices.
inline FoldedCase FoldedSquare(double amp, double w, int n, unsigned seed)
{
  return MakeFoldedCase(TriGrid(33, 33, 0, 0, 1, 1), amp, w, n, seed);
}

/// The unit cube, 9 x 9 x 9 vertices (Kuhn tets).
inline FoldedCase FoldedCube(double amp, double w, int n, unsigned seed)
{
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
  return MakeFoldedCase(KuhnGrid(9, 9, 9, lo, hi), amp, w, n, seed);
}

} // namespace av_test

#endif
