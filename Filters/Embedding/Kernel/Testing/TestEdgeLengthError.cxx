// SPDX-License-Identifier: BSD-3-Clause
// §5.1 relative edge length error: exact values on hand-made embeddings.
#include "AnalyticMetrics.h"
#include "EdgeLengthError.h"
#include "MeshTopology.h"
#include "StructuredMeshes.h"
#include "AnisoTestChecks.h"

#include <cmath>

int TestEdgeLengthError(int, char*[])
{
  using namespace av;
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
  const SimplexMesh mesh = MakeKuhnTetGrid(4, 3, 3, lo, hi);
  // Cube1 metric: diag(S^2, 1, 1). The embedding x -> (x, y, z) stretched by 1.1 in every
  // direction has error |1.1 l_e - l| / l; for identity metric it is exactly 10 %.
  MetricField identity;
  identity.Values.assign(6 * mesh.NumPoints(), 0.0);
  for (std::size_t i = 0; i < mesh.NumPoints(); ++i)
  {
    identity.Values[6 * i] = identity.Values[6 * i + 1] = identity.Values[6 * i + 2] = 1.0;
  }
  Embedding e;
  e.Dim = 5;
  e.Coords.assign(5 * mesh.NumPoints(), 0.0);
  for (std::size_t i = 0; i < mesh.NumPoints(); ++i)
  {
    for (int d = 0; d < 3; ++d)
    {
      e.Coords[5 * i + d] = 1.1 * mesh.Point(i)[d];
    }
  }
  const EdgeLengthErrorResult r = ComputeEdgeLengthError(mesh, identity, e, true, true);
  AV_CHECK(r.NumEdges == UniqueEdges(mesh).size() / 2);
  AV_CHECK_NEAR(r.AveragePercent, 10.0, 1e-9);
  AV_CHECK_NEAR(r.MaxPercent, 10.0, 1e-9);
  AV_CHECK(r.CellMaxPercent.size() == mesh.NumCells());
  AV_CHECK_NEAR(r.CellMaxPercent[3], 10.0, 1e-9);

  // Metric diag(4, 1, 1) (A = diag(2, 1, 1)), embedding = input: an x-edge of length h has
  // metric length 2h and error 50 %; y/z edges 0 %; the (1,1,1) diagonal sqrt(4+1+1)/sqrt(3).
  MetricField stretched = identity;
  for (std::size_t i = 0; i < mesh.NumPoints(); ++i)
  {
    stretched.Values[6 * i] = 4.0;
  }
  Embedding flat;
  flat.Dim = 3;
  flat.Coords = mesh.Points;
  const EdgeLengthErrorResult s = ComputeEdgeLengthError(mesh, stretched, flat, true, false);
  AV_CHECK_NEAR(s.MaxPercent, 50.0, 1e-9);
  bool sawY = false;
  for (std::size_t k = 0; k < s.NumEdges; ++k)
  {
    const double* a = mesh.Point(s.Edges[2 * k]);
    const double* b = mesh.Point(s.Edges[2 * k + 1]);
    if (a[0] == b[0] && a[2] == b[2])
    {
      sawY = true;
      AV_CHECK_NEAR(s.EdgePercent[k], 0.0, 1e-12);
    }
  }
  AV_CHECK(sawY);

  // The exact Gaussian embedding (x, y, h(x, y)) has only a discretization error.
  const AnalyticDomain d = RecommendedDomain(AnalyticPreset::Gaussian2D);
  const SimplexMesh grid = MakeTriangleGrid(81, 81, d.Lo, d.Hi);
  const MetricField g = EvaluateAnalyticMetric(AnalyticPreset::Gaussian2D, grid);
  Embedding gauss;
  gauss.Dim = 3;
  for (std::size_t i = 0; i < grid.NumPoints(); ++i)
  {
    gauss.Coords.insert(gauss.Coords.end(),
      { grid.Point(i)[0], grid.Point(i)[1], GaussianHeight(grid.Point(i)[0], grid.Point(i)[1]) });
  }
  const EdgeLengthErrorResult ge = ComputeEdgeLengthError(grid, g, gauss);
  AV_CHECK(ge.AveragePercent < 0.1); // measured 0.069 %
  AV_CHECK(ge.MaxPercent < 7.0); // measured 5.75 %: the measure itself, Q averaged over the edge
  // ... while the flat embedding misses the height field badly.
  Embedding flat2;
  flat2.Dim = 2;
  flat2.Coords = grid.Points;
  AV_CHECK(ComputeEdgeLengthError(grid, g, flat2).MaxPercent > 60.0);

  Embedding wrong;
  wrong.Dim = 3;
  wrong.Coords.assign(9, 0.0);
  AV_CHECK_THROWS(ComputeEdgeLengthError(mesh, identity, wrong));
  MetricField shortMetric;
  shortMetric.Values.assign(6, 1.0);
  AV_CHECK_THROWS(ComputeEdgeLengthError(mesh, shortMetric, flat));
  return AV_TEST_RESULT();
}
