// SPDX-License-Identifier: BSD-3-Clause
// Per-cell edge length error and the large-error summary on a hand-computed two-tet case.
#include "AnisoTestChecks.h"
#include "EdgeLengthError.h"
#include "EmbeddingErrorReport.h"

#include <cmath>
#include <string>

int TestEmbeddingErrorReport(int, char*[])
{
  using namespace av;
  // Two tets sharing the face (1, 2, 3): cell 0 = (0, 1, 2, 3), cell 1 = (4, 1, 3, 2) with
  // vertex 4 = (1, 1, 1) (opposite orientation of the shared face, both positive volume).
  SimplexMesh mesh;
  mesh.Points = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1 };
  mesh.Cells = { 0, 1, 2, 3, 4, 1, 3, 2 };
  MetricField identity;
  identity.Values.assign(6 * 5, 0.0);
  for (int i = 0; i < 5; ++i)
  {
    identity.Values[6 * i] = identity.Values[6 * i + 1] = identity.Values[6 * i + 2] = 1.0;
  }
  // Embedding in 4D: the input points, and vertex 0 lifted by h along the 4th axis. Edges of
  // vertex 0 (all of length 1 in the metric) become sqrt(1 + h^2): with h = sqrt(0.44) their
  // error is exactly 20 %. Every other edge keeps its length: cell 1 has no error.
  const double h = std::sqrt(0.44);
  Embedding e;
  e.Dim = 4;
  for (int i = 0; i < 5; ++i)
  {
    e.Coords.insert(e.Coords.end(), mesh.Point(i), mesh.Point(i) + 3);
    e.Coords.push_back(i == 0 ? h : 0.0);
  }
  const EdgeLengthErrorResult r = ComputeEdgeLengthError(mesh, identity, e, false, true);
  AV_CHECK(r.NumEdges == 9u); // 6 + 3 new edges from vertex 4
  AV_CHECK(r.CellMaxPercent.size() == 2u);
  AV_CHECK_NEAR(r.CellMaxPercent[0], 20.0, 1e-9);
  AV_CHECK_NEAR(r.CellMaxPercent[1], 0.0, 1e-9);
  AV_CHECK_NEAR(r.MaxPercent, 20.0, 1e-9);
  AV_CHECK_NEAR(r.AveragePercent, 3 * 20.0 / 9, 1e-9);

  // Summary: threshold 15 % -> only cell 0, at centroid (0.25, 0.25, 0.25).
  const LargeErrorSummary s = SummarizeLargeCellErrors(mesh, r.CellMaxPercent, 15.0);
  AV_CHECK(s.NumCells == 2u && s.NumAbove == 1u);
  AV_CHECK(s.WorstCell == 0);
  AV_CHECK_NEAR(s.WorstPercent, 20.0, 1e-9);
  AV_CHECK_NEAR(s.WorstCentroid[0], 0.25, 1e-15);
  AV_CHECK_NEAR(s.WorstCentroid[1], 0.25, 1e-15);
  AV_CHECK_NEAR(s.WorstCentroid[2], 0.25, 1e-15);
  const std::string text = DescribeLargeCellErrors(s);
  std::cout << text << "\n";
  AV_CHECK(text.find("1 of 2 cells") != std::string::npos);
  AV_CHECK(text.find("cell 0 at (0.25, 0.25, 0.25)") != std::string::npos);
  AV_CHECK(text.find("above 15 %") != std::string::npos);

  // Above every error: nothing to report, no sentence.
  const LargeErrorSummary none = SummarizeLargeCellErrors(mesh, r.CellMaxPercent, 25.0);
  AV_CHECK(none.NumAbove == 0u && none.WorstCell == 0);
  AV_CHECK(DescribeLargeCellErrors(none).empty());

  // Worst is the largest even when it comes last; NaN counts as the worst and as above.
  const LargeErrorSummary later = SummarizeLargeCellErrors(mesh, { 5.0, 70.0 }, 50.0);
  AV_CHECK(later.NumAbove == 1u && later.WorstCell == 1);
  AV_CHECK_NEAR(later.WorstCentroid[0], 0.5, 1e-15); // (1 + 1 + 0 + 0) / 4
  const LargeErrorSummary nan = SummarizeLargeCellErrors(mesh, { 80.0, std::nan("") }, 50.0);
  AV_CHECK(nan.NumAbove == 2u && nan.WorstCell == 1);
  AV_CHECK_THROWS(SummarizeLargeCellErrors(mesh, { 1.0 }, 50.0));
  return AV_TEST_RESULT();
}
