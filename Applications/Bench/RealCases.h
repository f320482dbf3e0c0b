// SPDX-License-Identifier: BSD-3-Clause
// RealCases: the benchmark's cases on real data (scripts/make-real-data.sh, listed in
// Documentation/real-data.md): CalculiX stress fields, OpenFOAM strain rates and CGAL
// surfaces, read with the VTK-free IO kernels and turned into a simplex mesh with a metric the
// way the anisovoronoi tool does with its defaults (tensor:ARRAY, curvature).
#ifndef av_bench_RealCases_h
#define av_bench_RealCases_h

#include "SimplexMesh.h"

#include <cstddef>
#include <string>
#include <vector>

namespace avbench
{

/// Where a real case comes from and which field makes its metric.
struct RealCaseInfo
{
  std::string Name;  ///< without the "real:" prefix
  std::string File;  ///< in the real-data directory
  std::string Field; ///< .frd result holding the tensor; empty for a surface (curvature)
  int StepIndex = 0; ///< 0-based step of the .frd (mode / increment)
};

/// Every real case, in the order of `real:all`.
const std::vector<RealCaseInfo>& RealCases();

/// True for "real:NAME" case names.
bool IsRealCaseName(const std::string& caseName);

/**
 * The real-data directory: `option` when not empty, else $AV_REAL_DATA_DIR, else real-data
 * next to the bin/ folder of this executable (build/real-data for build/bin).
 */
std::string RealDataDirectory(const std::string& option);

/// The tensor -> metric options of the volume cases (the anisovoronoi tool's --min-eigenvalue,
/// --max-anisotropy and --smooth; defaults = av::TensorToMetricOptions, as the tool's).
struct RealCaseOptions
{
  double MinEigenvalue = 1e-3;
  double MaxAnisotropy = 25.0;
  int SmoothingIterations = 0;
  double CreaseAngle = 180.0; ///< surfaces: the curvature metric's CreaseAngle (180 = none)
};

/// A real case ready for the embedding.
struct RealInput
{
  av::SimplexMesh Mesh;
  av::MetricField Metric;
  std::string Description;                   ///< e.g. "ccx-rotor.frd STRESS step 1 -> 2,208 tets"
  std::size_t FilePoints = 0, FileCells = 0; ///< as read, before the split into simplices
  double StretchMin = 0.0, StretchMax = 0.0; ///< of the metric (tangent stretch on surfaces)
  std::size_t CreaseEdges = 0;               ///< surfaces: edges sharper than CreaseAngle
  bool IsSurface = false;
};

/**
 * Reads case `name` ("real:rotor") from `dataDir`. Volumes: the .frd mesh split into
 * simplices (av::SplitIntoSimplices), the tensor interpolated onto the new points, then
 * av::TensorToMetric (`options`, else its defaults). Surfaces: the .off, then
 * av::SurfaceCurvatureMetric with its defaults. Throws std::runtime_error for an unknown case or a
 * missing file (naming scripts/make-real-data.sh), av::InputError for bad data.
 */
RealInput LoadRealCase(const std::string& name,
  const std::string& dataDir,
  const RealCaseOptions& options = RealCaseOptions());

/// Sites of a real case when --sites is not given: 3000 for volumes, 2000 for surfaces.
std::size_t DefaultRealSites(const RealInput& input);

} // namespace avbench

#endif
