// SPDX-License-Identifier: BSD-3-Clause
// anisovoronoi: command-line front end of the whole pipeline (metric -> embedding -> sites ->
// restricted Voronoi diagram -> dual mesh -> quality), for batch use without a GUI.
// Everything it writes goes into --output-dir; progress goes to stderr; a failure prints one
// line "anisovoronoi: error: ..." and exits with status 1 (2 for bad command lines).
// main: parse (CommandLine), build and run the VTK pipeline stage by stage (StageRunner),
// then write the files and report.json.

#include "AtomicOutput.h"
#include "CapturingOutputWindow.h"
#include "CommandLine.h"
#include "InputReaders.h"
#include "MeditOutput.h"
#include "MetricFieldOps.h"
#include "StageRunner.h"
#include "vtkAnisoAdaptedBackgroundMesh.h"
#include "vtkAnisoAnalyticMetric.h"
#include "vtkAnisoAnalyticMetricSource.h"
#include "vtkAnisoCurvatureMetric.h"
#include "vtkAnisoDataConversion.h"
#include "vtkAnisoEmbedding.h"
#include "vtkAnisoMeshQuality.h"
#include "vtkAnisoParticleSampler.h"
#include "vtkAnisoRestrictedDelaunay.h"
#include "vtkAnisoRestrictedVoronoi.h"
#include "vtkAnisoSimplexMesh.h"
#include "vtkAnisoTensorToMetric.h"
#include "vtkAnisoTetMesher.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDataObject.h>
#include <vtkDataSet.h>
#include <vtkDataSetSurfaceFilter.h>
#include <vtkFieldData.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkProbeFilter.h>
#include <vtkSmartPointer.h>
#include <vtkStaticPointLocator.h>
#include <vtkTable.h>
#include <vtkTriangleFilter.h>
#include <vtkTrivialProducer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>
#include <vtksys/SystemTools.hxx>

