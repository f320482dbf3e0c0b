// SPDX-License-Identifier: BSD-3-Clause
// The "mesh" stage of anisovoronoi-bench: sampling, av::RunMeshingPipeline, the dual's quality.
#include "MeshStage.h"

#include "DomainAngleBound.h"
#include "LloydRelaxation.h"
#include "MeshQuality.h"
#include "MeshTopology.h"
#include "MeshingPipeline.h"
#include "ParticleSampler.h"
#include "Stopwatch.h"
#include "SurfaceFidelity.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace avbench
{
namespace
{
/// Total area / volume of the input mesh (input space).
double DomainMeasure(const av::SimplexMesh& mesh)
{
  double total = 0.0;
  const int m = mesh.AmbientDim;
  for (std::size_t c = 0; c < mesh.NumCells(); ++c)
  {
    const std::int32_t* v = mesh.Cell(c);
    Eigen::Matrix3d e = Eigen::Matrix3d::Zero(); // edge vectors as columns
    for (int j = 0; j < mesh.SimplexDim; ++j)
    {
      for (int d = 0; d < m; ++d)
      {
        e(d, j) = mesh.Point(v[j + 1])[d] - mesh.Point(v[0])[d];
      }
    }
    if (mesh.SimplexDim == 3)
    {
      total += std::abs(e.determinant()) / 6.0;
    }
    else
    {
      total += 0.5 * e.col(0).cross(e.col(1)).norm(); // 2D: z = 0, still the area
    }
  }
  return total;
}

/// The sites of the stage: the particle sampler, then the optional Lloyd steps. `fixed`
/// gets the corner and feature-line sites, which the improvement rounds must not move.
av::SiteSet SampleSites(const av::SimplexMesh& mesh,
  const av::Embedding& embedding,
  const MeshStageOptions& options,
  std::vector<std::uint8_t>& fixed,
  MeshStageResult& r)
{
  const av::Stopwatch sampleWatch;
  av::ParticleSamplerResult sampled =
    av::SampleParticles(mesh, embedding, SamplerOptionsOf(options));
  r.SampleSeconds = sampleWatch.Seconds();
  r.CornerSites = sampled.NumCornerSites;
  r.FeatureLineSites = sampled.NumFeatureLineSites;
  // Corner and feature-line sites stay where the sampler put them (the ODT steps keep every
  // site whose cell meets the boundary anyway).
  fixed.resize(sampled.FeatureKind.size());
  for (std::size_t i = 0; i < fixed.size(); ++i)
    fixed[i] = sampled.FeatureKind[i] == 1 ? av::FeatureLinePoint : sampled.FeatureKind[i] != 0;
  if (options.LloydIterations > 0)
  {
    const av::Stopwatch lloydWatch;
    av::LloydResult lr =
      av::RelaxSitesLloyd(mesh, embedding, sampled.Sites, options.LloydIterations);
    sampled.Sites = std::move(lr.Sites);
    r.LloydSeconds = lloydWatch.Seconds();
  }
  return std::move(sampled.Sites);
}

/// The meshing options of the stage.
av::MeshingPipelineOptions PipelineOptions(const MeshStageOptions& options,
  const std::vector<std::uint8_t>* fixed,
  const av::MetricField* metric)
{
  av::MeshingPipelineOptions po;
  po.ImproveRounds = options.ImproveRounds;
  po.OdtIterations = options.OdtIterations;
  po.PerturbSlivers = options.PerturbSlivers;
  po.FixedSites = fixed;
  po.OdtKeepsFixedSites = options.OdtKeepsFeatureSites;
  po.Repair = options.Repair;
  po.MaxRepairRounds = options.MaxRepairRounds;
  po.RepairNonManifold = options.RepairNonManifold;
  po.ValidDual = options.ValidDual;
  po.FeatureAngle =
    options.PreserveSharpFeatures && options.RecoverFeatureEdges ? options.FeatureAngle : 180.0;
  po.CloseBoundaryNotches = options.CloseBoundaryNotches;
  po.Improvement.MeanSmoothingSweeps = options.MeanSmoothingSweeps;
  po.ImproveMesh = options.ImproveMesh;
  po.Improvement.PlanarBoundary = options.PlanarBoundary;
  po.Improvement.StraightCreases = options.StraightCreases;
  po.Improvement.Insertions = options.VertexInsertion;
  po.Improvement.Collapses = options.Collapses;
  po.Improvement.EdgeLengthRuleMinAngle = options.EdgeRuleAngle;
  po.Improvement.SnapToBoundary = options.BoundarySnap;
  po.Improvement.InputBoundaryMoves = options.InputBoundaryMoves;
  po.Improvement.BoundaryFlipMaxDihedral = options.BoundaryFlipMaxDihedral;
  po.Improvement.BoundaryFlipVolumeBudget = options.BoundaryFlipVolumeBudget;
  po.Metric = metric;
  return po;
}

/// Timings and counts of the meshing run.
void CopyMeshingCounts(const av::MeshingPipelineResult& m, MeshStageResult& r)
{
  r.RvdSeconds = m.VoronoiSeconds;
  r.RdtSeconds = m.DelaunaySeconds;
  r.ImproveSeconds = m.ImproveSeconds;
  r.RepairSeconds = m.RepairSeconds;
  r.MeshImprovementSeconds = m.MeshImprovementSeconds;
  r.ImprovementFlips =
    m.Improvement.NumFlips23 + m.Improvement.NumEdgeRemovals + m.Improvement.NumFlips22;
  r.ImprovementSmoothed = m.Improvement.NumSmoothed;
  r.ImprovementBoundaryOps =
    m.Improvement.NumBoundaryEdgeRemovals + m.Improvement.NumBoundarySmoothed;
  r.ImprovementVolumeChange = m.Improvement.BoundaryVolumeChange;
  r.ImprovementCreaseMoves = m.Improvement.NumCreaseSmoothed;
  r.ImprovementInsertions = m.Improvement.NumInsertions;
  r.ImprovementPeels = m.Improvement.NumBoundaryPeels;
  r.ImprovementCollapses = m.Improvement.NumCollapses;
  r.ImprovementSnaps = m.Improvement.NumBoundarySnaps;
  r.ImprovementWorstBefore = m.Improvement.WorstBefore;
  r.ImprovementWorstAfter = m.Improvement.WorstAfter;
  r.FeatureEdgesRequired = m.FeatureEdges.Required;
  r.FeatureEdgesMissingBefore = m.FeatureEdges.Required - m.FeatureEdges.Present;
  r.FeatureEdgesRecovered = m.FeatureEdges.Recovered;
  r.FeatureEdgesMissing = m.FeatureEdges.Missing;
  r.BoundaryNotches = m.BoundaryNotches.Notches;
  r.ImprovementMeanSmoothed = m.Improvement.NumMeanSmoothed;
  r.BoundaryNotchesClosed = m.BoundaryNotches.Closed;
  r.BoundaryNotchesLeft = m.BoundaryNotches.Left;
  r.InvertedBeforeImprovement = m.InvertedBeforeImprovement;
  r.ValidDualReplaced = m.ValidDual.Replaced;
  r.ValidDualSeconds = m.ValidDualSeconds;
  r.ValidDualTargetCells = m.ValidDual.TargetCells;
  r.ValidDualKeptCells = m.ValidDual.KeptCells;
  r.ValidDualTargetFlips = m.ValidDual.Flips.NumTargetFlips;
  r.SliversPerturbed = m.NumSlivers;
  r.OdtMovedSites = m.NumOdtMovedSites;
  const av::DelaunayRepairResult& repaired = m.Repaired;
  r.InsertedSites = repaired.NumInserted;
  r.RepairRounds = repaired.Rounds;
  r.InvertedPerRound = repaired.InvertedPerRound;
  r.RepairStalled = repaired.Stalled;
  r.RdtInvertedBeforeRepair = repaired.InitialInverted;
  r.NonManifoldFacesBeforeRepair = repaired.InitialNonManifoldFaces;
  r.Sites = repaired.NumInputSites;
  r.RvdPieces = repaired.Voronoi.NumPieces();
  r.Cells = repaired.Delaunay.NumCells();
  r.RdtInverted = repaired.Delaunay.NumInverted;
  r.NonManifoldFaces = repaired.Delaunay.NumNonManifoldFaces;
  r.UnusedSites = repaired.Delaunay.NumUnusedSites;
}

/// Surface dual meshes: Hausdorff distance to the input, self-intersections, triangles flipped
/// against the closest input triangle, Euler characteristic and boundary loops (the same
/// EvaluateSurfaceFidelity as vtkAnisoMeshQuality with a reference surface).
void MeasureSurfaceFidelity(const av::SimplexMesh& mesh,
  const av::SimplexMesh& dual,
  MeshStageResult& r)
{
  r.IsSurface = true;
  const av::SurfaceFidelityResult f = av::EvaluateSurfaceFidelity(dual, &mesh, 3);
  const av::HausdorffResult& h = f.Hausdorff;
  r.HausdorffPercent = h.MaxPercent;
  r.HausdorffForwardPercent = 100.0 * h.ForwardMax / h.Diagonal;
  r.HausdorffBackwardPercent = 100.0 * h.BackwardMax / h.Diagonal;
  r.SelfIntersections = f.SelfIntersections;
  r.Flipped = f.Flipped;
  r.InputEuler = f.ReferenceTopology.Euler;
  r.InputBoundaryLoops = f.ReferenceTopology.BoundaryLoops;
  r.Euler = f.Topology.Euler;
  r.BoundaryLoops = f.Topology.BoundaryLoops;
  r.NonManifoldEdges = f.Topology.NonManifoldEdges;
}

/// The dual's covered volume and its §5.2 quality against `metric` at the final sites.
void MeasureDualMesh(const av::SimplexMesh& mesh,
  const av::MetricField& metric,
  const av::DelaunayRepairResult& repaired,
  MeshStageResult& r)
{
  const av::RestrictedVoronoiDiagram& rvd = repaired.Voronoi;
  const av::RestrictedDelaunayMesh& rdt = repaired.Delaunay;
  const av::SiteSet& sites = repaired.Sites;
  double pieces = 0.0;
  for (double v : rvd.PieceMeasure)
  {
    pieces += v;
  }
  const double domain = DomainMeasure(mesh);
  r.RvdVolumeError = std::abs(pieces - domain) / domain;

  av::SimplexMesh dual;
  dual.AmbientDim = rdt.AmbientDim;
  dual.SimplexDim = rdt.SimplexDim;
  dual.Points = rdt.Points;
  dual.Cells = rdt.Cells;
  const av::MeshQualityResult q =
    av::EvaluateMeshQuality(dual, av::InterpolateMetricAtSites(mesh, metric, sites));
  if (dual.SimplexDim == dual.AmbientDim)
  {
    // How much of the domain the dual mesh covers (corners and edges cut off lower it).
    double covered = 0.0;
    for (std::size_t c = 0; c < dual.NumCells(); ++c)
      covered += std::abs(av::CellMeasure(dual, c));
    r.DualVolumeRatio = covered / domain;
  }
  if (dual.SimplexDim == 3 && dual.AmbientDim == 3)
    r.PinchedBoundaryEdges = av::CountPinchedBoundaryEdges(dual);
  if (mesh.SimplexDim == 3 && mesh.AmbientDim == 3)
  {
    const av::DomainAngleBound bound = av::ComputeDomainAngleBound(mesh, metric);
    r.DomainAngleBound = bound.MinAngle;
    r.DomainEdgesBelow15 = bound.NumBelow15;
  }
  if (dual.SimplexDim == 3 && dual.AmbientDim == 3 && dual.NumCells() > 0)
  {
    const av::DomainAngleBound own =
      av::ComputeDomainAngleBound(dual, av::InterpolateMetricAtSites(mesh, metric, sites));
    r.MeshBoundaryAngle = own.MinAngle;
    r.MeshBoundaryEdgesBelow15 = own.NumBelow15;
  }
  {
    // Elements whose sites lie in different bodies of the input (a contact assembly).
    std::vector<std::int32_t> body;
    if (av::LabelBodies(mesh, body) > 1)
    {
      const int nv = dual.SimplexDim + 1;
      auto siteBody = [&](std::int32_t s)
      { return body[static_cast<std::size_t>(mesh.Cell(sites.CellIds[s])[0])]; };
      for (std::size_t c = 0; c < dual.NumCells(); ++c)
      {
        bool mixed = false;
        for (int i = 1; i < nv; ++i)
          mixed = mixed || siteBody(dual.Cell(c)[i]) != siteBody(dual.Cell(c)[0]);
        r.CrossBodyElements += mixed ? 1 : 0;
      }
      for (std::size_t p = 0; p < rvd.NumPieces(); ++p)
        r.CrossBodyPieces += siteBody(rvd.PieceSite[p]) !=
            body[static_cast<std::size_t>(mesh.Cell(rvd.PieceElement[p])[0])]
          ? 1
          : 0;
    }
  }
  {
    const std::vector<double> ge =
      av::SimplexQualityInEmbedding(rdt.Cells, rdt.SimplexDim, sites.Coords, sites.Dim);
    double sum = 0.0;
    for (double g : ge)
      sum += g;
    r.GAvgEmbedded = ge.empty() ? 0.0 : sum / static_cast<double>(ge.size());
  }
  if (dual.SimplexDim == 2 && dual.AmbientDim == 3 && dual.NumCells() > 0)
  {
    MeasureSurfaceFidelity(mesh, dual, r);
  }
  r.GMin = q.Summary.GMin;
  r.GAvg = q.Summary.GAvg;
  r.ThetaMin = q.Summary.ThetaMin;
  r.ThetaAvg = q.Summary.ThetaAvg;
  r.PercentBad = q.Summary.PercentBad;
  r.Inverted = q.Summary.NumInverted;
  r.PercentEdgesInUnitRange = q.Summary.PercentEdgesInUnitRange;
}
} // namespace

PaperMeshValues PaperMeshValuesFor(av::AnalyticPreset preset)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  switch (preset)
  {
    case av::AnalyticPreset::Cube1:
      return { 0.09, 0.92, 1.66, 57.24, 0.29, 29.71 };
    case av::AnalyticPreset::Cube2:
      return { 0.10, 0.91, 1.68, 56.76, 0.42, 83.73 };
    case av::AnalyticPreset::Cube3:
      return { 0.04, 0.91, 0.6, 55.98, 0.57, 91.32 };
    case av::AnalyticPreset::SphereCylindrical:
      return { 0.08, 0.88, 1.34, 54.02, 1.24, 77.67 };
    case av::AnalyticPreset::Gaussian2D:
      // Tab. 3 "2D Domain": a different metric than our Gaussian case, for scale only.
      return { 0.34, 0.89, 18.11, 51.51, 0.19, 27.15 };
    case av::AnalyticPreset::SphereCosine:
      break;
  }
  return { nan, nan, nan, nan, nan, nan };
}

