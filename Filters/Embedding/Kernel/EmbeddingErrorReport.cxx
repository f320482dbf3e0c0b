// SPDX-License-Identifier: BSD-3-Clause
#include "EmbeddingErrorReport.h"

#include "InputError.h"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace av
{

namespace
{
/// a is a worse error than b; NaN is worse than any number (it is never a good fit).
bool WorseThan(double a, double b)
{
  return std::isnan(a) ? !std::isnan(b) : a > b;
}
}

LargeErrorSummary SummarizeLargeCellErrors(const SimplexMesh& mesh,
  const std::vector<double>& cellPercent,
  double thresholdPercent)
{
  const std::size_t nc = mesh.NumCells();
  if (cellPercent.size() != nc)
  {
    throw InputError("embedding error report: " + std::to_string(cellPercent.size()) +
      " cell errors for " + std::to_string(nc) + " cells");
  }
  LargeErrorSummary s;
  s.ThresholdPercent = thresholdPercent;
  s.NumCells = nc;
  for (std::size_t c = 0; c < nc; ++c)
  {
    const double e = cellPercent[c];
    // NaN counts as above the threshold and as the worst: it is never a good fit.
    const bool bad = !(e <= thresholdPercent);
    s.NumAbove += bad ? 1 : 0;
    if (s.WorstCell < 0 || WorseThan(e, s.WorstPercent))
    {
      s.WorstCell = static_cast<std::int64_t>(c);
      s.WorstPercent = e;
    }
  }
  if (s.WorstCell >= 0)
  {
    const std::int32_t* cell = mesh.Cell(static_cast<std::size_t>(s.WorstCell));
    const int nv = mesh.VerticesPerCell();
    for (int l = 0; l < nv; ++l)
    {
      for (int k = 0; k < mesh.AmbientDim && k < 3; ++k)
      {
        s.WorstCentroid[k] += mesh.Point(cell[l])[k] / nv;
      }
    }
  }
  return s;
}

std::string DescribeLargeCellErrors(const LargeErrorSummary& s)
{
  if (s.NumAbove == 0)
  {
    return std::string();
  }
  std::ostringstream out;
  out << "the embedding does not fit the metric in " << s.NumAbove << " of " << s.NumCells
      << " cells (edge length error above " << s.ThresholdPercent << " %); worst: cell "
      << s.WorstCell << " at (" << std::setprecision(6) << s.WorstCentroid[0] << ", "
      << s.WorstCentroid[1] << ", " << s.WorstCentroid[2] << "), " << std::setprecision(4)
      << s.WorstPercent
      << " %. See the cell array EdgeLengthError; a finer or graded background mesh, a "
         "smoother metric or more iterations usually help";
  return out.str();
}

} // namespace av