#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace
{
using avcli::Fail;
using avcli::Options;
using avcli::StageRunner;

/// The algorithms of the run, from the input to the quality of the dual mesh.
struct MeshingStages
{
  vtkSmartPointer<vtkAlgorithm> Source; ///< the reader, or the preset's own mesh
  vtkNew<vtkAnisoSimplexMesh> Simplices;
  vtkSmartPointer<vtkAlgorithm> Domain; ///< Simplices, or the finer mesh of --refine
  vtkSmartPointer<vtkAlgorithm> Metric; ///< Domain itself when it carries the metric
  vtkNew<vtkAnisoEmbedding> Embedding;
  vtkNew<vtkAnisoParticleSampler> Sampler;
  vtkNew<vtkAnisoRestrictedDelaunay> Delaunay;
  vtkNew<vtkAnisoRestrictedVoronoi> Voronoi;
  vtkNew<vtkAnisoMeshQuality> Quality;
};

// Stage names: progress lines, and the keys of their seconds in the report.
const char* const VoronoiStage = "restricted Voronoi diagram";
const char* const DelaunayStage = "restricted Delaunay mesh";
const char* const BackgroundStage = "adapt the background mesh";
std::string SamplingStage(const Options& o)
{
  return "sampling " + std::to_string(o.Sites) + " sites";
}
std::string EmbeddingStage(const Options& o)
{
  return "embedding in " + std::to_string(o.Dim) + "D";
}

bool IsPreset(const Options& o)
{
  return o.Metric.rfind("preset:", 0) == 0;
}

double FieldValue(vtkDataObject* data, const char* name, double fallback = NAN)
{
  if (!data || !data->GetFieldData())
    return fallback;
  vtkDataArray* a = data->GetFieldData()->GetArray(name);
  return a && a->GetNumberOfTuples() > 0 ? a->GetTuple1(0) : fallback;
}

std::string JsonNumber(double v)
{
  if (!std::isfinite(v))
    return "null";
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

void WriteXML(const avcli::AtomicOutput& output, vtkDataObject* data, const std::string& path)
{
  output.Write(path,
    [data](const std::string& temporary)
    {
      vtkSmartPointer<vtkXMLWriter> writer;
      if (vtkPolyData::SafeDownCast(data))
        writer = vtkSmartPointer<vtkXMLPolyDataWriter>::New();
      else
        writer = vtkSmartPointer<vtkXMLUnstructuredGridWriter>::New();
      writer->SetInputData(data);
      writer->SetFileName(temporary.c_str());
      writer->SetDataModeToBinary(); // appended mode does not read back with this VTK/expat
      return writer->Write() != 0;
    });
}

/// 1. The input mesh: read, or the preset's own mesh.
void RunSource(const Options& o, MeshingStages& s, StageRunner& runner)
{
  if (!o.Input.empty())
  {
    s.Source = avcli::MakeReader(o);
    runner.Run(s.Source, "read " + vtksys::SystemTools::GetFilenameName(o.Input));
    return;
  }
  const std::string presetName = o.Metric.substr(7);
  auto source = vtkSmartPointer<vtkAnisoAnalyticMetricSource>::New();
  if (!source->SetPresetByName(presetName.c_str()))
    Fail("unknown preset '" + presetName + "' (gaussian2d cube1 cube2 cube3 sphere-cyl sphere-cos)",
      2);
  if (o.Resolution != 0 && o.Resolution < 3)
    Fail("--resolution must be 0 or >= 3", 2);
  source->SetResolution(o.Resolution);
  s.Source = source;
  runner.Run(s.Source, "mesh " + presetName);
}

/// Points of `refined` that the probe missed (round-off on the boundary) take the point data
/// of the nearest point of `coarse`; returns how many.
vtkIdType FillMissedPoints(vtkUnstructuredGrid* refined, vtkDataSet* coarse, vtkDataArray* mask)
{
  vtkNew<vtkStaticPointLocator> locator;
  locator->SetDataSet(coarse);
  locator->BuildLocator();
  vtkIdType fixedPoints = 0;
  for (vtkIdType i = 0; mask && i < refined->GetNumberOfPoints(); ++i)
  {
    if (mask->GetTuple1(i) > 0.5)
      continue;
    const vtkIdType nearest = locator->FindClosestPoint(refined->GetPoint(i));
    for (int a = 0; a < refined->GetPointData()->GetNumberOfArrays(); ++a)
    {
      vtkDataArray* target = refined->GetPointData()->GetArray(a);
      vtkDataArray* from = target ? coarse->GetPointData()->GetArray(target->GetName()) : nullptr;
      if (from && from->GetNumberOfComponents() == target->GetNumberOfComponents())
        target->SetTuple(i, from->GetTuple(nearest));
    }
    ++fixedPoints;
  }
  return fixedPoints;
}

/// 2b. --refine: TetGen on the boundary surface of the simplices, their point data probed onto
/// the new mesh; returns its producer.
vtkSmartPointer<vtkAlgorithm> RunRefinement(const Options& o,
  vtkAnisoSimplexMesh* simplices,
  StageRunner& runner)
{
  vtkDataSet* coarse = vtkDataSet::SafeDownCast(simplices->GetOutputDataObject(0));
  if (!coarse || coarse->GetNumberOfCells() == 0 || coarse->GetCellType(0) != VTK_TETRA)
    Fail("--refine applies to volume (tetrahedral) inputs only", 2);
  vtkNew<vtkDataSetSurfaceFilter> boundary;
  vtkNew<vtkTriangleFilter> boundaryTriangles;
  vtkNew<vtkAnisoTetMesher> remesher;
  vtkNew<vtkProbeFilter> probe;
  boundary->SetInputConnection(simplices->GetOutputPort());
  boundaryTriangles->SetInputConnection(boundary->GetOutputPort());
  remesher->SetInputConnection(boundaryTriangles->GetOutputPort());
  remesher->SetShapeToInputSurface();
  remesher->SetTargetVertices(o.Refine);
  runner.Run(remesher, "remesh with TetGen (" + std::to_string(o.Refine) + " vertices)");
  probe->SetInputConnection(remesher->GetOutputPort());
  probe->SetSourceConnection(simplices->GetOutputPort());
  probe->PassPointArraysOff();
  runner.Run(probe, "interpolate point data onto the new mesh");
  vtkNew<vtkUnstructuredGrid> refined;
  refined->DeepCopy(probe->GetOutputDataObject(0));
  vtkDataArray* mask = refined->GetPointData()->GetArray(probe->GetValidPointMaskArrayName());
  const vtkIdType fixedPoints = FillMissedPoints(refined, coarse, mask);
  if (!o.Quiet && fixedPoints > 0)
    std::cerr << "[anisovoronoi] " << fixedPoints
              << " boundary point(s) took the nearest input point's data" << std::endl;
  auto producer = vtkSmartPointer<vtkTrivialProducer>::New();
  producer->SetOutput(refined);
  return producer;
}

/// The metric preparation of --hmin, --hmax, --hgrad, --size-mode, --no-gradation on `m`.
void SetPreparation(const Options& o, vtkAnisoTensorToMetric* m)
{
  m->SetSizeMode(o.SizeMode == "uniform" ? vtkAnisoTensorToMetric::SIZE_UNIFORM
      : o.SizeMode == "blend"            ? vtkAnisoTensorToMetric::SIZE_BLEND
                                         : vtkAnisoTensorToMetric::SIZE_FROM_TENSOR);
  m->SetSizeBlend(o.SizeBlend);
  m->SetNumberOfSites(o.Sites);
  m->SetHMin(o.HMin);
  m->SetHMax(o.HMax);
  m->SetMinCellsAcross(o.MinCellsAcross);
  m->SetGradation(o.Gradation);
  m->SetGradationFactor(o.HGrad);
}

/// metric:, preset: or --sol with a preparation option: the point metric `array` of
/// `upstream`, prepared (read as a metric: no floor, no cap); its output array is "Metric".
vtkSmartPointer<vtkAlgorithm> MakeMetricPreparation(
  const Options& o, vtkAlgorithm* upstream, const std::string& array)
{
  auto m = vtkSmartPointer<vtkAnisoTensorToMetric>::New();
  m->SetInputConnection(upstream->GetOutputPort());
  m->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, array.c_str());
  m->SetInterpretationToTensorAsMetric();
  m->SetMinimumEigenvalue(1e-15);
  m->SetMaximumAnisotropy(0.0);
  SetPreparation(o, m);
  return m;
}

/// A .sol carries absolute sizes (MMG / Feflo.a): without --sites, as many sites as its
/// complexity holds unit vertices, N = (integral of sqrt(det M)) / v_unit, as MMG does.
int SitesFromMetric(vtkAlgorithm* domain, const std::string& array)
{
  vtkDataSet* ds = vtkDataSet::SafeDownCast(domain->GetOutputDataObject(0));
  av::SimplexMesh mesh;
  av::MetricField metric;
  std::string error;
  if (!ds || !vtkAnisoDataConversion::ToSimplexMesh(ds, mesh, error) ||
    !vtkAnisoDataConversion::ToMetricField(
      ds->GetPointData()->GetArray(array.c_str()), mesh.NumPoints(), metric, error))
    Fail("cannot count the sites of the .sol metric: " + error);
  const double n = av::MetricComplexity(mesh, metric) / av::UnitVertexMeasure(mesh.SimplexDim);
  if (!(n >= 1.0 && n < 1e8))
    Fail("the .sol metric asks for " + std::to_string(n) +
      " vertices (complexity / unit vertex measure): give --sites N");
  return static_cast<int>(std::lround(n));
}

/// tensor:ARRAY: the metric of a tensor point or cell array of `domain`.
vtkSmartPointer<vtkAlgorithm> MakeTensorMetric(const Options& o, vtkAlgorithm* domain)
{
  auto m = vtkSmartPointer<vtkAnisoTensorToMetric>::New();
  m->SetInputConnection(domain->GetOutputPort());
  const std::string array = o.Metric.substr(7);
  vtkDataSet* ds = vtkDataSet::SafeDownCast(domain->GetOutputDataObject(0));
  const bool onCells = ds && !ds->GetPointData()->GetArray(array.c_str()) &&
    ds->GetCellData()->GetArray(array.c_str());
  if (ds && !ds->GetPointData()->GetArray(array.c_str()) && !onCells)
    Fail("the input has no point or cell array named '" + array + "'");
  m->SetInputArrayToProcess(0,
    0,
    0,
    onCells ? vtkDataObject::FIELD_ASSOCIATION_CELLS : vtkDataObject::FIELD_ASSOCIATION_POINTS,
    array.c_str());
  m->SetInterpretation(o.TensorAsMetric ? vtkAnisoTensorToMetric::TENSOR_AS_METRIC
                                        : vtkAnisoTensorToMetric::EIGENVALUES_AS_STRETCH);
  m->SetEigenvalueMode(o.Clamp ? vtkAnisoTensorToMetric::CLAMP : vtkAnisoTensorToMetric::ABSOLUTE);
  m->SetMinimumEigenvalue(o.MinEigenvalue);
  m->SetMaximumAnisotropy(o.MaxAnisotropy);
  m->SetSmoothingIterations(o.Smooth);
  SetPreparation(o, m);
  return m;
}

/// 3. The metric of the domain (the domain itself when it already carries it); returns the
/// name of its point array.
std::string RunMetric(Options& o, MeshingStages& s, StageRunner& runner)
{
  std::string metricName = "Metric";
  if (!o.Sol.empty() && !o.SitesGiven && o.Metric.rfind("metric:", 0) == 0)
  {
    o.Sites = SitesFromMetric(s.Domain, o.Metric.substr(7));
    if (!o.Quiet)
      std::cerr << "[anisovoronoi] " << o.Sites << " sites from the .sol metric's complexity"
                << std::endl;
  }
  if (IsPreset(o) && !o.Input.empty())
  {
    const std::string presetName = o.Metric.substr(7);
    auto m = vtkSmartPointer<vtkAnisoAnalyticMetric>::New();
    if (!m->SetPresetByName(presetName.c_str()))
      Fail("unknown preset '" + presetName + "'", 2);
    m->SetInputConnection(s.Domain->GetOutputPort());
    s.Metric = m;
  }
  else if (IsPreset(o))
    s.Metric = s.Domain; // the source already carries the preset's metric
  else if (o.Metric.rfind("tensor:", 0) == 0)
    s.Metric = MakeTensorMetric(o, s.Domain);
  else if (o.Metric.rfind("metric:", 0) == 0)
  {
    s.Metric = s.Domain;
    metricName = o.Metric.substr(7);
  }
  else if (o.Metric == "curvature")
  {
    auto m = vtkSmartPointer<vtkAnisoCurvatureMetric>::New();
    m->SetInputConnection(s.Domain->GetOutputPort());
    m->SetMaxStretch(o.MaxStretch);
    s.Metric = m;
  }
  else
    Fail("unknown metric SPEC '" + o.Metric +
        "' (tensor:ARRAY, metric:ARRAY, curvature or preset:NAME)",
      2);
  if (s.Metric != s.Domain)
    runner.Run(s.Metric, "metric (" + o.Metric + ")");
  // Presets and metric inputs keep their metric unless a preparation option asks otherwise.
  if (o.PrepareAsked && o.Metric.rfind("tensor:", 0) != 0)
  {
    s.Metric = MakeMetricPreparation(o, s.Metric, metricName);
    runner.Run(s.Metric, "metric preparation");
    metricName = "Metric";
  }
  return metricName;
}

/// 1. to 3.: the input, split into simplices, optionally refined, with its metric.
std::string RunInputStages(Options& o, MeshingStages& s, StageRunner& runner)
{
  RunSource(o, s, runner);
  // 2. Simplices (hexahedra, quadratic cells, ... are split).
  s.Simplices->SetInputConnection(s.Source->GetOutputPort());
  runner.Run(s.Simplices, "split into simplices");
  s.Domain = s.Simplices.GetPointer();
  if (o.Refine > 0)
    s.Domain = RunRefinement(o, s.Simplices, runner);
  const std::string metricName = RunMetric(o, s, runner);
  const bool tensorField = o.Metric.rfind("tensor:", 0) == 0;
  if (o.Adapt == "always" || (o.Adapt == "auto" && tensorField))
  {
    // 3b. --adapt: the mesh the embedding runs on follows the metric and the sites.
    auto adapted = vtkSmartPointer<vtkAnisoAdaptedBackgroundMesh>::New();
    adapted->SetInputConnection(s.Metric->GetOutputPort());
    adapted->SetInputArrayToProcess(
      0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, metricName.c_str());
    adapted->SetNumberOfSites(o.Sites);
    adapted->SetTargetEdgeLength(o.AdaptLength);
    adapted->SetOnlyWhenCoarse(o.Adapt == "auto");
    adapted->SetFeatureAngle(o.FeatureAngle);
    runner.Run(adapted, BackgroundStage);
    if (!o.Quiet)
      std::cerr << "[anisovoronoi] background mesh: mean edge "
                << adapted->GetInputMeanEdgeLength() << " output edges for " << o.Sites
                << " sites: "
                << (adapted->GetAdapted() ? "adapted" : "fine enough, kept (--adapt forces it)")
                << std::endl;
    s.Metric = adapted;
  }
  return metricName;
}

/// 4. to 6.: embedding, sites, the dual mesh (with the repair's inserted sites), then the
/// restricted Voronoi diagram of its vertices = the final sites (shrunken cells for display)
/// and the quality of the dual mesh.
void RunMeshingStages(const Options& o,
  const std::string& metricName,
  MeshingStages& s,
  StageRunner& runner)
{
  s.Embedding->SetInputConnection(s.Metric->GetOutputPort());
  s.Embedding->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, metricName.c_str());
  s.Embedding->SetTargetDimension(o.Dim);
  s.Embedding->SetIterations(o.Iterations);
  s.Embedding->SetMaxIterations(o.MaxIterations);
  s.Embedding->SetGlobalSolver(o.Solver == "direct" ? vtkAnisoEmbedding::DIRECT_SOLVER
      : o.Solver == "iterative"                    ? vtkAnisoEmbedding::ITERATIVE_SOLVER
                                                   : vtkAnisoEmbedding::AUTOMATIC_SOLVER);
  s.Embedding->SetSinglePrecisionSolve(!o.DoubleSolve);
  s.Embedding->SetElementMetric(o.ElementMetric == "edges" ? vtkAnisoEmbedding::EDGE_LENGTHS
                                                           : vtkAnisoEmbedding::VERTEX_MEAN);
  s.Embedding->SetSeparateBodies(o.SeparateBodies);
  s.Embedding->SetMu(o.Mu);
  s.Embedding->SetScaleFreeRegularizer(o.ScaleFreeRegularizer);
  s.Embedding->SetSeed(o.Seed);
  runner.Run(s.Embedding, EmbeddingStage(o));

  s.Sampler->SetInputConnection(s.Embedding->GetOutputPort(0));
  s.Sampler->SetNumberOfSites(o.Sites);
  s.Sampler->SetIterations(o.SampleIterations);
  s.Sampler->SetWarmupIterations(o.WarmupIterations);
  s.Sampler->SetPreserveSharpFeatures(o.Features);
  s.Sampler->SetFeatureAngle(o.FeatureAngle);
  s.Sampler->SetFeaturePatchArray(o.FeaturePatches.empty() ? nullptr : o.FeaturePatches.c_str());
  s.Sampler->SetFeatureCornerArray(o.FeatureCorners.empty() ? nullptr : o.FeatureCorners.c_str());
  s.Sampler->SetSeed(o.Seed);
  runner.Run(s.Sampler, SamplingStage(o));

  s.Delaunay->SetInputConnection(0, s.Embedding->GetOutputPort(0));
  s.Delaunay->SetInputConnection(1, s.Sampler->GetOutputPort(0));
  s.Delaunay->SetRepairInverted(o.Repair);
  s.Delaunay->SetMaxRepairRounds(o.RepairRounds);
  s.Delaunay->SetImprovementRounds(o.ImproveRounds);
  s.Delaunay->SetOdtIterations(o.OdtIterations);
  s.Delaunay->SetRepairNonManifold(o.RepairNonManifold);
  s.Delaunay->SetValidDual(o.ValidDual);
  s.Delaunay->SetImproveMesh(o.ImproveMesh);
  s.Delaunay->SetImproveBoundary(o.ImproveBoundary);
  s.Delaunay->SetMeanSmoothingSweeps(o.MeanSmoothingSweeps);
  s.Delaunay->SetKeepFeatureSites(o.KeepFeatureSites);
  s.Delaunay->SetCloseBoundaryNotches(o.CloseBoundaryNotches);
  runner.Run(s.Delaunay, DelaunayStage);
  s.Voronoi->SetInputConnection(0, s.Embedding->GetOutputPort(0));
  s.Voronoi->SetInputConnection(1, s.Delaunay->GetOutputPort(0));
  s.Voronoi->SetShrinkFactor(o.Shrink);
  runner.Run(s.Voronoi, VoronoiStage);
  s.Quality->SetInputConnection(s.Delaunay->GetOutputPort(0));
  // Surfaces: Hausdorff distance and flipped triangles against the input surface itself.
  if (vtkAnisoDataConversion::IsSurfaceInThreeD(
        vtkDataSet::SafeDownCast(s.Simplices->GetOutputDataObject(0))))
    s.Quality->SetInputConnection(1, s.Simplices->GetOutputPort(0));
  runner.Run(s.Quality, "mesh quality");
}

