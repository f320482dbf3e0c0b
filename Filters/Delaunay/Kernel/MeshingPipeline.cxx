// SPDX-License-Identifier: BSD-3-Clause
// The meshing sequence RVD -> RDT -> site improvement rounds -> repair (MeshingPipeline.h).
#include "MeshingPipeline.h"

#include "MeshQuality.h"

#include "FeatureEdgeRecovery.h"
#include "FinalMeshImprovement.h"
#include "MeshTopology.h"
#include "RestrictedDelaunay.h"
#include "RestrictedVoronoi.h"
#include "SharpFeatures.h"
#include "SiteImprovement.h"
#include "Stopwatch.h"
#include "ValidDualMesh.h"

#include <algorithm>
#include <string>
#include <utility>

namespace av
{
namespace
{
void ValidateOptions(
  const MeshingPipelineOptions& options, std::size_t numSites, std::size_t numPoints)
{
  auto fail = [](const std::string& m) { throw InputError("RunMeshingPipeline: " + m); };
  if (options.ImproveRounds < 0 || options.OdtIterations < 0 || options.MaxRepairRounds < 0)
    fail("ImproveRounds, OdtIterations and MaxRepairRounds must be >= 0");
  if (options.FixedSites && options.FixedSites->size() != numSites)
    fail("FixedSites must have one flag per site");
  if (!(options.FeatureAngle > 0.0))
    fail("FeatureAngle must be > 0 (180 or more: no feature-edge recovery)");
  if (options.ImproveMesh && options.Metric && options.Metric->NumPoints() != numPoints)
    fail("Metric must have 6 values per input mesh vertex");
}

/// False when the caller asks to abort at `step`.
bool Continue(const MeshingPipelineOptions& options, MeshingStep step)
{
  return !options.Progress || options.Progress(step);
}

/// Flags the sites whose cell id or barycentric coordinates differ between `before` and
/// `after` (same count and order).
void MarkMoved(const SiteSet& before, const SiteSet& after, std::vector<std::uint8_t>& moved)
{
  for (std::size_t i = 0; i < before.NumSites(); ++i)
  {
    moved[i] = moved[i] || after.CellIds[i] != before.CellIds[i] ||
      !std::equal(
        after.Bary.begin() + 4 * i, after.Bary.begin() + 4 * i + 4, before.Bary.begin() + 4 * i);
  }
}

/// Unflags (sets to 0) the sites of the cells of `rdt` that are inverted or that have a facet
/// shared by more than two cells: around those, the fixed sites do not make a valid dual.
void ReleaseSitesOfBadCells(const RestrictedDelaunayMesh& rdt, std::vector<std::uint8_t>& fixed)
{
  const std::size_t nv = static_cast<std::size_t>(rdt.SimplexDim + 1);
  const std::vector<std::uint8_t> nonManifold = NonManifoldCells(rdt);
  for (std::size_t c = 0; c < rdt.NumCells(); ++c)
    if (nonManifold[c] || (c < rdt.Inverted.size() && rdt.Inverted[c]))
      for (std::size_t i = 0; i < nv; ++i)
      {
        const std::int32_t s = rdt.Cells[c * nv + i];
        if (s >= 0 && static_cast<std::size_t>(s) < fixed.size())
          fixed[static_cast<std::size_t>(s)] = 0;
      }
}

/// The improvement rounds: ImproveSites, then the RVD and its dual of the moved sites, until
/// ImproveRounds rounds are done or one moves no site. Updates `sites`, `rvd`, `rdt` and the
/// round counts of `result`; false when the caller aborted.
bool ImproveSiteRounds(const SimplexMesh& mesh,
  const Embedding& embedding,
  const MeshingPipelineOptions& options,
  const RestrictedVoronoiOptions& voronoi,
  SiteSet& sites,
  RestrictedVoronoiDiagram& rvd,
  RestrictedDelaunayMesh& rdt,
  MeshingPipelineResult& result)
{
  SiteImprovementOptions improve;
  improve.OdtIterations = options.OdtIterations;
  improve.PerturbSlivers = options.PerturbSlivers;
  improve.ElementAdjacency = voronoi.ElementAdjacency;
  improve.Sliver.FixedSites = options.FixedSites;
  std::vector<std::uint8_t> odtFixed;
  for (int round = 0; round < options.ImproveRounds; ++round)
  {
    if (options.OdtKeepsFixedSites && options.FixedSites)
    {
      odtFixed = *options.FixedSites;
      ReleaseSitesOfBadCells(rdt, odtFixed);
      improve.Odt.FixedSites = &odtFixed;
    }
    SiteImprovementResult im = ImproveSites(mesh, embedding, sites, rvd, rdt, improve);
    if (round == 0)
    {
      result.NumSlivers = im.NumSlivers;
      result.NumOdtMovedSites = im.NumOdtMoved;
    }
    if (im.NumMovedSites == 0)
      break;
    MarkMoved(sites, im.Sites, result.Moved);
    sites = std::move(im.Sites);
    rvd = ComputeRestrictedVoronoi(mesh, embedding, sites, voronoi);
    rdt = ComputeRestrictedDelaunay(mesh, embedding, sites, rvd);
    ++result.ImproveRoundsDone;
    if (!Continue(options, MeshingStep::ImprovementRound))
      return false;
  }
  return true;
}

MeshingPipelineResult Aborted(MeshingPipelineResult&& result)
{
  result.Aborted = true;
  return std::move(result);
}
} // namespace

MeshingPipelineResult RunMeshingPipeline(const SimplexMesh& mesh,
  const Embedding& embedding,
  const SiteSet& sites,
  const MeshingPipelineOptions& options)
{
  ValidateRestrictedVoronoiInput(mesh, embedding, sites);
  ValidateOptions(options, sites.NumSites(), mesh.NumPoints());
  MeshingPipelineResult result;
  result.Moved.assign(sites.NumSites(), 0);
  DelaunayRepairOptions repair; // its Voronoi options: no geometry, the dual needs only records
  repair.MaxRounds = options.Repair ? options.MaxRepairRounds : 0;
  repair.RepairNonManifold = options.RepairNonManifold;

  Stopwatch watch;
  // Computed once for every diagram and site move below.
  const std::vector<std::int32_t> adjacency = ComputeElementAdjacency(mesh);
  repair.Voronoi.ElementAdjacency = &adjacency;
  SiteSet current = sites;
  RestrictedVoronoiDiagram rvd = ComputeRestrictedVoronoi(mesh, embedding, current, repair.Voronoi);
  result.VoronoiSeconds = watch.Seconds();
  if (!Continue(options, MeshingStep::Voronoi))
    return Aborted(std::move(result));

  watch.Restart();
  RestrictedDelaunayMesh rdt = ComputeRestrictedDelaunay(mesh, embedding, current, rvd);
  result.DelaunaySeconds = watch.Seconds();
  if (!Continue(options, MeshingStep::Delaunay))
    return Aborted(std::move(result));

  watch.Restart();
  const bool improved =
    ImproveSiteRounds(mesh, embedding, options, repair.Voronoi, current, rvd, rdt, result);
  result.ImproveSeconds = watch.Seconds();
  result.NumMovedSites =
    static_cast<std::size_t>(std::count(result.Moved.begin(), result.Moved.end(), 1));
  if (!improved || !Continue(options, MeshingStep::Improvement))
    return Aborted(std::move(result));

  watch.Restart();
  result.Repaired =
    RepairRestrictedDelaunay(mesh, embedding, current, std::move(rvd), std::move(rdt), repair);
  result.RepairSeconds = watch.Seconds();

  if (options.ValidDual)
  {
    watch.Restart();
    const RestrictedDelaunayMesh& dual = result.Repaired.Delaunay;
    const bool invalid = DualNeedsReplacement(dual);
    const MetricField siteMetric = invalid && options.Metric
      ? InterpolateMetricAtSites(mesh, *options.Metric, result.Repaired.Sites)
      : MetricField();
    result.ValidDual = MakeDualValid(mesh, adjacency, result.Repaired.Sites,
      options.Metric ? &siteMetric : nullptr, result.Repaired.Delaunay);
    result.ValidDualSeconds = watch.Seconds();
  }
  SharpFeatures features;
  if ((options.Features || options.FeatureAngle < 180.0) && mesh.SimplexDim == 2 &&
    mesh.AmbientDim == 3)
  {
    features =
      options.Features ? *options.Features : DetectSharpFeatures(mesh, options.FeatureAngle);
    DelaunayRepairResult& repaired = result.Repaired;
    result.FeatureEdges = RecoverFeatureEdges(mesh,
      repaired.Sites,
      ConsecutiveFeatureSites(mesh, features, repaired.Sites),
      repaired.Delaunay);
    if (result.FeatureEdges.Recovered > 0)
      RecountFinalDual(mesh, repaired.Delaunay, repaired.Sites);
  }
  if (options.CloseBoundaryNotches && mesh.SimplexDim == 2 && mesh.AmbientDim == 3)
  {
    DelaunayRepairResult& repaired = result.Repaired;
    result.BoundaryNotches = CloseBoundaryNotches(mesh, repaired.Sites,
      SitesOnOpenBoundary(mesh, adjacency, repaired.Sites), repaired.Delaunay);
    if (result.BoundaryNotches.Closed > 0)
      RecountFinalDual(mesh, repaired.Delaunay, repaired.Sites);
  }
  result.InvertedBeforeImprovement = result.Repaired.Delaunay.NumInverted;
  if (options.ImproveMesh && options.Metric)
  {
    watch.Restart();
    result.Improvement = ImproveFinalMesh(mesh, embedding, adjacency, *options.Metric,
      options.FixedSites, options.Improvement, result.Repaired, result.Moved,
      features.NumEdges() > 0 ? &features : nullptr);
    result.NumMovedSites =
      static_cast<std::size_t>(std::count(result.Moved.begin(), result.Moved.end(), 1));
    result.MeshImprovementSeconds = watch.Seconds();
  }
  return result;
}

} // namespace av
