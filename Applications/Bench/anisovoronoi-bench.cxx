// SPDX-License-Identifier: BSD-3-Clause
// anisovoronoi-bench: runs a stage of the pipeline on one of the paper's analytic test cases and
// prints one JSON object per line (machine-readable, comparable with the paper's tables).
//
// Stages are functions StageName(const Args&, const Case&, JsonLine&) registered in Stages();
// a new stage (e.g. "mesh") only adds a function and one table entry.
#include "AnalyticMetrics.h"
#include "BoundaryLayerCases.h"
#include "EdgeLengthError.h"
#include "EmbeddingSolver.h"
#include "JsonLine.h"
#include "MeshStage.h"
#include "MeshTopology.h"
#include "MetricAdaptedMesh.h"
#include "MetricAlgebra.h"
#include "RealCases.h"
#include "MetricPreparation.h"
#include "MetricScaling.h"
#include "ReferenceEmbedding.h"
#include "Stopwatch.h"
#include "StructuredMeshes.h"
#include "SurfaceCases.h"
#include "TetMesher.h"
#include "VoronoiStage.h"

#include <Eigen/Eigenvalues>

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace
{
using avbench::JsonLine;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The bench's metric preparation defaults: the kernel's, with the CLI's cells across thin
/// parts (vtkAnisoTensorToMetric's MinCellsAcross default).
av::MetricPreparationOptions DefaultPreparation()
{
  av::MetricPreparationOptions o;
  o.MinCellsAcross = 1.25;
  return o;
}

struct Args
{
  std::string CaseName;
  std::string Stage = "embed";
  int Dim = -1;        // -1: case default (3 for gaussian2d, else 8)
  int Iterations = -1; // -1: case default (20 for gaussian2d as Fig. 4, else 50)
  int Resolution = -1; // -1: case default
  std::size_t SphereVertices = 0;
  int Threads = 0;
  std::uint64_t Seed = 1;
  double Mu = 100.0;
  bool ScaleFreeRegularizer = false;
  int Anderson = 5;
  bool DoubleSolve = false;
  bool SeparateBodies = true; // bodies apart in the embedding (EmbeddingOptions)
  std::string Solver = "auto";     // global step: auto | direct | iterative
  double CgTolerance = 1e-4;       // iterative: relative residual of each CG solve
  bool SparsePreconditioner = true; // iterative: AMG on K's element-adjacent part
  int MaxIterations = 500;         // run to convergence up to this many iterations
  double ConvergenceTolerance = 1e-4; // mean relative energy decrease per iteration to stop
  double ErrorTarget = 2.0;        // run past --iterations while L_avg (%) is above this
  std::string Init = "aligned";
  double AlignedMaxResidual = av::EmbeddingOptions{}.AlignedStartMaxResidual;
  bool Weighted = false;
  av::EmbeddingElementMetric ElementMetric = av::EmbeddingOptions{}.ElementMetric;
  bool TrackError = true;
  std::size_t Sites = 0;     // 0: case default (paper Tab. 5 / Tab. 3)
  int SampleIterations = 150; // sampler L-BFGS iterations
  int WarmupIterations = 100; // sampler warm-up iterations
  double KernelWidth = 0.3;  // sampler sigma factor
  int Lloyd = 0;             // Lloyd (CVT) steps after sampling
  bool Repair = true;        // repair inverted dual elements by site insertion
  int RepairRounds = 10;
  bool RepairNonManifold = true;
  bool ValidDual = true;
  int ImproveRounds = 1;     // site improvement rounds before the repair (0 = paper)
  int OdtIterations = 3;     // ODT steps per improvement round
  bool PerturbSlivers = true;
  bool ImproveMesh = true;   // flips and smoothing of the final mesh in the metric
  bool PlanarBoundary = true; // ...and on planar boundary patches
  bool StraightCreases = true; // ...and along straight creases
  bool VertexInsertion = true; // tets: vertex insertion in the mesh improvement
  bool Collapses = true;       // edge collapses (triangles) / contractions (tets)
  double EdgeRuleAngle = 20.0; // the edge-length rule binds tets of at least this angle
  bool BoundarySnap = true;    // tets: off-boundary vertices moved onto the boundary
  bool InputBoundaryMoves = true; // tets: folded-boundary vertices move on the input's boundary
  double BoundaryFlipDihedral = 10.0; // ...and nearly planar ones (degrees)
  double BoundaryVolumeBudget = 5e-3; // ...changing at most this fraction of the volume
  bool Features = true;      // corner / feature-line particles
  bool OdtKeepsFeatures = false; // the ODT steps keep the feature sites (surfaces)
  bool FeatureEdges = true;      // surfaces: feature-line edges put back by flips
  bool BoundaryNotches = true;   // surfaces: the open boundary's notches closed
  int MeanSmoothing = 2;         // mean-quality smoothing sweeps of the final mesh
  bool Reference = false;    // closed-form isometric embedding instead of the solver
  double FeatureAngle = 30.0;
  std::string DataDir;       // real cases: --data-dir, else AV_REAL_DATA_DIR, else build/real-data
  avbench::RealCaseOptions RealMetric; // real tensor cases: --min-eigenvalue, --max-anisotropy, --smooth
  // Metric preparation (presets keep their metric unless one of these is given).
  bool Prepare = false;
  bool NoPrepare = false; // real tensor cases: --no-prepare-metric keeps the raw metric
  av::MetricPreparationOptions Preparation = DefaultPreparation();
  double MaxStretch = 0.0;    // surface cases: curvature metric cap (0: the case's own)
  double Adapt = 0.0;        // L_bg of the adapted background mesh (0 = the preset's grid)
  bool NoAdapt = false;      // real tensor cases: --no-adapt keeps a coarse input mesh
  int RvdRepeats = 3;        // voronoi stage: best of N
  bool RvdGeometry = true;   // voronoi stage: also the runs with ComputeGeometry
  bool RvdEmbeddedPoints = false; // voronoi stage: geometry runs keep the R^Dim vertices
};

/// Paper values (Tab. 5 and Fig. 4); NaN where the paper gives none.
struct PaperValues
{
  double LAvg = kNaN, LMax = kNaN, EmbedSeconds = kNaN;
};

struct Case
{
  av::AnalyticPreset Preset = av::AnalyticPreset::Cube1; // unused by real cases
  bool Real = false;          // a real:NAME case (RealCases.h)
  double StretchMin = 0.0, StretchMax = 0.0;
  std::size_t CreaseEdges = 0;               // real surfaces: edges sharper than the crease angle
  std::size_t FilePoints = 0, FileCells = 0; // real: as read, before the split into simplices
  av::SimplexMesh Mesh;
  av::MetricField Metric;
  double MeshSeconds = 0.0;
  std::string MeshDescription;
  PaperValues Paper;
  av::MetricField RawMetric;      ///< before preparation (empty: not prepared)
  av::MetricPreparationResult Prep; ///< what the preparation did
  double PrepSeconds = 0.0;         ///< its wall time
  bool IsSurface = false;              // a generated surface with a curvature metric
  std::size_t DefaultSites = 0;        // the paper's output vertex count
  avbench::PaperMeshValues PaperMesh{}; // Tab. 5 / Tab. 3 meshing row
  double MaxStretch = 0.0;             // surface cases: the curvature metric's cap
  av::AdaptedMeshResult Background; ///< --adapt: the figures of the adaptation
  av::BackgroundResolution InputResolution; ///< real cases: the given mesh against the metric
  bool Adapted = false; ///< the embedding runs on Background.Mesh
  bool BoundaryLayer = false;          ///< a bl-linearS / bl-expS case (BoundaryLayerCases.h)
  av::BoundaryLayerMetricOptions Layer; ///< its metric
  double EmbeddingScale = 1.0;         ///< factor ScaleMetricForEmbedding applied to Metric
};

PaperValues PaperFor(av::AnalyticPreset p)
{
  PaperValues v;
  switch (p)
  {
    case av::AnalyticPreset::Gaussian2D:
      v.LAvg = 0.92;
      v.LMax = 10.58;
      break;
    case av::AnalyticPreset::Cube1:
      v = { 1.65, 17.54, 138.84 };
      break;
    case av::AnalyticPreset::Cube2:
      v = { 1.30, 48.39, 567.56 };
      break;
    case av::AnalyticPreset::Cube3:
      v = { 2.12, 71.32, 562.28 };
      break;
    case av::AnalyticPreset::SphereCylindrical:
      v = { 3.21, 65.01, 587.61 };
      break;
    case av::AnalyticPreset::SphereCosine:
      break;
  }
  return v;
}

void StretchRange(const Case& c, double& smin, double& smax)
{
  smin = std::numeric_limits<double>::infinity();
  smax = 0.0;
  for (std::size_t i = 0; i < c.Metric.NumPoints(); ++i)
  {
    double s;
    if (c.IsSurface)
    {
      // Rank-2 tangent metric: the ratio of the two nonzero eigenvalues' square roots.
      const Eigen::Vector3d l =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(av::UnpackSymmetric(c.Metric.At(i))).eigenvalues();
      s = std::sqrt(l[2] / l[1]);
    }
    else
    {
      s = c.Mesh.AmbientDim == 2 ? av::StretchRatio(av::UnpackSymmetric2(c.Metric.At(i)))
                                 : av::StretchRatio(av::UnpackSymmetric(c.Metric.At(i)));
    }
    smin = std::min(smin, s);
    smax = std::max(smax, s);
  }
}

/// Metric preparation of the case (MetricPreparation.h) for `sites` sites; keeps the raw field,
/// scaled to the prepared one's complexity, for L_avg against it.
void PrepareCaseMetric(const Args& a, Case& c, std::size_t sites)
{
  av::MetricPreparationOptions o = a.Preparation;
  o.Dimension = c.Mesh.AmbientDim == 2 ? 2 : 3;
  o.TargetSites = static_cast<double>(sites);
  const av::Stopwatch watch;
  c.Prep = av::PrepareMetric(c.Mesh, c.Metric, o);
  c.PrepSeconds = watch.Seconds();
  c.RawMetric = std::move(c.Metric);
  c.Metric = c.Prep.Metric;
  // Back from cell units to the input's scale (the embedding's regime, as the CLI does), then
  // every eigenvalue >= 1 as the embedding needs; the same factors on the raw field.
  for (double& v : c.Metric.Values)
    v /= c.Prep.Scale;
  const double t = std::pow(c.Prep.Complexity / c.Prep.RawComplexity, 2.0 / c.Mesh.SimplexDim) /
    c.Prep.Scale * av::ScaleMetricForEmbedding(c.Mesh, c.Metric).Scale;
  for (double& v : c.RawMetric.Values)
    v *= t;
}

/// The raw (unprepared) field at the adapted mesh's points: the parent points' values with the
/// parent weights (a convex combination of SPD tensors stays SPD), so L_avg_raw stays defined.
av::MetricField CarryToAdapted(const av::AdaptedMeshResult& bg, const av::MetricField& in)
{
  av::MetricField out;
  const std::size_t n = bg.Mesh.NumPoints();
  out.Values.assign(6 * n, 0.0);
  for (std::size_t p = 0; p < n; ++p)
    for (int j = 0; j < 4; ++j)
    {
      const std::int32_t id = bg.ParentIds[4 * p + j];
      if (id < 0)
        continue;
      const double w = bg.ParentWeights[4 * p + j];
      for (int k = 0; k < 6; ++k)
        out.Values[6 * p + k] += w * in.At(static_cast<std::size_t>(id))[k];
    }
  return out;
}

/// --adapt L on a real case: the embedding runs on the background adapted to the (prepared)
/// metric and the sites, as the CLI's --adapt-length L.
void AdaptRealCase(const Args& a, Case& c, std::size_t sites, double length)
{
  av::AdaptedMeshOptions o;
  o.NumberOfSites = static_cast<int>(sites);
  o.TargetLength = length;
  o.FeatureAngle = a.FeatureAngle;
  c.Background = av::AdaptBackgroundMesh(c.Mesh, c.Metric, o);
  if (!c.RawMetric.Values.empty())
    c.RawMetric = CarryToAdapted(c.Background, c.RawMetric);
  c.Mesh = c.Background.Mesh;
  c.Metric = c.Background.Metric;
  c.MeshDescription += " -> adapted " + std::to_string(length).substr(0, 4);
  c.Adapted = true;
  StretchRange(c, c.StretchMin, c.StretchMax);
}

Case BuildRealCase(const Args& a)
{
  Case c;
  c.Real = true;
  const av::Stopwatch watch;
  avbench::RealInput in =
    avbench::LoadRealCase(a.CaseName, avbench::RealDataDirectory(a.DataDir), a.RealMetric);
  c.MeshSeconds = watch.Seconds();
  c.Mesh = std::move(in.Mesh);
  c.Metric = std::move(in.Metric);
  c.MeshDescription = in.Description;
  c.StretchMin = in.StretchMin;
  c.StretchMax = in.StretchMax;
  c.CreaseEdges = in.CreaseEdges;
  c.FilePoints = in.FilePoints;
  c.FileCells = in.FileCells;
  c.DefaultSites = avbench::DefaultRealSites(in);
  c.PaperMesh = avbench::PaperMeshValues{ kNaN, kNaN, kNaN, kNaN, kNaN, kNaN };
  c.IsSurface = c.Mesh.SimplexDim == 2 && c.Mesh.AmbientDim == 3;
  // Tensor data is prepared by default, as in the CLI; curvature metrics of surfaces only when
  // asked.
  if (a.Prepare || (!c.IsSurface && !a.NoPrepare))
  {
    PrepareCaseMetric(a, c, a.Sites > 0 ? a.Sites : c.DefaultSites);
    StretchRange(c, c.StretchMin, c.StretchMax);
  }
  const std::size_t sites = a.Sites > 0 ? a.Sites : c.DefaultSites;
  c.InputResolution = av::MeasureBackgroundResolution(c.Mesh, c.Metric, static_cast<int>(sites), 1.5);
  // Tensor fields on a mesh coarser than the output are adapted by default, as in the CLI.
  if (a.Adapt > 0.0)
    AdaptRealCase(a, c, sites, a.Adapt);
  else if (!a.NoAdapt && !c.IsSurface && av::CoarserThanOutput(c.InputResolution))
    AdaptRealCase(a, c, sites, av::kAutomaticBackgroundEdgeLength);
  return c;
}

/// A surface case of Tab. 3 (SurfaceCases.h); --resolution N scales its grid by N / 100.
Case BuildSurface(const Args& a)
{
  Case c;
  const av::Stopwatch watch;
  avbench::SurfaceCase s = avbench::BuildSurfaceCase(
    a.CaseName, a.MaxStretch, a.Resolution > 0 ? a.Resolution / 100.0 : 0.0);
  c.Preset = av::AnalyticPreset::Cube1; // unused for surfaces (no reference embedding)
  c.IsSurface = true;
  c.Mesh = std::move(s.Mesh);
  c.Metric = std::move(s.Metric);
  c.MeshDescription = s.Description;
  c.DefaultSites = s.Sites;
  c.MaxStretch = s.MaxStretch;
  c.Paper = { s.Paper[0], s.Paper[1], s.Paper[2] };
  c.PaperMesh = { s.Paper[3], s.Paper[4], s.Paper[5], s.Paper[6], s.Paper[7], s.Paper[8] };
  c.MeshSeconds = watch.Seconds();
  return c;
}

/// --adapt L on an analytic case: the background adapted to the metric and the sites, with the
/// closed-form metric evaluated exactly at its points (`exact`).
void AdaptAnalyticCase(const Args& a, Case& c, std::size_t sites,
  const std::function<av::MetricField(const av::SimplexMesh&)>& exact)
{
  av::AdaptedMeshOptions o;
  o.NumberOfSites = static_cast<int>(sites);
  o.TargetLength = a.Adapt;
  o.FeatureAngle = a.FeatureAngle;
  c.Background = av::AdaptBackgroundMesh(c.Mesh, c.Metric, o);
  c.Mesh = c.Background.Mesh;
  c.Metric = exact(c.Mesh);
  c.MeshDescription += " -> adapted " + std::to_string(a.Adapt).substr(0, 4);
  c.Adapted = true;
}

/// A boundary-layer case (BoundaryLayerCases.h); --resolution N sets the vertices across the
/// wall (default 21) and the normal grading with them; --adapt L as for the presets.
Case BuildBoundaryLayer(const Args& a)
{
  Case c;
  const av::Stopwatch watch;
  avbench::BoundaryLayerCase b = avbench::BuildBoundaryLayerCase(a.CaseName, a.Resolution);
  c.BoundaryLayer = true;
  c.Layer = b.Options;
  c.Mesh = std::move(b.Mesh);
  c.Metric = std::move(b.Metric);
  c.MeshDescription = b.Description;
  c.DefaultSites = b.Sites;
  c.PaperMesh = avbench::PaperMeshValues{ kNaN, kNaN, kNaN, kNaN, kNaN, kNaN };
  c.MeshSeconds = watch.Seconds();
  const std::size_t sites = a.Sites > 0 ? a.Sites : c.DefaultSites;
  if (a.Adapt > 0.0)
    AdaptAnalyticCase(a, c, sites,
      [&](const av::SimplexMesh& m) { return av::EvaluateBoundaryLayerMetric(c.Layer, m); });
  c.InputResolution = av::MeasureBackgroundResolution(c.Mesh, c.Metric, static_cast<int>(sites), 1.5);
  if (a.Prepare)
    PrepareCaseMetric(a, c, sites);
  else
    c.EmbeddingScale = av::ScaleMetricForEmbedding(c.Mesh, c.Metric).Scale; // as the CLI does
  StretchRange(c, c.StretchMin, c.StretchMax);
  return c;
}

Case BuildCase(const Args& a)
{
  if (avbench::IsBoundaryLayerCase(a.CaseName))
  {
    return BuildBoundaryLayer(a);
  }
  if (avbench::IsRealCaseName(a.CaseName))
  {
    return BuildRealCase(a);
  }
  if (avbench::IsSurfaceCase(a.CaseName))
  {
    return BuildSurface(a);
  }
  Case c;
  c.Preset = av::AnalyticPresetFromName(a.CaseName);
  c.Paper = PaperFor(c.Preset);
  c.DefaultSites = avbench::DefaultSitesFor(c.Preset);
  c.PaperMesh = avbench::PaperMeshValuesFor(c.Preset);
  const av::AnalyticDomain d = av::RecommendedDomain(c.Preset);
  const av::Stopwatch watch;
  if (d.IsBall)
  {
    std::size_t target = d.BallVertices;
    if (a.SphereVertices > 0)
    {
      target = a.SphereVertices;
    }
    else if (a.Resolution > 0)
    {
      // N vertices across the diameter ~ (pi / 6) N^3 vertices in the ball.
      target = static_cast<std::size_t>(std::lround(3.14159265358979 / 6.0 * std::pow(a.Resolution, 3)));
    }
    c.Mesh = av::TetrahedralizeSphere(d.Radius, target);
    c.MeshDescription = "tetgen-ball-" + std::to_string(target);
  }
  else if (d.AmbientDim == 2)
  {
    const int n = a.Resolution > 0 ? a.Resolution : d.GridVertices[0];
    c.Mesh = av::MakeTriangleGrid(n, n, d.Lo, d.Hi);
    c.MeshDescription = "grid-" + std::to_string(n) + "x" + std::to_string(n);
  }
  else
  {
    int n[3] = { d.GridVertices[0], d.GridVertices[1], d.GridVertices[2] };
    if (a.Resolution > 0)
    {
      // Keep the aspect of the recommended grid (cube2/3: 5 cells along x per cell across).
      const int ratio = (d.GridVertices[0] - 1) / (d.GridVertices[1] - 1);
      n[0] = ratio * (a.Resolution - 1) + 1;
      n[1] = n[2] = a.Resolution;
    }
    c.Mesh = av::MakeKuhnTetGrid(n[0], n[1], n[2], d.Lo, d.Hi);
    c.MeshDescription = "kuhn-" + std::to_string(n[0]) + "x" + std::to_string(n[1]) + "x" + std::to_string(n[2]);
  }
  c.Metric = av::EvaluateAnalyticMetric(c.Preset, c.Mesh);
  c.MeshSeconds = watch.Seconds();
  if (a.Adapt > 0.0)
    AdaptAnalyticCase(a, c, a.Sites > 0 ? a.Sites : c.DefaultSites,
      [&](const av::SimplexMesh& m) { return av::EvaluateAnalyticMetric(c.Preset, m); });
  if (a.Prepare)
    PrepareCaseMetric(a, c, a.Sites > 0 ? a.Sites : c.DefaultSites);
  StretchRange(c, c.StretchMin, c.StretchMax);
  return c;
}

double PeakRssMb()
{
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0; // Linux: kilobytes
}

/// The preset's exact isometric embedding (ReferenceEmbedding.h) instead of the solver: what
/// the rest of the pipeline gives when the embedding is not the limit.
void EmbedReference(const Case& c, int dim, JsonLine& out, av::Embedding* keep)
{
  const av::Stopwatch watch;
  av::Embedding ref = c.BoundaryLayer
    ? av::BoundaryLayerIsometricEmbedding(c.Layer, c.Mesh, dim, c.EmbeddingScale)
    : av::ComputeReferenceEmbedding(c.Preset, c.Mesh, dim);
  const double seconds = watch.Seconds();
  const av::EdgeLengthErrorResult e = av::ComputeEdgeLengthError(c.Mesh, c.Metric, ref);
  out.Set("embedding", "reference");
  out.Set("dim", dim);
  out.Set("L_avg", e.AveragePercent);
  out.Set("L_max", e.MaxPercent);
  out.Set("embed_seconds", seconds);
  if (keep)
  {
    *keep = std::move(ref);
  }
}

av::EmbeddingOptions EmbeddingOptionsFor(const Args& a, const Case& c, int dim)
{
  av::EmbeddingOptions o;
  o.TargetDim = dim;
  const bool gaussian = !c.Real && !c.IsSurface && c.Preset == av::AnalyticPreset::Gaussian2D;
  o.Iterations = a.Iterations >= 0 ? a.Iterations : (gaussian ? 20 : 50);
  o.Mu = a.Mu;
  o.ScaleFreeRegularizer = a.ScaleFreeRegularizer;
  o.Seed = a.Seed;
  o.AndersonWindow = a.Anderson;
  o.SinglePrecisionSolve = !a.DoubleSolve;
  o.SeparateBodies = a.SeparateBodies;
  o.GlobalSolver = a.Solver == "direct"    ? av::EmbeddingGlobalSolver::Direct
    : a.Solver == "iterative" ? av::EmbeddingGlobalSolver::Iterative
                              : av::EmbeddingGlobalSolver::Automatic;
  o.IterativeTolerance = a.CgTolerance;
  o.SparsePreconditioner = a.SparsePreconditioner;
  o.MaxIterations = a.MaxIterations;
  o.ConvergenceTolerance = a.ConvergenceTolerance;
  o.TargetAverageErrorPercent = a.ErrorTarget;
  o.ElementMeasureWeighting = a.Weighted;
  o.ElementMetric = a.ElementMetric;
  o.Initialization = a.Init == "random" ? av::EmbeddingInitialization::Random
    : a.Init == "smooth"                 ? av::EmbeddingInitialization::Smooth
                                         : av::EmbeddingInitialization::MetricAligned;
  o.AlignedStartMaxResidual = a.AlignedMaxResidual;
  return o;
}

/// The keys of the "embed" report of a solver run (`reached`: first iteration at the paper's
/// L_avg, -1 if none).
void ReportEmbedding(const Args& a, const Case& c, const av::EmbeddingOptions& o,
  const av::EmbeddingResult& r, const av::EdgeLengthErrorResult& e, double embedSeconds,
  int reached, double errorAtIterations, JsonLine& out)
{
  out.Set("embedding", "solver");
  out.Set("dim", o.TargetDim);
  out.Set("iterations", r.IterationsDone);
  out.Set("L_avg", e.AveragePercent);
  out.Set("L_max", e.MaxPercent);
  out.Set("metric_prep", !c.RawMetric.Values.empty());
  if (!c.RawMetric.Values.empty())
  {
    const av::EdgeLengthErrorResult raw = av::ComputeEdgeLengthError(c.Mesh, c.RawMetric, r.Embedded);
    out.Set("L_avg_raw", raw.AveragePercent);
    out.Set("L_max_raw", raw.MaxPercent);
    out.Set("metric_prep_median_change", c.Prep.Deviation.Median);
    out.Set("metric_prep_p95_change", c.Prep.Deviation.Percentile95);
    out.Set("metric_prep_max_change", c.Prep.Deviation.Maximum);
    out.Set("metric_prep_changed_fraction", c.Prep.Deviation.ChangedFraction);
    out.Set("metric_prep_graded_vertices", c.Prep.NumGraded);
    out.Set("metric_prep_thickness_limited", c.Prep.NumThicknessLimited);
    out.Set("metric_prep_cells_across", c.Prep.CellsAcross);
    out.Set("metric_prep_seconds", c.PrepSeconds);
    out.Set("metric_prep_gradations", c.Prep.GradationRuns);
    out.Set("metric_prep_sweeps", c.Prep.TotalGradationSweeps);
    out.Set("metric_implied_sites", c.Prep.ImpliedSites);
  }
  out.Set("embed_seconds", embedSeconds);
  out.Set("setup_seconds", r.SetupSeconds);
  out.Set("factor_seconds", r.FactorSeconds);
  out.Set("iteration_seconds", r.IterationSeconds);
  out.Set("local_step_seconds", r.LocalStepSeconds);
  out.Set("solve_seconds", r.SolveSeconds);
  out.Set("factor_entries", r.FactorNonZeros);
  out.Set("element_metric_fallbacks", r.ElementMetricFallbacks);
  out.Set("energy_initial", r.EnergyHistory.front().Total);
  out.Set("energy_final", r.EnergyHistory.back().Total);
  out.Set("anderson_accepted", r.AndersonAccepted);
  out.Set("anderson_rejected", r.AndersonRejected);
  out.Set("solve_precision", a.DoubleSolve ? "double" : "single");
  out.Set("double_precision_retries", r.DoublePrecisionRetries);
  out.Set("global_solver",
    r.IterativeSolve ? "iterative" : (r.SwitchedToDirect ? "iterative, then direct" : "direct"));
  if (r.IterativeSolve || r.SwitchedToDirect)
  {
    out.Set("cg_tolerance", o.IterativeTolerance);
    out.Set("amg_matrix", o.SparsePreconditioner ? "element-adjacent" : "full");
    out.Set("cg_solves", r.SolverSolves);
    out.Set("cg_iterations_per_solve",
      r.SolverSolves > 0 ? static_cast<double>(r.SolverIterations) / r.SolverSolves : 0.0);
    out.Set("cg_max_iterations", r.SolverMaxIterations);
  }
  out.Set("max_iterations", o.MaxIterations);
  out.Set("convergence_tolerance", o.ConvergenceTolerance);
  out.Set("final_relative_decrease", r.FinalRelativeDecrease);
  out.Set("converged", r.Converged);
  out.Set("stalled", r.Stalled);
  out.Set("error_target", o.TargetAverageErrorPercent);
  out.Set("reached_error_target", r.ReachedErrorTarget);
  if (std::isfinite(errorAtIterations))
  {
    out.Set("L_avg_at_min_iterations", errorAtIterations);
  }
  out.Set("paper_L_avg", c.Paper.LAvg);
  out.Set("paper_L_max", c.Paper.LMax);
  out.Set("paper_embed_seconds", c.Paper.EmbedSeconds);
  if (a.TrackError && std::isfinite(c.Paper.LAvg))
  {
    out.Set("iterations_to_paper_error", reached);
  }
  out.Set("mu", o.Mu);
  out.Set("scale_free_regularizer", o.ScaleFreeRegularizer);
  out.Set("anderson", o.AndersonWindow);
  out.Set("init", a.Init);
  out.Set("aligned_start", r.AlignedStart);
  out.Set("aligned_start_residual", r.AlignedStartResidual);
  out.Set("weighted", a.Weighted);
  out.Set("seed", static_cast<long long>(a.Seed));
}

/// Stage "embed": the high-d embedding and its §5.1 edge length error (kept in *keep if given).
void StageEmbed(const Args& a, const Case& c, JsonLine& out, av::Embedding* keep = nullptr)
{
  const int dim = a.Dim > 0 ? a.Dim : (c.Mesh.AmbientDim == 2 ? 3 : 8);
  if (a.Reference && c.IsSurface)
  {
    throw std::runtime_error("--reference-embedding: the surface cases have no closed-form embedding");
  }
  if (a.Reference)
  {
    if (c.Real)
    {
      throw std::runtime_error("--reference-embedding needs an analytic preset");
    }
    EmbedReference(c, dim, out, keep);
    return;
  }
  av::EmbeddingOptions o = EmbeddingOptionsFor(a, c, dim);
  std::unique_ptr<av::EdgeLengthErrorEvaluator> evaluator;
  if (a.TrackError)
  {
    evaluator.reset(new av::EdgeLengthErrorEvaluator(c.Mesh, c.Metric));
  }
  int reached = -1;
  double trackSeconds = 0.0;
  double errorAtIterations = kNaN; // L_avg after the fixed count, before running to convergence
  if (evaluator && std::isfinite(c.Paper.LAvg))
  {
    // Error per iteration; its cost is measured and left out of embed_seconds.
    o.Progress = [&](const av::EmbeddingProgress& p) {
      const av::Stopwatch trackWatch;
      const double lavg = evaluator->Evaluate(p.Solver->CurrentEmbedding()).AveragePercent;
      if (reached < 0 && lavg <= c.Paper.LAvg)
      {
        reached = p.Iteration;
      }
      if (p.Iteration == o.Iterations)
      {
        errorAtIterations = lavg;
      }
      trackSeconds += trackWatch.Seconds();
      return true;
    };
  }
  const av::Stopwatch watch;
  av::EmbeddingResult r = av::ComputeEmbedding(c.Mesh, c.Metric, o);
  const double embedSeconds = watch.Seconds() - trackSeconds;
  const av::EdgeLengthErrorResult e = evaluator ? evaluator->Evaluate(r.Embedded)
                                                : av::ComputeEdgeLengthError(c.Mesh, c.Metric, r.Embedded);
  ReportEmbedding(a, c, o, r, e, embedSeconds, reached, errorAtIterations, out);
  if (keep)
  {
    *keep = std::move(r.Embedded);
  }
}

/// The embedding the mesh stage works on: with "all" its full "embed" report goes to `out`,
/// with "mesh" only its kind and dimension.
av::Embedding EmbedForMesh(const Args& a, const Case& c, JsonLine& out)
{
  av::Embedding embedded;
  if (a.Stage == "all")
  {
    StageEmbed(a, c, out, &embedded);
  }
  else
  {
    Args quiet = a;
    quiet.TrackError = false; // the per-iteration error is only for the embed report
    JsonLine scratch;
    StageEmbed(quiet, c, scratch, &embedded);
    out.Set("embedding", a.Reference ? "reference" : "solver");
    out.Set("dim", embedded.Dim);
  }
  return embedded;
}

avbench::MeshStageOptions MeshStageOptionsFor(const Args& a, const Case& c)
{
  avbench::MeshStageOptions o;
  o.Sites = a.Sites > 0 ? a.Sites : c.DefaultSites;
  o.SampleIterations = a.SampleIterations;
  o.WarmupIterations = a.WarmupIterations;
  o.Seed = a.Seed;
  o.KernelWidthFactor = a.KernelWidth;
  o.LloydIterations = a.Lloyd;
  o.Repair = a.Repair;
  o.MaxRepairRounds = a.RepairRounds;
  o.RepairNonManifold = a.RepairNonManifold;
  o.ValidDual = a.ValidDual;
  o.ImproveRounds = a.ImproveRounds;
  o.OdtIterations = a.OdtIterations;
  o.PerturbSlivers = a.PerturbSlivers;
  o.ImproveMesh = a.ImproveMesh;
  o.PlanarBoundary = a.PlanarBoundary;
  o.StraightCreases = a.StraightCreases;
  o.VertexInsertion = a.VertexInsertion;
  o.Collapses = a.Collapses;
  o.EdgeRuleAngle = a.EdgeRuleAngle;
  o.BoundarySnap = a.BoundarySnap;
  o.InputBoundaryMoves = a.InputBoundaryMoves;
  o.BoundaryFlipMaxDihedral = a.BoundaryFlipDihedral;
  o.BoundaryFlipVolumeBudget = a.BoundaryVolumeBudget;
  o.PreserveSharpFeatures = a.Features;
  o.OdtKeepsFeatureSites = a.OdtKeepsFeatures;
  o.RecoverFeatureEdges = a.FeatureEdges;
  o.CloseBoundaryNotches = a.BoundaryNotches;
  o.MeanSmoothingSweeps = a.MeanSmoothing;
  o.FeatureAngle = a.FeatureAngle;
  return o;
}

/// The keys of the "mesh" report.
void ReportMesh(const Case& c, const avbench::MeshStageOptions& o,
  const avbench::MeshStageResult& r, JsonLine& out)
{
  const avbench::PaperMeshValues& p = c.PaperMesh;
  out.Set("sites", r.Sites);
  out.Set("sharp_features", o.PreserveSharpFeatures);
  out.Set("odt_keeps_feature_sites", o.OdtKeepsFeatureSites);
  out.Set("recover_feature_edges", o.RecoverFeatureEdges);
  out.Set("feature_angle", o.FeatureAngle);
  out.Set("corner_sites", r.CornerSites);
  out.Set("feature_line_sites", r.FeatureLineSites);
  out.Set("sample_iterations", o.SampleIterations);
  out.Set("warmup_iterations", o.WarmupIterations);
  out.Set("sample_seconds", r.SampleSeconds);
  out.Set("kernel_width", o.KernelWidthFactor);
  out.Set("lloyd_iterations", o.LloydIterations);
  out.Set("lloyd_seconds", r.LloydSeconds);
  out.Set("rvd_seconds", r.RvdSeconds);
  out.Set("rdt_seconds", r.RdtSeconds);
  out.Set("improve_rounds", o.ImproveRounds);
  out.Set("odt_iterations", o.OdtIterations);
  out.Set("perturb_slivers", o.PerturbSlivers);
  out.Set("improve_seconds", r.ImproveSeconds);
  out.Set("odt_moved_sites", r.OdtMovedSites);
  out.Set("slivers_perturbed", r.SliversPerturbed);
  out.Set("repair", o.Repair);
  out.Set("repair_nonmanifold", o.RepairNonManifold);
  out.Set("valid_dual", o.ValidDual);
  out.Set("repair_seconds", r.RepairSeconds);
  out.Set("mesh_improvement", o.ImproveMesh);
  out.Set("mesh_improvement_seconds", r.MeshImprovementSeconds);
  out.Set("mesh_improvement_flips", r.ImprovementFlips);
  out.Set("mesh_improvement_smoothed", r.ImprovementSmoothed);
  out.Set("mesh_improvement_boundary_ops", r.ImprovementBoundaryOps);
  out.Set("mesh_improvement_crease_moves", r.ImprovementCreaseMoves);
  out.Set("mesh_improvement_insertions", r.ImprovementInsertions);
  out.Set("mesh_improvement_peels", r.ImprovementPeels);
  out.Set("mesh_improvement_collapses", r.ImprovementCollapses);
  out.Set("mesh_improvement_snaps", r.ImprovementSnaps);
  out.Set("mesh_improvement_worst_before", r.ImprovementWorstBefore);
  out.Set("mesh_improvement_worst_after", r.ImprovementWorstAfter);
  out.Set("feature_edges_required", r.FeatureEdgesRequired);
  out.Set("feature_edges_missing_before", r.FeatureEdgesMissingBefore);
  out.Set("feature_edges_recovered", r.FeatureEdgesRecovered);
  out.Set("feature_edges_missing", r.FeatureEdgesMissing);
  out.Set("close_boundary_notches", o.CloseBoundaryNotches);
  out.Set("mean_smoothing_sweeps", o.MeanSmoothingSweeps);
  out.Set("mesh_improvement_mean_smoothed", r.ImprovementMeanSmoothed);
  out.Set("boundary_notches", r.BoundaryNotches);
  out.Set("boundary_notches_closed", r.BoundaryNotchesClosed);
  out.Set("boundary_notches_left", r.BoundaryNotchesLeft);
  out.Set("mesh_improvement_volume_change", r.ImprovementVolumeChange);
  out.Set("valid_dual_replaced", r.ValidDualReplaced);
  out.Set("valid_dual_seconds", r.ValidDualSeconds);
  out.Set("valid_dual_target_cells", r.ValidDualTargetCells);
  out.Set("valid_dual_kept_cells", r.ValidDualKeptCells);
  out.Set("valid_dual_target_flips", r.ValidDualTargetFlips);
  out.Set("inverted_before_mesh_improvement", r.InvertedBeforeImprovement);
  out.Set("repair_rounds", r.RepairRounds);
  out.Set("inverted_per_round", r.InvertedPerRound);
  out.Set("repair_stalled", r.RepairStalled);
  out.Set("inserted_sites", r.InsertedSites);
  out.Set("mesh_seconds", r.MeshSeconds);
  out.Set("output_cells", r.Cells);
  out.Set("G_min", r.GMin);
  out.Set("G_avg", r.GAvg);
  out.Set("G_avg_embedded", r.GAvgEmbedded);
  out.Set("theta_min", r.ThetaMin);
  out.Set("theta_avg", r.ThetaAvg);
  out.Set("pct_bad", r.PercentBad);
  out.Set("inverted", r.Inverted);
  out.Set("rdt_inverted", r.RdtInverted);
  out.Set("rdt_inverted_before_repair", r.RdtInvertedBeforeRepair);
  out.Set("nonmanifold_faces_before_repair", r.NonManifoldFacesBeforeRepair);
  out.Set("edges_in_unit_range", r.PercentEdgesInUnitRange);
  out.Set("rvd_volume_error", r.RvdVolumeError);
  if (r.DualVolumeRatio > 0.0)
    out.Set("dual_volume_ratio", r.DualVolumeRatio);
  out.Set("rvd_pieces", r.RvdPieces);
  out.Set("nonmanifold_faces", r.NonManifoldFaces);
  out.Set("cross_body_elements", r.CrossBodyElements);
  out.Set("cross_body_pieces", r.CrossBodyPieces);
  out.Set("pinched_boundary_edges", r.PinchedBoundaryEdges);
  if (r.DomainAngleBound >= 0.0)
  {
    out.Set("theta_domain_bound", r.DomainAngleBound);
    out.Set("domain_edges_below_15", r.DomainEdgesBelow15);
  }
  if (r.MeshBoundaryAngle >= 0.0)
  {
    out.Set("theta_mesh_boundary", r.MeshBoundaryAngle);
    out.Set("mesh_boundary_edges_below_15", r.MeshBoundaryEdgesBelow15);
  }
  out.Set("unused_sites", r.UnusedSites);
  out.Set("paper_G_min", p.GMin);
  out.Set("paper_G_avg", p.GAvg);
  out.Set("paper_theta_min", p.ThetaMin);
  out.Set("paper_theta_avg", p.ThetaAvg);
  out.Set("paper_pct_bad", p.PercentBad);
  out.Set("paper_mesh_seconds", p.MeshSeconds);
  if (r.IsSurface)
  {
    out.Set("hausdorff", r.HausdorffPercent);
    out.Set("hausdorff_to_input", r.HausdorffForwardPercent);
    out.Set("hausdorff_from_input", r.HausdorffBackwardPercent);
    out.Set("self_intersections", r.SelfIntersections);
    out.Set("flipped", r.Flipped);
    out.Set("euler", r.Euler);
    out.Set("input_euler", r.InputEuler);
    out.Set("boundary_loops", r.BoundaryLoops);
    out.Set("input_boundary_loops", r.InputBoundaryLoops);
    out.Set("nonmanifold_edges", r.NonManifoldEdges);
    out.Set("max_stretch_cap", c.MaxStretch);
  }
  if (!c.Real && !c.IsSurface && c.Preset == av::AnalyticPreset::Gaussian2D)
  {
    out.Set("paper_mesh_note", "Tab. 3 2D Domain row: a different metric");
  }
}

/// Stage "mesh" (and "all" = embed + mesh keys): sampling, RVD, RDT and the dual's quality.
/// The embedding is computed first; with "mesh" only its dimension is reported.
void StageMesh(const Args& a, const Case& c, JsonLine& out)
{
  const av::Embedding embedded = EmbedForMesh(a, c, out);
  const avbench::MeshStageOptions o = MeshStageOptionsFor(a, c);
  ReportMesh(c, o, avbench::RunMeshStage(c.Mesh, c.Metric, embedded, o), out);
}

/// Stage "voronoi": sampling as "mesh" does, then the RVD alone, timed without / with
/// geometry and without / with its whole-element fast path (keys rvd_<geom|lean>_<fast|full>_*).
void StageVoronoi(const Args& a, const Case& c, JsonLine& out)
{
  const av::Embedding embedded = EmbedForMesh(a, c, out);
  const avbench::MeshStageOptions o = MeshStageOptionsFor(a, c);
  const avbench::VoronoiStageResult r =
    avbench::RunVoronoiStage(
      c.Mesh, embedded, o, a.RvdRepeats, a.RvdGeometry, a.RvdEmbeddedPoints);
  out.Set("sites", r.Sites);
  out.Set("elements", r.Elements);
  out.Set("sample_seconds", r.SampleSeconds);
  out.Set("rvd_repeats", a.RvdRepeats);
  out.Set("rvd_embedded_points", a.RvdEmbeddedPoints);
  out.Set("rvd_peak_rss", r.PeakIsReset ? "VmHWM reset per run" : "getrusage maxrss delta");
  for (const avbench::VoronoiRun& run : r.Runs)
  {
    const std::string p =
      std::string("rvd_") + (run.Geometry ? "geom_" : "lean_") + (run.FastPath ? "fast_" : "full_");
    out.Set(p + "seconds", run.BestSeconds);
    out.Set(p + "cpu_seconds", run.BestCpuSeconds);
    out.Set(p + "peak_rss_mb", run.PeakRssMb);
    out.Set(p + "output_mb", run.OutputMb);
    out.Set(p + "pieces", run.Pieces);
    if (run.Geometry)
      out.Set(p + "vertices", run.Vertices);
    if (run.FastPath)
    {
      out.Set(p + "whole_elements", run.WholeElements);
      out.Set(p + "whole_fraction",
        r.Elements ? static_cast<double>(run.WholeElements) / static_cast<double>(r.Elements)
                   : 0.0);
      out.Set(p + "same_as_full", run.SameAsNoFastPath);
    }
  }
}

using StageFn = std::function<void(const Args&, const Case&, JsonLine&)>;
const std::map<std::string, StageFn>& Stages()
{
  static const std::map<std::string, StageFn> stages = {
    { "embed", [](const Args& a, const Case& c, JsonLine& o) { StageEmbed(a, c, o); } },
    { "mesh", StageMesh }, { "all", StageMesh }, { "voronoi", StageVoronoi } };
  return stages;
}

void Usage(std::ostream& os)
{
  os
    << "usage: anisovoronoi-bench CASE [options]\n"
       "  CASE: gaussian2d | cube1 | cube2 | cube3 | sphere-cyl | sphere-cos | all\n"
       "        | cyclide | cyclide2 | torus | surfaces (Tab. 3 surfaces, curvature metric Eq. "
       "19)\n"
       "        | real:NAME | real:all  (real data of scripts/make-real-data.sh; NAME:\n"
       "        compressor rotor segmenttet cubef2f1 hueeber1 squarebend mixer (tensor\n"
       "        fields, default 3000 sites) turbine knot1 mushroom fandisk (curvature,\n"
       "        default 2000 sites); Documentation/real-data.md)\n"
       "        | bl-linearS | bl-expS | boundary-layers  (analytic boundary layer with wall\n"
       "        stretch S on a background graded along the normal; boundary-layers = bl-linear100\n"
       "        bl-linear1000 bl-exp100 bl-exp1000; sites from the metric's complexity)\n"
       "  --data-dir D      real-data directory (default $AV_REAL_DATA_DIR, else\n"
       "                    real-data next to the bin/ folder of this program)\n"
       "  --min-eigenvalue F, --max-anisotropy A, --smooth N  real tensor cases: the tensor ->\n"
       "                    metric options of the anisovoronoi tool (defaults 1e-3, 25, 0)\n"

       "  --stage S         embed | mesh (embedding, then sampling + RVD + RDT + quality) | all\n"
       "                    (both reports) | voronoi (embedding, sampling, then the RVD alone:\n"
       "                    best-of-N times and peak RSS without / with geometry and without /\n"
       "                    with the whole-element fast path); default embed\n"
       "  --rvd-repeats N   voronoi: runs per configuration, the best time is kept (default 3)\n"
       "  --no-rvd-geometry voronoi: only the runs without geometry\n"
       "  --rvd-embedded-points  voronoi: the geometry runs keep the vertices in R^Dim too\n"
       "                    (KeepEmbeddedPoints, off by default)\n"
       "  --dim D           target dimension (default 3 for gaussian2d, else 8)\n"
       "  --iterations N    solver iterations (default 20 for gaussian2d as Fig. 4, else 50)\n"
       "  --resolution N    N vertices per side (cube2/3 keep 5:1:1, spheres ~pi/6 N^3 vertices);\n"
       "                    default: gaussian2d 101^2, cube1 21^3, cube2/3 101x21x21, spheres "
       "50,000\n"
       "  --vertices V      target vertex count of the sphere meshes (TetGen)\n"
       "  --threads T       limit TBB threads (default: all cores)\n"
       "  --seed S          random seed of the initial field (default 1)\n"
       "  --mu M            regularizer weight (default 100)\n"
       "  --scale-free-regularizer  E_reg in units of the largest bounding-box extent\n"
       "                    (default: in the input's length unit, as printed in the paper)\n"
       "  --anderson W      Anderson window, 0 = plain local/global (default 5)\n"
       "  --double-solve    global steps with CHOLMOD's double solve (default: float factor copy)\n"
       "  --no-separate-bodies  parts of the input with no shared point stay where the solve\n"
       "                    leaves them in R^m (default: moved apart, meshed as separate domains)\n"
       "  --solver S        global step: auto (direct below 20,000 tet /\n"
       "                    150,000 triangle mesh vertices) | direct | "
       "iterative\n"
       "  --cg-tolerance T  iterative: relative residual of each CG solve (default 1e-4)\n"
       "  --full-preconditioner  iterative: AMG hierarchy on the whole K (default: on its\n"
       "                    element-adjacent part, the regularizer's two-ring on the diagonal)\n"
       "  --max-iterations N  run to convergence up to N iterations (default 500; <= "
       "--iterations:\n"
       "                    exactly --iterations)\n"
       "  --convergence-tolerance T  stop past --iterations when the energy drops by less than T\n"
       "                    per iteration (mean of the last 10; default 1e-4)\n"
       "  --error-target P  past --iterations, stop once L_avg <= P % (default 2; 0 = none)\n"
       "  --init aligned|smooth|random  initial free coordinates (default aligned: fitted to\n"
       "                    (M - I)^{1/2}, smooth where that fit is poor; EmbeddingSolver.h)\n"
       "  --aligned-max-residual R  aligned: the fit's largest relative residual kept (0.005)\n"
       "  --weighted        element-measure weighted energy (default: paper's unweighted)\n"
       "  --element-metric mean|edges  each element's metric: its vertex mean (default), or the one\n"
       "                    of its edges' 5.1 lengths (consistent between neighbours)\n"
       "  --no-track        do not evaluate L_avg per iteration (iterations_to_paper_error)\n"
       "  --sites N         sites for mesh (default: cube1 2000, cube2 5000, cube3 5600,\n"
       "                    sphere-cyl 5000, sphere-cos 1000, gaussian2d 4000)\n"
       "  --sample-iterations N  sampler iterations (default 150; the paper: 50)\n"
       "  --warmup-iterations N  sampler warm-up iterations at sigma factor 0.25 (default 100)\n"
       "  --kernel-width F  sampler sigma factor (default 0.3)\n"
       "  --lloyd N         Lloyd (CVT) steps after sampling (default 0)\n"
       "  --no-repair       mesh: keep inverted dual elements (default: insert sites at their\n"
       "                    Voronoi vertices until none is left)\n"
       "  --repair-rounds N mesh: insertion rounds at most (default 10)\n"
       "  --no-repair-nonmanifold  mesh: leave non-manifold faces of the dual (default: insert\n"
       "                    sites at the Voronoi vertices around them too)\n"
       "  --no-valid-dual   mesh: keep a volume dual still invalid after the repair (default:\n"
       "                    Delaunay of its sites, carved, flipped towards the metric)\n"
       "  --improve-rounds N  mesh: site improvement rounds before the repair: ODT steps\n"
       "                    and sliver pushes, then RVD + RDT again (default 1, 0 = the\n"
       "                    paper's pipeline)\n"
       "  --odt-iterations N  mesh: ODT steps per improvement round (default 3, 0 = none)\n"
       "  --no-sliver-push  mesh: no sliver pushes in the improvement rounds\n"
       "  --no-mesh-improvement  mesh: keep the repaired dual as it is (default: flips and\n"
       "                    vertex smoothing raise its worst element in the metric)\n"
       "  --no-planar-boundary  mesh: the improvement leaves every boundary vertex and face\n"
       "                    as it is (default: it also moves vertices and removes edges in\n"
       "                    planar boundary patches)\n"
       "  --no-straight-creases  mesh: feature-line vertices of tet meshes stay (default: they\n"
       "                    slide along straight creases, the two planes kept exactly)\n"
       "  --no-vertex-insertion  mesh: the improvement of tet meshes adds no vertices (default:\n"
       "                    it inserts one where flips and smoothing leave a tet below the\n"
       "                    --edge-rule-angle)\n"
       "  --no-collapses    mesh: the improvement removes no vertices (default: edge collapses\n"
       "                    of triangles; tets: contraction of a free interior vertex into a\n"
       "                    neighbour where a tet below the --edge-rule-angle stays bad)\n"
       "  --edge-rule-angle A  mesh: tets of at least A degrees keep the edge-length rule (no\n"
       "                    new out-of-range edges); worse ones may be flipped, smoothed,\n"
       "                    split, contracted and peeled at that price (default 20)\n"
       "  --no-boundary-snap  mesh: boundary vertices of tet meshes that lie inside the domain\n"
       "                    stay there (default: moved onto the domain's boundary where that\n"
       "                    raises their worst tet)\n"
       "  --no-input-boundary-moves  mesh: boundary vertices of tet meshes whose faces are\n"
       "                    folded stay (default: they move on the input's boundary)\n"
       "  --boundary-flip-dihedral D  mesh: the improvement also removes boundary edges whose\n"
       "                    two faces are at most D degrees from coplanar (default 10; 0 =\n"
       "                    planar only), at most 0.5 % of the volume in all\n"
       "  --boundary-volume-budget F  mesh: that share of the volume (default 5e-3)\n"
       "  --no-features     mesh: no corner / feature-line particles (paper §4.1 sharp features)\n"
       "  --keep-feature-sites  mesh: the ODT steps keep the corner and feature-line sites on\n"
       "                    surfaces too (default: only the sliver push does)\n"
       "  --no-feature-edges  mesh: surfaces: no flips that put the edges between sites\n"
       "                    consecutive along a feature line into the dual\n"
       "  --mean-smoothing N  mesh: sweeps of the final mesh's vertices that raise the mean\n"
       "                    shape G of their star, never its worst element (default 2, 0 =\n"
       "                    the worst-first improvement only)\n"
       "  --no-boundary-notches  mesh: surfaces: leave the dual's boundary vertices that are\n"
       "                    off the input's open boundary (default: close those notches)\n"
       "  --feature-angle A mesh: dihedral angle in degrees above which a boundary edge is a\n"
       "                    feature line (default 30)\n"
       "  --adapt L         embed on the adapted background mesh (MetricAdaptedMesh) with edges "
       "of\n"
       "                    at most L output edges for the sites (0.5: two per output edge);\n"
       "                    on real: cases, after the metric preparation. Default: real\n"
       "                    tensor cases whose mesh is coarser than the output (mean edge\n"
       "                    longer than one output edge) are adapted with L = 1.5\n"
       "  --no-adapt        real tensor cases: embed on the given mesh, however coarse\n"
       "  --reference-embedding  the preset's exact isometric embedding (x, y, z, H) instead\n"
       "                    of the solver (all presets but sphere-cos): separates the\n"
       "                    embedding's share of a quality loss from the rest\n"
       "  --prepare-metric  prepare the preset's metric for the sites (gradation 1.3), as do\n"
       "  --hmin H --hmax H --hgrad B --size-mode tensor|uniform|blend --size-blend A\n"
       "                    (--no-gradation: none); adds L_avg_raw, metric_prep_* keys\n"
       "  --min-cells-across K  cells across thin parts of volumes (default 1.25, 0 = off)\n"
       "  --no-prepare-metric  real tensor cases (prepared by default, as the CLI does):\n"
       "                    the raw metric\n"
       "  --crease-angle A  real surface cases: edges sharper than A degrees are creases the\n"
       "                    curvature metric is not estimated across (default 180 = none)\n"
       "  --max-stretch S   surface cases: cap on the curvature metric's stretch ratio\n"
       "                    (default: cyclide, torus 10; cyclide2 29 as Tab. 3)\n"
       "  surface cases: --resolution N scales the parameter grid by N / 100; the mesh\n"
       "  report adds hausdorff (% of the bounding-box diagonal, both directions),\n"
       "  self_intersections, flipped, euler, boundary_loops\n"
       "Prints one JSON object per case on stdout.\n";
}

/// Throws std::runtime_error for option values out of range.
void CheckArgs(const Args& a)
{
  if (a.Init != "aligned" && a.Init != "smooth" && a.Init != "random")
  {
    throw std::runtime_error("--init must be aligned, smooth or random");
  }
  if (a.Solver != "auto" && a.Solver != "direct" && a.Solver != "iterative")
  {
    throw std::runtime_error("--solver must be auto, direct or iterative");
  }
  if (a.WarmupIterations < 0)
  {
    throw std::runtime_error("--warmup-iterations must be >= 0");
  }
  if (a.ImproveRounds < 0 || a.OdtIterations < 0)
  {
    throw std::runtime_error("--improve-rounds and --odt-iterations must be >= 0");
  }
  if (a.RepairRounds < 0)
  {
    throw std::runtime_error("--repair-rounds must be >= 0");
  }
  if (!(a.EdgeRuleAngle >= 0.0 && a.EdgeRuleAngle <= 90.0))
  {
    throw std::runtime_error("--edge-rule-angle must be in [0, 90]");
  }
  if (a.MaxStretch < 0.0 || (a.MaxStretch > 0.0 && a.MaxStretch < 1.0))
  {
    throw std::runtime_error("--max-stretch must be >= 1");
  }
  if (a.Resolution != -1 && a.Resolution < 2)
  {
    throw std::runtime_error("--resolution must be >= 2");
  }
}

bool Parse(int argc, char** argv, Args& a)
{
  if (argc < 2)
  {
    return false;
  }
  for (int i = 1; i < argc; ++i)
  {
    const std::string k = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc)
      {
        throw std::runtime_error("missing value after " + k);
      }
      return argv[++i];
    };
    if (k == "--help" || k == "-h")
    {
      return false;
    }
    else if (k == "--stage")
      a.Stage = next();
    else if (k == "--dim")
      a.Dim = std::stoi(next());
    else if (k == "--iterations")
      a.Iterations = std::stoi(next());
    else if (k == "--resolution")
      a.Resolution = std::stoi(next());
    else if (k == "--vertices")
      a.SphereVertices = static_cast<std::size_t>(std::stoll(next()));
    else if (k == "--threads")
      a.Threads = std::stoi(next());
    else if (k == "--seed")
      a.Seed = static_cast<std::uint64_t>(std::stoull(next()));
    else if (k == "--mu")
      a.Mu = std::stod(next());
    else if (k == "--scale-free-regularizer")
      a.ScaleFreeRegularizer = true;
    else if (k == "--anderson")
      a.Anderson = std::stoi(next());
    else if (k == "--double-solve")
      a.DoubleSolve = true;
    else if (k == "--no-separate-bodies")
      a.SeparateBodies = false;
    else if (k == "--solver")
      a.Solver = next();
    else if (k == "--cg-tolerance")
      a.CgTolerance = std::stod(next());
    else if (k == "--full-preconditioner")
      a.SparsePreconditioner = false;
    else if (k == "--max-iterations")
      a.MaxIterations = std::stoi(next());
    else if (k == "--convergence-tolerance")
      a.ConvergenceTolerance = std::stod(next());
    else if (k == "--error-target")
      a.ErrorTarget = std::stod(next());
    else if (k == "--init")
      a.Init = next();
    else if (k == "--aligned-max-residual")
      a.AlignedMaxResidual = std::stod(next());
    else if (k == "--weighted")
      a.Weighted = true;
    else if (k == "--element-metric")
    {
      const std::string v = next();
      if (v != "mean" && v != "edges")
      {
        throw std::runtime_error("--element-metric: expected mean or edges, got " + v);
      }
      a.ElementMetric =
        v == "edges" ? av::EmbeddingElementMetric::EdgeLengths : av::EmbeddingElementMetric::VertexMean;
    }
    else if (k == "--no-track")
      a.TrackError = false;
    else if (k == "--sites")
      a.Sites = static_cast<std::size_t>(std::stoll(next()));
    else if (k == "--sample-iterations")
      a.SampleIterations = std::stoi(next());
    else if (k == "--warmup-iterations")
      a.WarmupIterations = std::stoi(next());
    else if (k == "--kernel-width")
      a.KernelWidth = std::stod(next());
    else if (k == "--lloyd")
      a.Lloyd = std::stoi(next());
    else if (k == "--no-repair")
      a.Repair = false;
    else if (k == "--rvd-repeats")
      a.RvdRepeats = std::stoi(next());
    else if (k == "--no-rvd-geometry")
      a.RvdGeometry = false;
    else if (k == "--rvd-embedded-points")
      a.RvdEmbeddedPoints = true;
    else if (k == "--no-mesh-improvement")
      a.ImproveMesh = false;
    else if (k == "--no-planar-boundary")
      a.PlanarBoundary = false;
    else if (k == "--no-straight-creases")
      a.StraightCreases = false;
    else if (k == "--no-vertex-insertion")
      a.VertexInsertion = false;
    else if (k == "--no-collapses")
      a.Collapses = false;
    else if (k == "--edge-rule-angle")
      a.EdgeRuleAngle = std::stod(next());
    else if (k == "--no-boundary-snap")
      a.BoundarySnap = false;
    else if (k == "--no-input-boundary-moves")
      a.InputBoundaryMoves = false;
    else if (k == "--boundary-flip-dihedral")
      a.BoundaryFlipDihedral = std::stod(next());
    else if (k == "--boundary-volume-budget")
      a.BoundaryVolumeBudget = std::stod(next());
    else if (k == "--repair-rounds")
      a.RepairRounds = std::stoi(next());
    else if (k == "--repair-nonmanifold") // the default
      a.RepairNonManifold = true;
    else if (k == "--no-repair-nonmanifold")
      a.RepairNonManifold = false;
    else if (k == "--no-valid-dual")
      a.ValidDual = false;
    else if (k == "--improve-rounds")
      a.ImproveRounds = std::stoi(next());
    else if (k == "--odt-iterations")
      a.OdtIterations = std::stoi(next());
    else if (k == "--no-sliver-push")
      a.PerturbSlivers = false;
    else if (k == "--no-features")
      a.Features = false;
    else if (k == "--keep-feature-sites")
      a.OdtKeepsFeatures = true;
    else if (k == "--no-feature-edges")
      a.FeatureEdges = false;
    else if (k == "--no-boundary-notches")
      a.BoundaryNotches = false;
    else if (k == "--mean-smoothing")
      a.MeanSmoothing = std::stoi(next());
    else if (k == "--reference-embedding")
      a.Reference = true;
    else if (k == "--max-stretch")
      a.MaxStretch = std::stod(next());
    else if (k == "--feature-angle")
      a.FeatureAngle = std::stod(next());
    else if (k == "--data-dir")
      a.DataDir = next();
    else if (k == "--min-eigenvalue")
      a.RealMetric.MinEigenvalue = std::stod(next());
    else if (k == "--max-anisotropy")
      a.RealMetric.MaxAnisotropy = std::stod(next());
    else if (k == "--smooth")
      a.RealMetric.SmoothingIterations = std::stoi(next());
    else if (k == "--crease-angle")
      a.RealMetric.CreaseAngle = std::stod(next());
    else if (k == "--prepare-metric")
      a.Prepare = true;
    else if (k == "--no-prepare-metric")
      a.NoPrepare = true;
    else if (k == "--hmin" || k == "--hmax" || k == "--hgrad" || k == "--size-blend")
    {
      const double v = std::stod(next());
      av::MetricPreparationOptions& p = a.Preparation;
      (k == "--hmin" ? p.HMin : k == "--hmax" ? p.HMax : k == "--hgrad" ? p.GradationFactor : p.SizeBlend) = v;
      a.Prepare = true;
    }
    else if (k == "--min-cells-across")
    {
      a.Preparation.MinCellsAcross = std::stod(next());
      a.Prepare = true;
    }
    else if (k == "--size-mode")
    {
      const std::string m = next();
      if (m != "tensor" && m != "uniform" && m != "blend")
        throw std::runtime_error("--size-mode must be tensor, uniform or blend");
      a.Preparation.SizeMode = m == "uniform" ? av::MetricSizeMode::Uniform
        : m == "blend"                        ? av::MetricSizeMode::Blend
                                              : av::MetricSizeMode::Tensor;
      a.Prepare = true;
    }
    else if (k == "--no-gradation")
      a.Preparation.Gradation = false;
    else if (k == "--adapt")
      a.Adapt = std::stod(next());
    else if (k == "--no-adapt")
      a.NoAdapt = true;
    else if (!k.empty() && k[0] != '-' && a.CaseName.empty())
      a.CaseName = k;
    else
      throw std::runtime_error("unknown argument '" + k + "'");
  }
  CheckArgs(a);
  return !a.CaseName.empty();
}
/// Builds case `name`, runs `stage` on it and prints its JSON line; false on error (the line
/// then has an "error" key).
bool RunCase(const Args& args, const std::string& name, const StageFn& stage, int threads)
{
  JsonLine out;
  out.Set("case", name);
  out.Set("stage", args.Stage);
  bool ok = true;
  try
  {
    Args a = args;
    a.CaseName = name;
    const Case c = BuildCase(a);
    out.Set("mesh", c.MeshDescription);
    if (c.Real)
    {
      out.Set("file_points", c.FilePoints);
      out.Set("file_cells", c.FileCells);
      if (c.IsSurface)
      {
        out.Set("crease_angle", a.RealMetric.CreaseAngle);
        out.Set("crease_edges", c.CreaseEdges);
      }
    }
    out.Set("input_vertices", c.Mesh.NumPoints());
    out.Set("input_elements", c.Mesh.NumCells());
    std::vector<std::int32_t> body;
    out.Set("input_bodies", av::LabelBodies(c.Mesh, body));
    out.Set("stretch_min", c.StretchMin);
    out.Set("stretch_max", c.StretchMax);
    out.Set("input_mesh_seconds", c.MeshSeconds);
    if (c.BoundaryLayer)
    {
      out.Set("layer_profile", av::BoundaryLayerProfileName(c.Layer.Profile));
      out.Set("layer_stretch", c.Layer.Stretch);
    }
    if (c.Real || c.BoundaryLayer)
    {
      out.Set("input_mean_edge", c.InputResolution.MeanEdgeLength);
      out.Set("input_long_edges", c.InputResolution.LongEdgeFraction);
    }
    out.Set("background_adapted", c.Adapted);
    if (c.Adapted)
    {
      out.Set("adapt_length", a.Adapt > 0.0 ? a.Adapt : av::kAutomaticBackgroundEdgeLength);
      out.Set("background_seconds", c.Background.Seconds);
      out.Set("background_splits", c.Background.NumSplits);
      out.Set("background_collapses", c.Background.NumCollapses);
      out.Set("background_max_edge", c.Background.MaxEdgeLength);
    }
    stage(a, c, out);
    out.Set("threads", threads);
    out.Set("peak_rss_mb", PeakRssMb());
  }
  catch (const std::exception& e)
  {
    out.Set("error", e.what());
    ok = false;
  }
  std::cout << out.Str() << std::endl;
  return ok;
}
} // namespace