/// 7. The data files and energy.csv.
void WriteFiles(const avcli::AtomicOutput& output, const std::string& dir, MeshingStages& s)
{
  WriteXML(output, s.Embedding->GetOutputDataObject(0), dir + "embedded.vtu");
  WriteXML(output, s.Sampler->GetOutputDataObject(0), dir + "sites.vtp");
  WriteXML(output, s.Voronoi->GetOutputDataObject(0), dir + "voronoi.vtu");
  WriteXML(output, s.Voronoi->GetOutputDataObject(1), dir + "voronoi_faces.vtp");
  WriteXML(output, s.Quality->GetOutputDataObject(0), dir + "mesh.vtu");
  if (auto* energy = vtkTable::SafeDownCast(s.Embedding->GetOutputDataObject(1)))
  {
    output.Write(dir + "energy.csv",
      [energy](const std::string& temporary)
      {
        std::ofstream csv(temporary);
        csv << "iteration,E_em,E_reg,E_total\n";
        csv.precision(12);
        for (vtkIdType r = 0; r < energy->GetNumberOfRows(); ++r)
          csv << r << "," << energy->GetValueByName(r, "E_em").ToDouble() << ","
              << energy->GetValueByName(r, "E_reg").ToDouble() << ","
              << energy->GetValueByName(r, "E_total").ToDouble() << "\n";
        csv.close();
        return !csv.fail();
      });
  }
}

