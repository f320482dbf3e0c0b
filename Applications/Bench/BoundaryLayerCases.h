// SPDX-License-Identifier: BSD-3-Clause
// BoundaryLayerCases: the benchmark's boundary-layer cases (issue 12/13 targets): the analytic
// metric of BoundaryLayerMetric.h on a Kuhn background graded along the wall normal, with the
// sites its complexity asks for, as a user's MMG .mesh/.sol pair would give them.
#ifndef av_bench_BoundaryLayerCases_h
#define av_bench_BoundaryLayerCases_h

#include "BoundaryLayerMetric.h"
#include "SimplexMesh.h"

#include <cstddef>
#include <string>
#include <vector>

namespace avbench
{

/// True for "bl-linearS" and "bl-expS" with a stretch S >= 1 ("bl-linear100", "bl-exp1000").
bool IsBoundaryLayerCase(const std::string& name);

/// The four cases of the targets: bl-linear100 bl-linear1000 bl-exp100 bl-exp1000.
std::vector<std::string> BoundaryLayerCaseNames();

/// A boundary-layer case ready for the embedding.
struct BoundaryLayerCase
{
  av::BoundaryLayerMetricOptions Options;
  av::SimplexMesh Mesh;
  av::MetricField Metric;    ///< in the input's units (diag(1/h0^2, 1/h0^2, 1/h_z^2))
  std::string Description;   ///< e.g. "graded-kuhn-21x21x96 linear stretch 100"
  std::size_t Sites = 0;     ///< complexity / unit vertex measure, as the CLI takes a .sol's
};

/**
 * Builds case `name` on [0, 1]^3 (wall at z = 0, h0 = 0.1): n x n vertices across the wall
 * (`resolution`, default 21, i.e. h0 / 2) and normal levels stepping by the same fraction of h_z
 * (BoundaryLayerLevels), so that every background edge is about half an output edge in the
 * metric. Throws std::runtime_error for a name that IsBoundaryLayerCase rejects.
 */
BoundaryLayerCase BuildBoundaryLayerCase(const std::string& name, int resolution);

} // namespace avbench

#endif
