// SPDX-License-Identifier: BSD-3-Clause
#include "MetricAdaptedMesh.h"

#include "AdaptiveMeshState.h"
#include "MeshTopology.h"
#include "MetricAlgebra.h"
#include "MetricFieldOps.h"
#include "Stopwatch.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>

namespace av
{
namespace
{
void CheckOptions(const AdaptedMeshOptions& o)
{
  const std::string who = "AdaptBackgroundMesh: ";
  if (o.NumberOfSites <= 0)
    throw InputError(
      who + "the number of sites must be positive (got " + std::to_string(o.NumberOfSites) + ")");
  if (!(o.TargetLength > 0.0 && o.TargetLength <= 10.0))
    throw InputError(who + "the target edge length must be in (0, 10] output edges (got " +
      std::to_string(o.TargetLength) + ")");
  if (!(o.CollapseRatio >= 0.0 && o.CollapseRatio <= 0.7))
    throw InputError(
      who + "the collapse ratio must be in [0, 0.7] (got " + std::to_string(o.CollapseRatio) + ")");
  if (!(o.FeatureAngle > 0.0 && o.FeatureAngle <= 180.0))
    throw InputError(who + "the feature angle must be in (0, 180] degrees");
  if (!(o.SurfaceDeviationAngle >= 0.0 && o.SurfaceDeviationAngle <= 30.0))
    throw InputError(who + "the surface deviation angle must be in [0, 30] degrees");
  if (!(o.MinQuality >= 0.0 && o.MinQuality < 1.0))
    throw InputError(who + "the minimum quality must be in [0, 1)");
  if (o.MaxPoints < 4 || o.MaxPoints > 2000000000u)
    throw InputError(who + "the point limit must be in [4, 2e9]");
}

void CheckInput(const SimplexMesh& mesh, const MetricField& metric)
{
  const std::string who = "AdaptBackgroundMesh: ";
  const bool kinds = (mesh.SimplexDim == 3 && mesh.AmbientDim == 3) ||
    (mesh.SimplexDim == 2 && (mesh.AmbientDim == 2 || mesh.AmbientDim == 3));
  if (!kinds)
    throw InputError(who + "needs tetrahedra, 2D triangles or surface triangles");
  if (mesh.NumCells() == 0 || mesh.NumPoints() == 0)
    throw InputError(who + "the mesh is empty");
  CheckCellIds(mesh, who, mesh.SimplexDim == 3 ? "tetrahedron" : "triangle");
  if (!AllFinite(mesh.Points.data(), static_cast<int>(mesh.Points.size())))
    throw InputError(who + "the mesh has non-finite coordinates");
  if (metric.NumPoints() != mesh.NumPoints() || metric.Values.size() % 6 != 0)
    throw InputError(who + "the metric has " + std::to_string(metric.Values.size()) +
      " values, expected 6 per point (" + std::to_string(6 * mesh.NumPoints()) + ")");
  std::atomic<long long> bad{ -1 };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, metric.NumPoints(), 4096),
    [&](const tbb::blocked_range<std::size_t>& r)
    {
      for (std::size_t i = r.begin(); i != r.end(); ++i)
      {
        const double* v = metric.At(i);
        if (!AllFinite(v, 6) || !IsPositiveSemiDefinite(UnpackSymmetric(v)))
          bad = static_cast<long long>(i);
      }
    });
  if (bad >= 0)
    throw InputError(who + "the metric at point " + std::to_string(bad.load()) +
      " is not a finite symmetric positive (semi-)definite tensor");
}

AdaptiveMeshState InitialState(const SimplexMesh& mesh, const MetricField& metric, double scale)
{
  AdaptiveMeshState s;
  s.AmbientDim = mesh.AmbientDim;
  s.SimplexDim = mesh.SimplexDim;
  s.LengthScale = std::sqrt(scale);
  s.Points = mesh.Points;
  s.Metric = metric.Values;
  const std::size_t np = mesh.NumPoints();
  s.Parents.assign(4 * np, -1);
  s.Weights.assign(4 * np, 0.0);
  for (std::size_t i = 0; i < np; ++i)
  {
    s.Parents[4 * i] = static_cast<std::int32_t>(i);
    s.Weights[4 * i] = 1.0;
  }
  s.Cells = mesh.Cells;
  s.CellParent.resize(mesh.NumCells());
  for (std::size_t c = 0; c < mesh.NumCells(); ++c)
    s.CellParent[c] = static_cast<std::int32_t>(c);
  s.UpdateSqrtMetric(0);
  return s;
}

/// Longest and mean normalized edge length of the state, and the fraction of its edges longer
/// than `longLength`.
void EdgeStatistics(const AdaptiveMeshState& s, double& maxLength, double& meanLength,
  double longLength, double& longFraction)
{
  const int nv = s.Nv(), ne = s.SimplexDim == 3 ? 6 : 3;
  std::vector<std::uint64_t> keys(s.NumCells() * ne);
  for (std::size_t c = 0; c < s.NumCells(); ++c)
    for (int e = 0; e < ne; ++e)
      keys[c * ne + e] =
        EdgeKey(s.Cells[c * nv + kSimplexEdges[e][0]], s.Cells[c * nv + kSimplexEdges[e][1]]);
  tbb::parallel_sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  struct Stats
  {
    double Max = 0.0, Sum = 0.0, Long = 0.0;
  };
  const Stats r = tbb::parallel_reduce(
    tbb::blocked_range<std::size_t>(0, keys.size(), 4096),
    Stats{},
    [&](const tbb::blocked_range<std::size_t>& range, Stats acc)
    {
      for (std::size_t i = range.begin(); i != range.end(); ++i)
      {
        const double l = s.EdgeLength(static_cast<std::int32_t>(keys[i] >> 32),
          static_cast<std::int32_t>(keys[i] & 0xffffffffu));
        acc.Max = std::max(acc.Max, l);
        acc.Sum += l;
        acc.Long += l > longLength ? 1.0 : 0.0;
      }
      return acc;
    },
    [](Stats x, Stats y) {
      return Stats{ std::max(x.Max, y.Max), x.Sum + y.Sum, x.Long + y.Long };
    });
  const double n = static_cast<double>(keys.size());
  maxLength = r.Max;
  meanLength = keys.empty() ? 0.0 : r.Sum / n;
  longFraction = keys.empty() ? 0.0 : r.Long / n;
}