std::size_t NumberOfCells(vtkDataObject* data)
{
  vtkDataSet* ds = vtkDataSet::SafeDownCast(data);
  return ds ? static_cast<std::size_t>(ds->GetNumberOfCells()) : 0;
}

/// The keys of report.json (the benchmark's), in order, as JSON values.
std::vector<std::pair<std::string, std::string>> ReportEntries(const Options& o,
  MeshingStages& s,
  const StageRunner& runner)
{
  vtkDataObject* embedded = s.Embedding->GetOutputDataObject(0);
  vtkDataSet* meshIn = vtkDataSet::SafeDownCast(embedded);
  vtkDataObject* sitesOut = s.Sampler->GetOutputDataObject(0);
  vtkDataObject* qualityOut = s.Quality->GetOutputDataObject(0);
  vtkDataObject* rvdOut = s.Voronoi->GetOutputDataObject(0);
  vtkDataObject* rdtOut = s.Delaunay->GetOutputDataObject(0);
  double stretchRange[2] = { NAN, NAN };
  if (meshIn && meshIn->GetPointData()->GetArray("Stretch"))
    meshIn->GetPointData()->GetArray("Stretch")->GetRange(stretchRange);
  const double repairSeconds = FieldValue(rdtOut, "RepairSeconds");
  const double meshSeconds = runner.SecondsOf(SamplingStage(o)) + runner.SecondsOf(VoronoiStage) +
    runner.SecondsOf(DelaunayStage);
  std::vector<std::pair<std::string, std::string>> report = {
    { "input", "\"" + (o.Input.empty() ? o.Metric : o.Input) + "\"" },
    { "metric", "\"" + o.Metric + "\"" },
    { "input_vertices", std::to_string(meshIn ? meshIn->GetNumberOfPoints() : 0) },
    { "input_elements", std::to_string(meshIn ? meshIn->GetNumberOfCells() : 0) },
    { "adapt_length", JsonNumber(o.AdaptLength) },
    { "background_input_vertices", JsonNumber(FieldValue(embedded, "BackgroundInputPoints")) },
    { "background_seconds", JsonNumber(runner.SecondsOf(BackgroundStage)) },
    { "background_adapted", FieldValue(embedded, "BackgroundAdapted") > 0.0 ? "true" : "false" },
    { "background_input_mean_edge",
      JsonNumber(FieldValue(embedded, "BackgroundInputMeanEdgeLength")) },
    { "dim", std::to_string(o.Dim) },
    { "iterations", std::to_string(o.Iterations) },
    { "embedding_iterations", JsonNumber(FieldValue(embedded, "EmbeddingIterations")) },
    { "embedding_converged", FieldValue(embedded, "EmbeddingConverged") > 0.0 ? "true" : "false" },
    { "iterative_solve", FieldValue(embedded, "IterativeSolve") > 0.0 ? "true" : "false" },
    { "switched_to_direct", FieldValue(embedded, "SwitchedToDirect") > 0.0 ? "true" : "false" },
    { "aligned_start", FieldValue(embedded, "AlignedStart") > 0.0 ? "true" : "false" },
    { "aligned_start_residual", JsonNumber(FieldValue(embedded, "AlignedStartResidual")) },
    { "cells_above_error_threshold", JsonNumber(FieldValue(embedded, "CellsAboveErrorThreshold")) },
    { "input_bodies", JsonNumber(FieldValue(embedded, "InputBodies")) },
    { "metric_scale", JsonNumber(FieldValue(embedded, "MetricScale")) },
    { "stretch_min", JsonNumber(stretchRange[0]) },
    { "stretch_max", JsonNumber(stretchRange[1]) },
    { "L_avg", JsonNumber(FieldValue(embedded, "L_avg")) },
    { "L_max", JsonNumber(FieldValue(embedded, "L_max")) },
    { "L_avg_raw", JsonNumber(FieldValue(embedded, "L_avg_raw")) },
    { "L_max_raw", JsonNumber(FieldValue(embedded, "L_max_raw")) },
    { "metric_prep_median_change", JsonNumber(FieldValue(embedded, "MetricPrepMedianChange")) },
    { "metric_prep_p95_change", JsonNumber(FieldValue(embedded, "MetricPrepP95Change")) },
    { "metric_prep_max_change", JsonNumber(FieldValue(embedded, "MetricPrepMaxChange")) },
    { "metric_prep_changed_fraction",
      JsonNumber(FieldValue(embedded, "MetricPrepChangedFraction")) },
    { "metric_prep_graded_vertices", JsonNumber(FieldValue(embedded, "NumGraded")) },
    { "metric_implied_sites", JsonNumber(FieldValue(embedded, "ImpliedSites")) },
    { "embed_seconds", JsonNumber(runner.SecondsOf(EmbeddingStage(o))) },
    { "factor_seconds", JsonNumber(FieldValue(embedded, "FactorSeconds")) },
    { "sites", std::to_string(o.Sites) },
    { "sample_iterations", std::to_string(o.SampleIterations) },
    { "warmup_iterations", std::to_string(o.WarmupIterations) },
    { "corner_sites", JsonNumber(FieldValue(sitesOut, "NumCornerSites")) },
    { "feature_line_sites", JsonNumber(FieldValue(sitesOut, "NumFeatureLineSites")) },
    { "coincident_sites_removed", JsonNumber(FieldValue(sitesOut, "NumCoincidentRemoved")) },
    { "sample_seconds", JsonNumber(runner.SecondsOf(SamplingStage(o))) },
    { "rvd_seconds", JsonNumber(runner.SecondsOf(VoronoiStage)) },
    { "rdt_seconds", JsonNumber(runner.SecondsOf(DelaunayStage) - repairSeconds) },
    { "repair", o.Repair ? "true" : "false" },
    { "repair_seconds", JsonNumber(repairSeconds) },
    { "repair_rounds", JsonNumber(FieldValue(rdtOut, "RepairRounds")) },
    { "inserted_sites", JsonNumber(FieldValue(rdtOut, "NumInsertedSites")) },
    { "repair_stalled", FieldValue(rdtOut, "RepairStalled") > 0.0 ? "true" : "false" },
    { "slivers_perturbed", JsonNumber(FieldValue(rdtOut, "NumSliversPerturbed")) },
    { "moved_sites", JsonNumber(FieldValue(rdtOut, "NumMovedSites")) },
    { "odt_moved_sites", JsonNumber(FieldValue(rdtOut, "NumOdtMovedSites")) },
    { "rdt_inverted_before_repair", JsonNumber(FieldValue(rdtOut, "NumInvertedBeforeRepair")) },
    { "rdt_inverted", JsonNumber(FieldValue(rdtOut, "NumInverted")) },
    { "valid_dual_replaced", FieldValue(rdtOut, "ValidDualReplaced") > 0.0 ? "true" : "false" },
    { "mesh_improvement", o.ImproveMesh ? "true" : "false" },
    { "mesh_improvement_seconds", JsonNumber(FieldValue(rdtOut, "MeshImprovementSeconds")) },
    { "mesh_improvement_flips", JsonNumber(FieldValue(rdtOut, "NumImprovementFlips")) },
    { "mesh_improvement_moves", JsonNumber(FieldValue(rdtOut, "NumImprovementMoves")) },
    { "mean_smoothing_sweeps", JsonNumber(o.MeanSmoothingSweeps) },
    { "mesh_improvement_mean_moves", JsonNumber(FieldValue(rdtOut, "NumImprovementMeanMoves")) },
    { "mesh_improvement_insertions", JsonNumber(FieldValue(rdtOut, "NumImprovementInsertions")) },
    { "mesh_improvement_collapses", JsonNumber(FieldValue(rdtOut, "NumImprovementCollapses")) },
    { "mesh_improvement_boundary_snaps", JsonNumber(FieldValue(rdtOut, "NumImprovementBoundarySnaps")) },
    { "feature_edges_required", JsonNumber(FieldValue(rdtOut, "NumFeatureEdgesRequired")) },
    { "feature_edges_recovered", JsonNumber(FieldValue(rdtOut, "NumFeatureEdgesRecovered")) },
    { "feature_edges_missing", JsonNumber(FieldValue(rdtOut, "NumFeatureEdgesMissing")) },
    { "boundary_notches", JsonNumber(FieldValue(rdtOut, "NumBoundaryNotches")) },
    { "boundary_notches_closed", JsonNumber(FieldValue(rdtOut, "NumBoundaryNotchesClosed")) },
    { "boundary_notches_left", JsonNumber(FieldValue(rdtOut, "NumBoundaryNotchesLeft")) },
    { "inverted_before_mesh_improvement",
      JsonNumber(FieldValue(rdtOut, "NumInvertedBeforeMeshImprovement")) },
    { "mesh_seconds", JsonNumber(meshSeconds) },
    { "voronoi_cells", std::to_string(NumberOfCells(rvdOut)) },
    { "rvd_volume_error", JsonNumber(FieldValue(rvdOut, "RelativeVolumeError")) },
    { "mesh_elements", std::to_string(NumberOfCells(qualityOut)) },
    { "G_min", JsonNumber(FieldValue(qualityOut, "G_min")) },
    { "G_avg", JsonNumber(FieldValue(qualityOut, "G_avg")) },
    { "theta_min", JsonNumber(FieldValue(qualityOut, "theta_min")) },
    { "theta_avg", JsonNumber(FieldValue(qualityOut, "theta_avg")) },
    { "pct_bad", JsonNumber(FieldValue(qualityOut, "pct_bad")) },
    { "inverted", JsonNumber(FieldValue(qualityOut, "inverted")) },
    { "edges_in_unit_range", JsonNumber(FieldValue(qualityOut, "edges_in_unit_range")) },
    { "nonmanifold_faces", JsonNumber(FieldValue(rdtOut, "NumNonManifoldFaces")) },
    { "nonmanifold_faces_before_repair",
      JsonNumber(FieldValue(rdtOut, "NumNonManifoldFacesBeforeRepair")) },
  };
  // Surfaces (null otherwise): fidelity to the input surface, paper §6.3.
  static const char* const surfaceKeys[] = { "hausdorff",
    "hausdorff_to_input",
    "hausdorff_from_input",
    "self_intersections",
    "flipped",
    "euler",
    "input_euler",
    "boundary_loops",
    "input_boundary_loops",
    "nonmanifold_edges" };
  for (const char* key : surfaceKeys)
    report.emplace_back(key, JsonNumber(FieldValue(qualityOut, key)));
  return report;
}