std::size_t DefaultSitesFor(av::AnalyticPreset preset)
{
  switch (preset)
  {
    case av::AnalyticPreset::Cube1:
      return 2000;
    case av::AnalyticPreset::Cube2:
      return 5000;
    case av::AnalyticPreset::Cube3:
      return 5600;
    case av::AnalyticPreset::SphereCylindrical:
      return 5000;
    case av::AnalyticPreset::SphereCosine:
      return 1000;
    case av::AnalyticPreset::Gaussian2D:
      return 4000;
  }
  return 1000;
}

av::ParticleSamplerOptions SamplerOptionsOf(const MeshStageOptions& options)
{
  av::ParticleSamplerOptions so;
  so.NumSites = options.Sites;
  so.Iterations = options.SampleIterations;
  so.WarmupIterations = options.WarmupIterations;
  so.Seed = options.Seed;
  so.KernelWidthFactor = options.KernelWidthFactor;
  so.PreserveSharpFeatures = options.PreserveSharpFeatures;
  so.FeatureAngle = options.FeatureAngle;
  return so;
}

MeshStageResult RunMeshStage(const av::SimplexMesh& mesh,
  const av::MetricField& metric,
  const av::Embedding& embedding,
  const MeshStageOptions& options)
{
  MeshStageResult r;
  const av::Stopwatch meshWatch;
  std::vector<std::uint8_t> fixedSites;
  const av::SiteSet sites = SampleSites(mesh, embedding, options, fixedSites, r);
  const av::MeshingPipelineResult meshed =
    av::RunMeshingPipeline(mesh, embedding, sites, PipelineOptions(options, &fixedSites, &metric));
  r.MeshSeconds = meshWatch.Seconds();
  CopyMeshingCounts(meshed, r);
  MeasureDualMesh(mesh, metric, meshed.Repaired, r);
  return r;
}

} // namespace avbench