/// s of AdaptedMeshResult::MetricScale for `complexity`.
double NormalizingScale(int sites, int simplexDim, double complexity)
{
  return std::pow(sites * UnitVertexMeasure(simplexDim) / complexity, 2.0 / simplexDim);
}
/// Complexity of the working mesh's metric.
double StateComplexity(const AdaptiveMeshState& s)
{
  SimplexMesh view;
  view.AmbientDim = s.AmbientDim;
  view.SimplexDim = s.SimplexDim;
  view.Points = s.Points;
  view.Cells = s.Cells;
  MetricField field;
  field.Values = s.Metric;
  return MetricComplexity(view, field);
}

/// Splits until no edge is longer than the target (or the point limit); true when done.
bool RefineAll(AdaptiveMeshState& s,
  const MetricField& metric,
  const AdaptedMeshOptions& o,
  AdaptedMeshResult& result)
{
  return RefineLongEdges(s,
           metric,
           o.TargetLength,
           o.MaxPoints,
           1000000,
           result.NumSplits,
           result.RefinePasses) == RefineStatus::Done;
}
} // namespace

AdaptedMeshResult AdaptBackgroundMesh(const SimplexMesh& mesh,
  const MetricField& metric,
  const AdaptedMeshOptions& options)
{
  Stopwatch clock;
  CheckOptions(options);
  CheckInput(mesh, metric);
  AdaptedMeshResult result;
  result.Complexity = MetricComplexity(mesh, metric);
  if (!(result.Complexity > 0.0) || !std::isfinite(result.Complexity))
    throw InputError("AdaptBackgroundMesh: the metric has zero complexity (integral of "
                     "sqrt(det M)); it cannot be scaled to a number of sites");
  const int k = mesh.SimplexDim;
  // s^(k/2) C / UnitVertexMeasure(k) = sites: an output edge has normalized length about 1.
  result.MetricScale = NormalizingScale(options.NumberOfSites, k, result.Complexity);
  AdaptiveMeshState s = InitialState(mesh, metric, result.MetricScale);
  // All splits come before all collapses: a split point then always lies in one input element,
  // so its parents are that element's vertices (exact weights, on the input surface).
  bool done = true;
  if (options.Refine)
  {
    done = RefineAll(s, metric, options, result);
    // The input's complexity (mean metric per coarse cell) misjudges a fast-varying field; the
    // refined mesh resolves it: rescale once from it, refine on when the scale grew.
    const double c = StateComplexity(s);
    const double scale = NormalizingScale(options.NumberOfSites, k, c);
    if (done && c > 0.0 && std::isfinite(scale) &&
      std::abs(scale / result.MetricScale - 1.0) > 0.05)
    {
      result.Complexity = c;
      result.MetricScale = scale;
      s.LengthScale = std::sqrt(scale);
      done = RefineAll(s, metric, options, result);
    }
  }
  result.HitPointLimit = !done;
  if (options.Coarsen && options.CollapseRatio > 0.0)
    result.NumCollapses = CollapseShortEdges(s,
      options.CollapseRatio * options.TargetLength,
      options.TargetLength,
      options,
      options.MaxCoarsenPasses,
      result.CoarsenPasses);
  CompactMesh(s);
  double longFraction = 0.0;
  EdgeStatistics(s, result.MaxEdgeLength, result.MeanEdgeLength, options.TargetLength, longFraction);
  result.Mesh.AmbientDim = s.AmbientDim;
  result.Mesh.SimplexDim = s.SimplexDim;
  result.Mesh.Points = std::move(s.Points);
  result.Mesh.Cells = std::move(s.Cells);
  result.Metric.Values = std::move(s.Metric);
  result.ParentIds = std::move(s.Parents);
  result.ParentWeights = std::move(s.Weights);
  result.CellParent = std::move(s.CellParent);
  result.Seconds = clock.Seconds();
  return result;
}

BackgroundResolution MeasureBackgroundResolution(const SimplexMesh& mesh,
  const MetricField& metric,
  int numberOfSites,
  double targetLength)
{
  CheckInput(mesh, metric);
  if (numberOfSites <= 0 || !(targetLength > 0.0))
    throw InputError("MeasureBackgroundResolution: needs a positive number of sites and length");
  const double complexity = MetricComplexity(mesh, metric);
  if (!(complexity > 0.0) || !std::isfinite(complexity))
    throw InputError("MeasureBackgroundResolution: the metric has zero complexity");
  const AdaptiveMeshState s =
    InitialState(mesh, metric, NormalizingScale(numberOfSites, mesh.SimplexDim, complexity));
  BackgroundResolution r;
  EdgeStatistics(s, r.MaxEdgeLength, r.MeanEdgeLength, targetLength, r.LongEdgeFraction);
  return r;
}

} // namespace av
