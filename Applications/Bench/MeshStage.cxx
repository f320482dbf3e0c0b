#include "MeshStage.h"

#include "LloydRelaxation.h"
#include "MeshTopology.h"
#include "MeshQuality.h"
#include "ParticleSampler.h"
#include "RestrictedDelaunay.h"
#include "RestrictedDelaunayRefinement.h"
#include "RestrictedVoronoi.h"
#include "SiteImprovement.h"
#include "StructuredMeshes.h"

#include <Eigen/Dense>

#include <chrono>
#include <cmath>
#include <limits>
#include <utility>

namespace avbench
{
namespace
{
using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

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

MeshStageResult RunMeshStage(const av::SimplexMesh& mesh, const av::MetricField& metric,
  const av::Embedding& embedding, const MeshStageOptions& options)
{
  MeshStageResult r;
  const auto t0 = Clock::now();

  av::ParticleSamplerOptions so;
  so.NumSites = options.Sites;
  so.Iterations = options.SampleIterations;
  so.WarmupIterations = options.WarmupIterations;
  so.Seed = options.Seed;
  so.KernelWidthFactor = options.KernelWidthFactor;
  so.PreserveSharpFeatures = options.PreserveSharpFeatures;
  so.FeatureAngle = options.FeatureAngle;
  av::ParticleSamplerResult sampled = av::SampleParticles(mesh, embedding, so);
  r.SampleSeconds = Since(t0);
  r.CornerSites = sampled.NumCornerSites;
  r.FeatureLineSites = sampled.NumFeatureLineSites;
  // Corner and feature-line sites stay where the sampler put them (the ODT steps keep every
  // site whose cell meets the boundary anyway).
  std::vector<std::uint8_t> fixedSites(sampled.FeatureKind.size());
  for (std::size_t i = 0; i < fixedSites.size(); ++i)
    fixedSites[i] = sampled.FeatureKind[i] != 0 ? 1 : 0;
  if (options.LloydIterations > 0)
  {
    const auto tl = Clock::now();
    av::LloydResult lr =
      av::RelaxSitesLloyd(mesh, embedding, sampled.Sites, options.LloydIterations);
    sampled.Sites = std::move(lr.Sites);
    r.LloydSeconds = Since(tl);
  }

  const auto t1 = Clock::now();
  av::DelaunayRepairOptions ro; // its Voronoi options: no geometry, the dual needs only records
  ro.MaxRounds = options.Repair ? options.MaxRepairRounds : 0;
  ro.RepairNonManifold = options.RepairNonManifold;
  // Computed once for all the diagrams and site moves on this mesh.
  const std::vector<std::int32_t> adjacency = av::ComputeElementAdjacency(mesh);
  ro.Voronoi.ElementAdjacency = &adjacency;
  av::RestrictedVoronoiDiagram rvd0 =
    av::ComputeRestrictedVoronoi(mesh, embedding, sampled.Sites, ro.Voronoi);
  r.RvdSeconds = Since(t1);

  const auto t2 = Clock::now();
  av::RestrictedDelaunayMesh rdt0 =
    av::ComputeRestrictedDelaunay(mesh, embedding, sampled.Sites, rvd0);
  r.RdtSeconds = Since(t2);

  // Site improvement rounds: ODT steps and sliver pushes, then the RVD and its dual again.
  const auto ts = Clock::now();
  for (int round = 0; round < options.ImproveRounds; ++round)
  {
    av::SiteImprovementOptions io;
    io.OdtIterations = options.OdtIterations;
    io.PerturbSlivers = options.PerturbSlivers;
    io.ElementAdjacency = &adjacency;
    io.Sliver.FixedSites = &fixedSites;
    const av::SiteImprovementResult im =
      av::ImproveSites(mesh, embedding, sampled.Sites, rvd0, rdt0, io);
    if (round == 0)
    {
      r.SliversPerturbed = im.NumSlivers;
      r.OdtMovedSites = im.NumOdtMoved;
    }
    if (im.NumMovedSites == 0)
    {
      break;
    }
    sampled.Sites = std::move(im.Sites);
    rvd0 = av::ComputeRestrictedVoronoi(mesh, embedding, sampled.Sites, ro.Voronoi);
    rdt0 = av::ComputeRestrictedDelaunay(mesh, embedding, sampled.Sites, rvd0);
  }
  r.ImproveSeconds = Since(ts);

  const auto t3 = Clock::now();
  const std::size_t sampledSites = sampled.Sites.NumSites();
  av::DelaunayRepairResult repaired = av::RepairRestrictedDelaunay(
    mesh, embedding, sampled.Sites, std::move(rvd0), std::move(rdt0), ro);
  r.RepairSeconds = Since(t3);
  r.MeshSeconds = Since(t0);
  const av::RestrictedVoronoiDiagram& rvd = repaired.Voronoi;
  const av::RestrictedDelaunayMesh& rdt = repaired.Delaunay;
  sampled.Sites = std::move(repaired.Sites);
  r.InsertedSites = repaired.NumInserted;
  r.RepairRounds = repaired.Rounds;
  r.InvertedPerRound = repaired.InvertedPerRound;
  r.RepairStalled = repaired.Stalled;
  r.RdtInvertedBeforeRepair = repaired.InitialInverted;
  r.NonManifoldFacesBeforeRepair = repaired.InitialNonManifoldFaces;

  r.Sites = sampledSites;
  r.RvdPieces = rvd.NumPieces();
  double pieces = 0.0;
  for (double v : rvd.PieceMeasure)
  {
    pieces += v;
  }
  const double domain = DomainMeasure(mesh);
  r.RvdVolumeError = std::abs(pieces - domain) / domain;

  r.Cells = rdt.NumCells();
  r.RdtInverted = rdt.NumInverted;
  r.NonManifoldFaces = rdt.NumNonManifoldFaces;
  r.UnusedSites = rdt.NumUnusedSites;

  av::SimplexMesh dual;
  dual.AmbientDim = rdt.AmbientDim;
  dual.SimplexDim = rdt.SimplexDim;
  dual.Points = rdt.Points;
  dual.Cells = rdt.Cells;
  const av::MeshQualityResult q =
    av::EvaluateMeshQuality(dual, av::InterpolateMetricAtSites(mesh, metric, sampled.Sites));
  if (dual.SimplexDim == dual.AmbientDim)
  {
    // How much of the domain the dual mesh covers (corners and edges cut off lower it).
    double covered = 0.0;
    for (std::size_t c = 0; c < dual.NumCells(); ++c)
      covered += std::abs(av::CellMeasure(dual, c));
    r.DualVolumeRatio = covered / domain;
  }
  {
    const std::vector<double> ge = av::SimplexQualityInEmbedding(
      rdt.Cells, rdt.SimplexDim, sampled.Sites.Coords, sampled.Sites.Dim);
    double sum = 0.0;
    for (double g : ge)
      sum += g;
    r.GAvgEmbedded = ge.empty() ? 0.0 : sum / static_cast<double>(ge.size());
  }
  r.GMin = q.Summary.GMin;
  r.GAvg = q.Summary.GAvg;
  r.ThetaMin = q.Summary.ThetaMin;
  r.ThetaAvg = q.Summary.ThetaAvg;
  r.PercentBad = q.Summary.PercentBad;
  r.Inverted = q.Summary.NumInverted;
  r.PercentEdgesInUnitRange = q.Summary.PercentEdgesInUnitRange;
  return r;
}

} // namespace avbench
