// SPDX-License-Identifier: BSD-3-Clause
// SurfaceCases: the paper's surface test cases for anisovoronoi-bench (Tab. 3: the Dupin
// cyclides of Figs. 6 and 13, and a torus): mesh, curvature metric (Eq. 19), paper values.
#ifndef av_bench_SurfaceCases_h
#define av_bench_SurfaceCases_h

#include "SimplexMesh.h"

#include <cstddef>
#include <string>
#include <vector>

namespace avbench
{

/// A generated surface case.
struct SurfaceCase
{
  av::SimplexMesh Mesh;
  av::MetricField Metric;
  std::string Description;  ///< generator and parameters
  std::size_t Sites = 2000; ///< the paper's output vertex count
  double MaxStretch = 10.0; ///< cap used for the curvature metric
  /// Tab. 3 (NaN where the paper has no row): L_avg, L_max, embed s, G_min, G_avg, theta_min,
  /// theta_avg, % < 30 deg, mesh s.
  double Paper[9];
};

/// True for "cyclide", "cyclide2", "torus".
bool IsSurfaceCase(const std::string& name);

/// Names of the surface cases.
std::vector<std::string> SurfaceCaseNames();

/**
 * Builds case `name`: cyclide (Cyclide1 of Tab. 3: a = 2, c = 1, mu = 1.5, 120 x 90 = 10,800
 * vertices, 2000 sites), cyclide2 (Cyclide2: a = 2, c = 1.9, mu = 1.95, 180 x 144 = 25,920
 * vertices, stretch capped at the paper's 29, 8000 sites), torus (R = 3, r = 1, 120 x 60,
 * 2000 sites). `maxStretch` > 0 replaces the case's cap; `resolutionScale` > 0 scales the
 * grid. Throws std::runtime_error for an unknown name.
 */
SurfaceCase BuildSurfaceCase(const std::string& name, double maxStretch, double resolutionScale);

} // namespace avbench

#endif