/// 7. report.json.
void WriteReport(const avcli::AtomicOutput& output,
  const std::string& dir,
  const Options& o,
  MeshingStages& s,
  const StageRunner& runner)
{
  const std::vector<std::pair<std::string, std::string>> report = ReportEntries(o, s, runner);
  output.Write(dir + "report.json",
    [&report](const std::string& temporary)
    {
      std::ofstream json(temporary);
      json << "{\n";
      for (std::size_t k = 0; k < report.size(); ++k)
        json << "  \"" << report[k].first << "\": " << report[k].second
             << (k + 1 < report.size() ? ",\n" : "\n");
      json << "}\n";
      json.close();
      return !json.fail();
    });
}

// The files a run writes into --output-dir (checked against the inputs before the run).
const char* const OutputNames[] = { "embedded.vtu", "sites.vtp", "voronoi.vtu",
  "voronoi_faces.vtp", "mesh.vtu", "energy.csv", "report.json" };
} // namespace

int main(int argc, char* argv[])
{
  // VTK's own error output is replaced by our one-line messages.
  // VTK 9 also logs errors to stderr through loguru: silence it, we print one line.
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  vtkNew<avcli::CapturingOutputWindow> window;
  vtkOutputWindow::SetInstance(window);
  Options o = avcli::ParseCommandLine(argc, argv); // --sites may come from a .sol
  window->ShowWarnings = !o.Quiet;
  if (!o.OutputDir.empty() && !vtksys::SystemTools::MakeDirectory(o.OutputDir))
    Fail("cannot create the output directory '" + o.OutputDir + "'");
  const std::string dir = o.OutputDir + "/";
  const avcli::AtomicOutput output({ o.Input, o.Sol });
  // Before minutes of work, not after.
  if (!o.OutputDir.empty())
    for (const char* name : OutputNames)
      output.RefuseInput(dir + name);
  if (!o.MeditOutput.empty())
  {
    output.RefuseInput(o.MeditOutput);
    output.RefuseInput(avcli::SolPathFor(o.MeditOutput));
  }
  StageRunner runner(o.Quiet);
  MeshingStages stages;
  const std::string metricName = RunInputStages(o, stages, runner);
  RunMeshingStages(o, metricName, stages, runner);
  if (!o.MeditOutput.empty())
  {
    avcli::WriteMeditOutput(output, stages.Quality->GetOutputDataObject(0), o.MeditOutput);
    if (!o.Quiet)
      std::cerr << "[anisovoronoi] wrote " << o.MeditOutput << " and "
                << avcli::SolPathFor(o.MeditOutput) << std::endl;
  }
  if (o.OutputDir.empty())
    return 0;
  WriteFiles(output, dir, stages);
  WriteReport(output, dir, o, stages, runner);
  if (o.FormatMedit)
    avcli::WriteMeditOutput(output, stages.Quality->GetOutputDataObject(0), dir + "mesh.mesh");
  if (!o.Quiet)
    std::cerr << "[anisovoronoi] wrote embedded.vtu sites.vtp voronoi.vtu voronoi_faces.vtp "
                 "mesh.vtu energy.csv report.json"
              << (o.FormatMedit ? " mesh.mesh mesh.sol" : "") << " to " << o.OutputDir << std::endl;
  return 0;
}
