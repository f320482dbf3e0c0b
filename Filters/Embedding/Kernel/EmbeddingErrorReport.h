// SPDX-License-Identifier: BSD-3-Clause
// EmbeddingErrorReport: where the embedding does not fit the metric (cells whose §5.1 edge
// length error is large), so that filters and the CLI can say so instead of going on silently.
#ifndef av_EmbeddingErrorReport_h
#define av_EmbeddingErrorReport_h

#include "SimplexMesh.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace av
{

/// The cells whose error exceeds a threshold, and the worst one.
struct LargeErrorSummary
{
  double ThresholdPercent = 0.0;
  std::size_t NumCells = 0;    ///< cells in the mesh
  std::size_t NumAbove = 0;    ///< cells with an error above ThresholdPercent
  std::int64_t WorstCell = -1; ///< cell with the largest error (-1: empty mesh)
  double WorstPercent = 0.0;   ///< its error, in %
  std::array<double, 3> WorstCentroid{ { 0.0, 0.0, 0.0 } }; ///< its centroid (z = 0 in 2D)
};

/// Counts the cells with cellPercent > thresholdPercent and locates the worst cell.
/// cellPercent: one value per cell (EdgeLengthErrorResult::CellMaxPercent). Throws InputError
/// on a size mismatch.
LargeErrorSummary SummarizeLargeCellErrors(const SimplexMesh& mesh,
  const std::vector<double>& cellPercent,
  double thresholdPercent);

/// One sentence for a warning ("" when no cell is above the threshold): how many cells, the
/// worst cell's id, location and error, the threshold, and what usually helps.
std::string DescribeLargeCellErrors(const LargeErrorSummary& summary);

} // namespace av

#endif