int main(int argc, char** argv)
{
  Args args;
  try
  {
    if (!Parse(argc, argv, args))
    {
      Usage(argc < 2 ? std::cerr : std::cout);
      return argc < 2 ? 2 : 0;
    }
  }
  catch (const std::exception& e)
  {
    std::cerr << "anisovoronoi-bench: " << e.what() << "\n";
    Usage(std::cerr);
    return 2;
  }
  const auto stage = Stages().find(args.Stage);
  if (stage == Stages().end())
  {
    std::cerr << "anisovoronoi-bench: unknown stage '" << args.Stage << "'\n";
    return 2;
  }
  const int threads = args.Threads > 0 ? args.Threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));

  std::vector<std::string> cases;
  if (args.CaseName == "all")
  {
    for (av::AnalyticPreset p : av::AllAnalyticPresets())
    {
      cases.push_back(av::AnalyticPresetName(p));
    }
  }
  else if (args.CaseName == "real:all")
  {
    for (const avbench::RealCaseInfo& r : avbench::RealCases())
    {
      cases.push_back("real:" + r.Name);
    }
  }
  else if (args.CaseName == "surfaces")
  {
    cases = avbench::SurfaceCaseNames();
  }
  else if (args.CaseName == "boundary-layers")
  {
    cases = avbench::BoundaryLayerCaseNames();
  }
  else
  {
    cases.push_back(args.CaseName);
  }
  int status = 0;
  for (const std::string& name : cases)
  {
    status = RunCase(args, name, stage->second, threads) ? status : 1;
  }
  return status;
}
