// SPDX-License-Identifier: BSD-3-Clause
// AdaptiveMeshState: the working mesh of MetricAdaptedMesh (points with their input parents and
// metric, cells with their input parent) and the two operators on it, edge refinement and edge
// collapse. Internal to the BackgroundMesh kernel.
#ifndef av_AdaptiveMeshState_h
#define av_AdaptiveMeshState_h

#include "MeshTopology.h"
#include "MetricAdaptedMesh.h"

#include <Eigen/Dense>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{

struct AdaptiveMeshState
{
  int AmbientDim = 3;
  int SimplexDim = 3;
  double LengthScale = 1.0;          ///< sqrt(s): normalized length = LengthScale x metric length
  std::vector<double> Points;        ///< n x AmbientDim
  std::vector<double> Metric;        ///< n x 6, unscaled
  std::vector<double> SqrtMetric;    ///< n x 6, M^(1/2) (for the edge length of paper §5.1)
  std::vector<std::int32_t> Parents; ///< n x 4 input point ids, -1 unused
  std::vector<double> Weights;       ///< n x 4
  std::vector<std::int32_t> Cells;   ///< c x (SimplexDim + 1)
  std::vector<std::int32_t> CellParent;

  int Nv() const { return SimplexDim + 1; }
  std::size_t NumPoints() const { return Metric.size() / 6; }
  std::size_t NumCells() const { return CellParent.size(); }
  const double* Point(std::size_t i) const { return Points.data() + i * AmbientDim; }
  Eigen::Vector3d Position(std::size_t i) const
  {
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (int d = 0; d < AmbientDim; ++d)
      p[d] = Points[i * AmbientDim + d];
    return p;
  }
  /// Normalized metric length of the edge a-b (paper §5.1 form with the square roots).
  double EdgeLength(std::int32_t a, std::int32_t b) const;
  /// Fills SqrtMetric for the points [first, NumPoints()) in parallel.
  void UpdateSqrtMetric(std::size_t first);
};

/// Local vertex pairs of the edges of a triangle (first 3) or a tetrahedron (6).
extern const int kSimplexEdges[6][2];

/// How a refinement call ended.
enum class RefineStatus
{
  Done,      ///< no edge is longer than the target
  PassLimit, ///< long edges remain after maxPasses passes
  PointLimit ///< the mesh reached maxPoints points
};

/**
 * Splits edges longer than `target`, longest first, in at most `maxPasses` passes of
 * element-disjoint splits. New points are edge midpoints with merged parent weights and the
 * log-Euclidean metric of their parents.
 */
RefineStatus RefineLongEdges(AdaptiveMeshState& state,
  const MetricField& inputMetric,
  double target,
  std::size_t maxPoints,
  int maxPasses,
  std::size_t& numSplits,
  int& passes);

/// Collapses edges shorter than `shortLength` under the safety checks of AdaptBackgroundMesh
/// (options give the angles and the quality floor) in at most `maxPasses` passes, then drops
/// the dead cells and unused points. Returns the number of collapses.
std::size_t CollapseShortEdges(AdaptiveMeshState& state,
  double shortLength,
  double target,
  const AdaptedMeshOptions& options,
  int maxPasses,
  int& passes);

/// Drops the points no cell uses (ids renumbered in order).
void CompactMesh(AdaptiveMeshState& state);

} // namespace av

#endif
