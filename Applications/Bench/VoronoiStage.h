// SPDX-License-Identifier: BSD-3-Clause
// VoronoiStage: the "voronoi" stage of anisovoronoi-bench, the restricted Voronoi diagram alone
// (sampled sites, then ComputeRestrictedVoronoi timed with and without geometry and its
// whole-element fast path), kept apart from the JSON / CLI code.
#ifndef av_bench_VoronoiStage_h
#define av_bench_VoronoiStage_h

#include "MeshStage.h"
#include "SimplexMesh.h"

#include <cstddef>
#include <vector>

namespace avbench
{

/// One configuration of ComputeRestrictedVoronoi, timed.
struct VoronoiRun
{
  bool Geometry = false, FastPath = false;
  double BestSeconds = 0.0;    ///< best of the repeats (wall)
  double BestCpuSeconds = 0.0; ///< best of the repeats, CPU time of the process (all threads)
  /// Largest increase of the resident set over the run (peak RSS, VmHWM after resetting it
  /// through /proc/self/clear_refs, minus the RSS before): the RVD's working memory and its
  /// output. getrusage's lifetime maximum instead (a delta over the stage) where the reset is
  /// not allowed; < 0 when neither is available.
  double PeakRssMb = -1.0;
  double OutputMb = 0.0; ///< bytes held by the returned diagram's arrays
  std::size_t Pieces = 0, Vertices = 0, WholeElements = 0;
  bool SameAsNoFastPath = true; ///< fast path: every field equals the run without it
};

struct VoronoiStageResult
{
  std::size_t Sites = 0, Elements = 0;
  double SampleSeconds = 0.0;
  bool PeakIsReset = false; ///< PeakRssMb from a reset VmHWM (else getrusage deltas)
  std::vector<VoronoiRun> Runs;
};

/// Samples options.Sites sites as the mesh stage does (no Lloyd), then times the RVD without /
/// with geometry (when `geometry`; with the R^Dim vertices when `embeddedPoints`), each without
/// / with the fast path, best of `repeats`.
VoronoiStageResult RunVoronoiStage(const av::SimplexMesh& mesh,
  const av::Embedding& embedding,
  const MeshStageOptions& options,
  int repeats,
  bool geometry,
  bool embeddedPoints);

} // namespace avbench

#endif
