// anisovoronoi: command-line front end of the whole pipeline (metric -> embedding -> sites ->
// restricted Voronoi diagram -> dual mesh -> quality), for batch use without a GUI.
// Everything it writes goes into --output-dir; progress goes to stderr; a failure prints one
// line "anisovoronoi: error: ..." and exits with status 1 (2 for bad command lines).

#include "vtkAnisoAnalyticMetric.h"
#include "vtkAnisoAnalyticMetricSource.h"
#include "vtkAnisoCurvatureMetric.h"
#include "vtkAnisoEmbedding.h"
#include "vtkAnisoFRDReader.h"
#include "vtkAnisoMeditReader.h"
#include "vtkAnisoMeshQuality.h"
#include "vtkAnisoParticleSampler.h"
#include "vtkAnisoRestrictedDelaunay.h"
#include "vtkAnisoRestrictedVoronoi.h"
#include "vtkAnisoSimplexMesh.h"
#include "OffReader.h"
#include "vtkAnisoTensorToMetric.h"
#include "vtkAnisoTetMesher.h"

#include <vtkAlgorithmOutput.h>
#include <vtkCallbackCommand.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkDataObject.h>
#include <vtkDataSet.h>
#include <vtkDataSetReader.h>
#include <vtkDataSetSurfaceFilter.h>
#include <vtkCellArray.h>
#include <vtkExecutive.h>
#include <vtkPoints.h>
#include <vtkProbeFilter.h>
#include <vtkStaticPointLocator.h>
#include <vtkTrivialProducer.h>
#include <vtkFieldData.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkOBJReader.h>
#include <vtkOutputWindow.h>
#include <vtkPLYReader.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSTLReader.h>
#include <vtkSmartPointer.h>
#include <vtkTable.h>
#include <vtkTriangleFilter.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLGenericDataObjectReader.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>
#include <vtksys/SystemTools.hxx>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace
{
const char* const Usage = R"(usage: anisovoronoi [INPUT] --metric SPEC --output-dir DIR [options]

Anisotropic Voronoi cells and meshes from a Riemannian metric through a high-dimensional
embedding (AnisoVoronoi). INPUT: VTK legacy (.vtk) or XML (.vtu/.vtp/...), Medit .mesh
(metric from --sol), CalculiX .frd, or a surface (.stl/.ply/.obj/.off). Non-simplex cells
(hexahedra, quadratic cells, ...) are split into simplices. INPUT may be omitted with
--metric preset:NAME: the preset's own mesh is generated.

metric SPEC:
  tensor:ARRAY     convert a tensor point/cell array (stress, strain rate, ...) into a metric
  metric:ARRAY     ARRAY already is an SPD metric (6 or 9 components)
  curvature        curvature metric of a triangle surface (paper Eq. 19)
  preset:NAME      analytic metric: gaussian2d cube1 cube2 cube3 sphere-cyl sphere-cos

options:
  --sol FILE               Medit .sol metric for a .mesh input
  --step N                 result step of a .frd input (0-based, default 0)
  --resolution N           mesh size for preset:NAME without INPUT (0 = paper size)
  --sites N                number of Voronoi cells / mesh vertices (default 2000)
  --dim N                  embedding dimension (default 8)
  --iterations N           embedding iterations (default 50)
  --double-solve           embedding: CHOLMOD's double-precision solves (default: float copy)
  --sample-iterations N    particle L-BFGS iterations at the paper's kernel (default 150;
                           the paper: 50)
  --warmup-iterations N    particle iterations at a narrower kernel first (default 100;
                           0 with --sample-iterations 1500 or more: best quality)
  --no-features            no corner / feature-line sites (paper §4.1 sharp features)
  --feature-angle A        dihedral angle (degrees) above which an edge is a feature line
                           (default 30; 180 = none)
  --seed S                 random seed (default 1)
  --mu X                   regularisation weight (default 100)
  --shrink F               shrink factor of the Voronoi cells (default 0.8; 1 = none)
  --tensor-as-metric       tensor: use eigenvalues as metric eigenvalues, not stretches
  --clamp                  tensor: clamp eigenvalues instead of taking absolute values
  --min-eigenvalue X       tensor: floor relative to the largest |eigenvalue| (default 1e-3)
  --max-anisotropy X       tensor: cap on the stretch ratio (default 25, 0 = none)
  --smooth N               tensor: log-Euclidean smoothing iterations (default 0)
  --refine N               volumes: remesh the domain with TetGen to about N vertices and
                           interpolate the input's point data onto it (a coarse FE mesh
                           cannot carry a fast-varying metric; default 0 = off)
  --no-repair              keep inverted mesh elements (default: insert sites at their dual
                           Voronoi vertices until none is left, paper §4.2)
  --repair-rounds N        insertion rounds at most (default 10)
  --repair-nonmanifold     also repair faces shared by more than two mesh elements
  --improve-rounds N       site improvement rounds before the repair (default 1; 0 = the
                           paper's pipeline): ODT steps and sliver pushes, diagram redone
  --odt-iterations N       ODT steps per improvement round (default 3; 0 = sliver pushes only)
  --output-dir DIR         where the results go (created if missing)
  --quiet                  no progress on stderr
  --help                   this text

writes into DIR: embedded.vtu, sites.vtp, voronoi.vtu, voronoi_faces.vtp, mesh.vtu,
energy.csv, report.json (the benchmark's keys). With the repair, mesh.vtu and voronoi.vtu
use the final sites (sampled ones first, then inserted ones; sites.vtp: the sampled ones).
)";

struct Options
{
  std::string Input, Metric, Sol, OutputDir;
  int Step = 0, Resolution = 0, Sites = 2000, Dim = 8, Iterations = 50, SampleIterations = 150;
  int WarmupIterations = 100, Seed = 1, Smooth = 0, Refine = 0, RepairRounds = 10, ImproveRounds = 1, OdtIterations = 3;
  double FeatureAngle = 30.0;
  bool Features = true;
  double Mu = 100.0, Shrink = 0.8, MinEigenvalue = 1e-3, MaxAnisotropy = 25.0;
  bool TensorAsMetric = false, Clamp = false, Quiet = false, Repair = true;
  bool RepairNonManifold = false, DoubleSolve = false;
};

[[noreturn]] void Fail(const std::string& message, int code = 1)
{
  std::cerr << "anisovoronoi: error: " << message << std::endl;
  std::exit(code);
}

/// Collects the first error a VTK algorithm reports, so it can be printed as one line.
class ErrorCatcher : public vtkCommand
{
public:
  static ErrorCatcher* New() { return new ErrorCatcher; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    if (this->Message.empty() && data)
    {
      std::string text = static_cast<const char*>(data);
      // VTK prefixes "ERROR: In file, line N\nclass (0x...): message": keep the message.
      const std::size_t colon = text.find("): ");
      this->Message = colon == std::string::npos ? text : text.substr(colon + 3);
      while (!this->Message.empty() &&
        (this->Message.back() == '\n' || this->Message.back() == ' '))
        this->Message.pop_back();
    }
  }
  std::string Message;
};

/**
 * Receives every VTK error/warning: errors raised inside helper objects (e.g. the legacy
 * reader's internal reader) reach no algorithm observer, so they are collected here.
 */
class CapturingOutputWindow : public vtkOutputWindow
{
public:
  static CapturingOutputWindow* New() { return new CapturingOutputWindow; }
  void DisplayErrorText(const char* text) override
  {
    if (this->FirstError.empty() && text)
    {
      std::string t = text;
      const std::size_t colon = t.find("): ");
      t = colon == std::string::npos ? t : t.substr(colon + 3);
      while (!t.empty() && (t.back() == '\n' || t.back() == ' '))
        t.pop_back();
      this->FirstError = t;
    }
  }
  void DisplayWarningText(const char* text) override
  {
    if (this->ShowWarnings && text)
      std::cerr << "[anisovoronoi] warning: " << text << std::flush;
  }
  void DisplayGenericWarningText(const char* text) override { this->DisplayWarningText(text); }
  void DisplayText(const char*) override {}
  void DisplayDebugText(const char*) override {}
  std::string FirstError;
  bool ShowWarnings = true;
};

int ParseInt(const std::string& flag, const char* value)
{
  char* end = nullptr;
  const long v = std::strtol(value, &end, 10);
  if (!end || *end || v < -1000000000L || v > 1000000000L)
    Fail(flag + " expects an integer, got '" + value + "'", 2);
  return static_cast<int>(v);
}

double ParseDouble(const std::string& flag, const char* value)
{
  char* end = nullptr;
  const double v = std::strtod(value, &end);
  if (!end || *end || !std::isfinite(v))
    Fail(flag + " expects a number, got '" + value + "'", 2);
  return v;
}

Options ParseCommandLine(int argc, char* argv[])
{
  Options o;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    auto next = [&]() -> const char* {
      if (i + 1 >= argc)
        Fail(a + " needs a value", 2);
      return argv[++i];
    };
    if (a == "--help" || a == "-h")
    {
      std::cout << Usage;
      std::exit(0);
    }
    else if (a == "--metric")
      o.Metric = next();
    else if (a == "--sol")
      o.Sol = next();
    else if (a == "--output-dir" || a == "-o")
      o.OutputDir = next();
    else if (a == "--step")
      o.Step = ParseInt(a, next());
    else if (a == "--resolution")
      o.Resolution = ParseInt(a, next());
    else if (a == "--sites")
      o.Sites = ParseInt(a, next());
    else if (a == "--dim")
      o.Dim = ParseInt(a, next());
    else if (a == "--iterations")
      o.Iterations = ParseInt(a, next());
    else if (a == "--sample-iterations")
      o.SampleIterations = ParseInt(a, next());
    else if (a == "--warmup-iterations")
      o.WarmupIterations = ParseInt(a, next());
    else if (a == "--no-features")
      o.Features = false;
    else if (a == "--feature-angle")
      o.FeatureAngle = ParseDouble(a, next());
    else if (a == "--double-solve")
      o.DoubleSolve = true;
    else if (a == "--seed")
      o.Seed = ParseInt(a, next());
    else if (a == "--refine")
      o.Refine = ParseInt(a, next());
    else if (a == "--smooth")
      o.Smooth = ParseInt(a, next());
    else if (a == "--mu")
      o.Mu = ParseDouble(a, next());
    else if (a == "--shrink")
      o.Shrink = ParseDouble(a, next());
    else if (a == "--min-eigenvalue")
      o.MinEigenvalue = ParseDouble(a, next());
    else if (a == "--max-anisotropy")
      o.MaxAnisotropy = ParseDouble(a, next());
    else if (a == "--tensor-as-metric")
      o.TensorAsMetric = true;
    else if (a == "--clamp")
      o.Clamp = true;
    else if (a == "--quiet")
      o.Quiet = true;
    else if (a == "--no-repair")
      o.Repair = false;
    else if (a == "--repair-rounds")
      o.RepairRounds = ParseInt(a, next());
    else if (a == "--improve-rounds")
      o.ImproveRounds = ParseInt(a, next());
    else if (a == "--odt-iterations")
      o.OdtIterations = ParseInt(a, next());
    else if (a == "--repair-nonmanifold")
      o.RepairNonManifold = true;
    else if (!a.empty() && a[0] == '-')
      Fail("unknown option " + a + " (see --help)", 2);
    else if (o.Input.empty())
      o.Input = a;
    else
      Fail("more than one INPUT given ('" + o.Input + "', '" + a + "')", 2);
  }
  if (o.Metric.empty())
    Fail("--metric SPEC is required (see --help)", 2);
  if (o.OutputDir.empty())
    Fail("--output-dir DIR is required", 2);
  if (o.Input.empty() && o.Metric.rfind("preset:", 0) != 0)
    Fail("an INPUT file is required unless --metric preset:NAME", 2);
  if (o.Sites < 1)
    Fail("--sites must be at least 1", 2);
  if (o.Dim < 3 || o.Dim > 20)
    Fail("--dim must be in [3, 20]", 2);
  if (o.Iterations < 0 || o.SampleIterations < 0 || o.WarmupIterations < 0)
    Fail("iteration counts must be >= 0", 2);
  if (!(o.FeatureAngle > 0 && o.FeatureAngle <= 180))
    Fail("--feature-angle must be in (0, 180]", 2);
  if (!(o.Shrink > 0 && o.Shrink <= 1))
    Fail("--shrink must be in (0, 1]", 2);
  if (o.RepairRounds < 0 || o.RepairRounds > 1000)
    Fail("--repair-rounds must be in [0, 1000]", 2);
  if (o.ImproveRounds < 0 || o.ImproveRounds > 10)
    Fail("--improve-rounds must be in [0, 10]", 2);
  if (o.OdtIterations < 0 || o.OdtIterations > 20)
    Fail("--odt-iterations must be in [0, 20]", 2);
  return o;
}

class Pipeline
{
public:
  explicit Pipeline(bool quiet)
    : Quiet(quiet)
  {
  }

  /// Runs `algorithm`; on failure prints its first error and exits.
  void Run(vtkAlgorithm* algorithm, const std::string& stage)
  {
    vtkNew<ErrorCatcher> catcher;
    const unsigned long tag = algorithm->AddObserver(vtkCommand::ErrorEvent, catcher);
    const unsigned long execTag =
      algorithm->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, catcher);
    if (!this->Quiet)
      std::cerr << "[anisovoronoi] " << stage << " ..." << std::flush;
    const auto t0 = std::chrono::steady_clock::now();
    auto* window = static_cast<CapturingOutputWindow*>(vtkOutputWindow::GetInstance());
    window->FirstError.clear();
    algorithm->Update();
    if (catcher->Message.empty() && !window->FirstError.empty())
      catcher->Message = window->FirstError;
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    algorithm->RemoveObserver(tag);
    algorithm->GetExecutive()->RemoveObserver(execTag);
    if (!catcher->Message.empty())
    {
      if (!this->Quiet)
        std::cerr << " failed" << std::endl;
      Fail(stage + ": " +
        (catcher->Message.empty() ? std::string("the stage failed") : catcher->Message));
    }
    if (!this->Quiet)
      std::cerr << " " << seconds << " s" << std::endl;
    this->Seconds[stage] = seconds;
  }

  std::map<std::string, double> Seconds;

private:
  bool Quiet;
};

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

void WriteXML(vtkDataObject* data, const std::string& path)
{
  vtkSmartPointer<vtkXMLWriter> writer;
  if (vtkPolyData::SafeDownCast(data))
    writer = vtkSmartPointer<vtkXMLPolyDataWriter>::New();
  else
    writer = vtkSmartPointer<vtkXMLUnstructuredGridWriter>::New();
  writer->SetInputData(data);
  writer->SetFileName(path.c_str());
  writer->SetDataModeToBinary(); // appended mode does not read back with this VTK/expat
  if (!writer->Write())
    Fail("cannot write " + path);
}

/// Reads INPUT by its extension; returns the algorithm producing it.
vtkSmartPointer<vtkAlgorithm> MakeReader(const Options& o)
{
  if (!vtksys::SystemTools::FileExists(o.Input, true))
    Fail("cannot read '" + o.Input + "': no such file");
  const std::string ext =
    vtksys::SystemTools::LowerCase(vtksys::SystemTools::GetFilenameLastExtension(o.Input));
  if (ext == ".mesh")
  {
    auto r = vtkSmartPointer<vtkAnisoMeditReader>::New();
    r->SetFileName(o.Input.c_str());
    if (!o.Sol.empty())
      r->SetSolFileName(o.Sol.c_str());
    return r;
  }
  if (!o.Sol.empty())
    Fail("--sol is only meaningful with a Medit .mesh INPUT", 2);
  if (ext == ".frd")
  {
    auto r = vtkSmartPointer<vtkAnisoFRDReader>::New();
    r->SetFileName(o.Input.c_str());
    r->SetStepIndex(o.Step);
    return r;
  }
  if (ext == ".vtk")
  {
    auto r = vtkSmartPointer<vtkDataSetReader>::New();
    r->SetFileName(o.Input.c_str());
    r->ReadAllTensorsOn();
    r->ReadAllScalarsOn();
    r->ReadAllVectorsOn();
    r->ReadAllFieldsOn();
    return r;
  }
  if (ext == ".vtu" || ext == ".vtp" || ext == ".vts" || ext == ".vtr" || ext == ".vti")
  {
    auto r = vtkSmartPointer<vtkXMLGenericDataObjectReader>::New();
    r->SetFileName(o.Input.c_str());
    return r;
  }
  vtkSmartPointer<vtkAlgorithm> surface;
  if (ext == ".stl")
  {
    auto r = vtkSmartPointer<vtkSTLReader>::New();
    r->SetFileName(o.Input.c_str());
    surface = r;
  }
  else if (ext == ".ply")
  {
    auto r = vtkSmartPointer<vtkPLYReader>::New();
    r->SetFileName(o.Input.c_str());
    surface = r;
  }
  else if (ext == ".off")
  {
    av::SimplexMesh surfaceMesh;
    try
    {
      surfaceMesh = av::ReadOff(o.Input);
    }
    catch (const av::InputError& e)
    {
      Fail(std::string("read ") + vtksys::SystemTools::GetFilenameName(o.Input) + ": " + e.what());
    }
    auto grid = vtkSmartPointer<vtkPolyData>::New();
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    for (std::size_t i = 0; i < surfaceMesh.NumPoints(); ++i)
      points->InsertNextPoint(surfaceMesh.Point(i));
    vtkNew<vtkCellArray> triangles;
    for (std::size_t c = 0; c < surfaceMesh.NumCells(); ++c)
    {
      const vtkIdType ids[3] = { surfaceMesh.Cell(c)[0], surfaceMesh.Cell(c)[1],
        surfaceMesh.Cell(c)[2] };
      triangles->InsertNextCell(3, ids);
    }
    grid->SetPoints(points);
    grid->SetPolys(triangles);
    auto producer = vtkSmartPointer<vtkTrivialProducer>::New();
    producer->SetOutput(grid);
    return producer;
  }
  else if (ext == ".obj")
  {
    auto r = vtkSmartPointer<vtkOBJReader>::New();
    r->SetFileName(o.Input.c_str());
    surface = r;
  }
  else
  {
    Fail("unsupported INPUT extension '" + ext +
      "' (use .vtk .vtu .vtp .mesh .frd .stl .ply .obj .off)");
  }
  // Surfaces: polygons -> triangles.
  auto tri = vtkSmartPointer<vtkTriangleFilter>::New();
  tri->SetInputConnection(surface->GetOutputPort());
  tri->PassVertsOff();
  tri->PassLinesOff();
  return tri;
}
}

int main(int argc, char* argv[])
{
  // VTK's own error output is replaced by our one-line messages.
  // VTK 9 also logs errors to stderr through loguru: silence it, we print one line.
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  vtkNew<CapturingOutputWindow> window;
  vtkOutputWindow::SetInstance(window);
  const Options o = ParseCommandLine(argc, argv);
  window->ShowWarnings = !o.Quiet;
  if (!vtksys::SystemTools::MakeDirectory(o.OutputDir))
    Fail("cannot create the output directory '" + o.OutputDir + "'");
  Pipeline pipeline(o.Quiet);

  // 1. Input mesh (read, or the preset's own mesh).
  vtkSmartPointer<vtkAlgorithm> source;
  const bool preset = o.Metric.rfind("preset:", 0) == 0;
  const std::string presetName = preset ? o.Metric.substr(7) : std::string();
  if (o.Input.empty())
  {
    auto s = vtkSmartPointer<vtkAnisoAnalyticMetricSource>::New();
    if (!s->SetPresetByName(presetName.c_str()))
      Fail("unknown preset '" + presetName +
        "' (gaussian2d cube1 cube2 cube3 sphere-cyl sphere-cos)", 2);
    if (o.Resolution != 0 && o.Resolution < 3)
      Fail("--resolution must be 0 or >= 3", 2);
    s->SetResolution(o.Resolution);
    source = s;
    pipeline.Run(source, "mesh " + presetName);
  }
  else
  {
    source = MakeReader(o);
    pipeline.Run(source, "read " + vtksys::SystemTools::GetFilenameName(o.Input));
  }

  // 2. Simplices (hexahedra, quadratic cells, ... are split).
  vtkNew<vtkAnisoSimplexMesh> simplices;
  simplices->SetInputConnection(source->GetOutputPort());
  pipeline.Run(simplices, "split into simplices");

  // 2b. Optional finer background mesh: TetGen on the boundary surface, point data probed.
  vtkSmartPointer<vtkAlgorithm> domain = simplices.GetPointer();
  vtkNew<vtkDataSetSurfaceFilter> boundary;
  vtkNew<vtkTriangleFilter> boundaryTriangles;
  vtkNew<vtkAnisoTetMesher> remesher;
  vtkNew<vtkProbeFilter> probe;
  vtkNew<vtkUnstructuredGrid> refined;
  vtkNew<vtkTrivialProducer> refinedProducer;
  if (o.Refine > 0)
  {
    vtkDataSet* ds = vtkDataSet::SafeDownCast(simplices->GetOutputDataObject(0));
    if (!ds || ds->GetNumberOfCells() == 0 || ds->GetCellType(0) != VTK_TETRA)
      Fail("--refine applies to volume (tetrahedral) inputs only", 2);
    boundary->SetInputConnection(simplices->GetOutputPort());
    boundaryTriangles->SetInputConnection(boundary->GetOutputPort());
    remesher->SetInputConnection(boundaryTriangles->GetOutputPort());
    remesher->SetShapeToInputSurface();
    remesher->SetTargetVertices(o.Refine);
    pipeline.Run(remesher, "remesh with TetGen (" + std::to_string(o.Refine) + " vertices)");
    probe->SetInputConnection(remesher->GetOutputPort());
    probe->SetSourceConnection(simplices->GetOutputPort());
    probe->PassPointArraysOff();
    pipeline.Run(probe, "interpolate point data onto the new mesh");
    // Points the probe missed (round-off on the boundary) take the nearest input point's data.
    refined->DeepCopy(probe->GetOutputDataObject(0));
    vtkDataArray* mask = refined->GetPointData()->GetArray(probe->GetValidPointMaskArrayName());
    vtkDataSet* coarse = vtkDataSet::SafeDownCast(simplices->GetOutputDataObject(0));
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
        vtkDataArray* from =
          target ? coarse->GetPointData()->GetArray(target->GetName()) : nullptr;
        if (from && from->GetNumberOfComponents() == target->GetNumberOfComponents())
          target->SetTuple(i, from->GetTuple(nearest));
      }
      ++fixedPoints;
    }
    if (!o.Quiet && fixedPoints > 0)
      std::cerr << "[anisovoronoi] " << fixedPoints
                << " boundary point(s) took the nearest input point's data" << std::endl;
    refinedProducer->SetOutput(refined);
    domain = refinedProducer.GetPointer();
  }

  // 3. Metric.
  vtkSmartPointer<vtkAlgorithm> metric;
  const char* metricName = "Metric";
  if (preset && !o.Input.empty())
  {
    auto m = vtkSmartPointer<vtkAnisoAnalyticMetric>::New();
    if (!m->SetPresetByName(presetName.c_str()))
      Fail("unknown preset '" + presetName + "'", 2);
    m->SetInputConnection(domain->GetOutputPort());
    metric = m;
  }
  else if (preset)
  {
    metric = domain; // the source already carries the preset's metric
  }
  else if (o.Metric.rfind("tensor:", 0) == 0)
  {
    auto m = vtkSmartPointer<vtkAnisoTensorToMetric>::New();
    m->SetInputConnection(domain->GetOutputPort());
    const std::string array = o.Metric.substr(7);
    vtkDataSet* ds = vtkDataSet::SafeDownCast(domain->GetOutputDataObject(0));
    const bool onCells = ds && !ds->GetPointData()->GetArray(array.c_str()) &&
      ds->GetCellData()->GetArray(array.c_str());
    if (ds && !ds->GetPointData()->GetArray(array.c_str()) && !onCells)
      Fail("the input has no point or cell array named '" + array + "'");
    m->SetInputArrayToProcess(0, 0, 0,
      onCells ? vtkDataObject::FIELD_ASSOCIATION_CELLS : vtkDataObject::FIELD_ASSOCIATION_POINTS,
      array.c_str());
    m->SetInterpretation(o.TensorAsMetric ? vtkAnisoTensorToMetric::TENSOR_AS_METRIC
                                          : vtkAnisoTensorToMetric::EIGENVALUES_AS_STRETCH);
    m->SetEigenvalueMode(
      o.Clamp ? vtkAnisoTensorToMetric::CLAMP : vtkAnisoTensorToMetric::ABSOLUTE);
    m->SetMinimumEigenvalue(o.MinEigenvalue);
    m->SetMaximumAnisotropy(o.MaxAnisotropy);
    m->SetSmoothingIterations(o.Smooth);
    metric = m;
  }
  else if (o.Metric.rfind("metric:", 0) == 0)
  {
    metric = domain;
    metricName = nullptr; // chosen below on the embedding
  }
  else if (o.Metric == "curvature")
  {
    auto m = vtkSmartPointer<vtkAnisoCurvatureMetric>::New();
    m->SetInputConnection(domain->GetOutputPort());
    metric = m;
  }
  else
  {
    Fail("unknown metric SPEC '" + o.Metric +
      "' (tensor:ARRAY, metric:ARRAY, curvature or preset:NAME)", 2);
  }
  if (metric != domain)
    pipeline.Run(metric, "metric (" + o.Metric + ")");

  // 4. Embedding.
  vtkNew<vtkAnisoEmbedding> embedding;
  embedding->SetInputConnection(metric->GetOutputPort());
  embedding->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS,
    metricName ? metricName : o.Metric.substr(7).c_str());
  embedding->SetTargetDimension(o.Dim);
  embedding->SetIterations(o.Iterations);
  embedding->SetSinglePrecisionSolve(!o.DoubleSolve);
  embedding->SetMu(o.Mu);
  embedding->SetSeed(o.Seed);
  pipeline.Run(embedding, "embedding in " + std::to_string(o.Dim) + "D");
  vtkDataObject* embedded = embedding->GetOutputDataObject(0);

  // 5. Sites.
  vtkNew<vtkAnisoParticleSampler> sampler;
  sampler->SetInputConnection(embedding->GetOutputPort(0));
  sampler->SetNumberOfSites(o.Sites);
  sampler->SetIterations(o.SampleIterations);
  sampler->SetWarmupIterations(o.WarmupIterations);
  sampler->SetPreserveSharpFeatures(o.Features);
  sampler->SetFeatureAngle(o.FeatureAngle);
  sampler->SetSeed(o.Seed);
  pipeline.Run(sampler, "sampling " + std::to_string(o.Sites) + " sites");

  // 6. The dual mesh (with the repair's inserted sites), then the restricted Voronoi diagram
  // of its vertices = the final sites (shrunken cells for display).
  vtkNew<vtkAnisoRestrictedDelaunay> rdt;
  rdt->SetInputConnection(0, embedding->GetOutputPort(0));
  rdt->SetInputConnection(1, sampler->GetOutputPort(0));
  rdt->SetRepairInverted(o.Repair);
  rdt->SetMaxRepairRounds(o.RepairRounds);
  rdt->SetImprovementRounds(o.ImproveRounds);
  rdt->SetOdtIterations(o.OdtIterations);
  rdt->SetRepairNonManifold(o.RepairNonManifold);
  pipeline.Run(rdt, "restricted Delaunay mesh");
  vtkNew<vtkAnisoRestrictedVoronoi> rvd;
  rvd->SetInputConnection(0, embedding->GetOutputPort(0));
  rvd->SetInputConnection(1, rdt->GetOutputPort(0));
  rvd->SetShrinkFactor(o.Shrink);
  pipeline.Run(rvd, "restricted Voronoi diagram");
  vtkNew<vtkAnisoMeshQuality> quality;
  quality->SetInputConnection(rdt->GetOutputPort(0));
  pipeline.Run(quality, "mesh quality");

  // 7. Files.
  const std::string dir = o.OutputDir + "/";
  WriteXML(embedded, dir + "embedded.vtu");
  WriteXML(sampler->GetOutputDataObject(0), dir + "sites.vtp");
  WriteXML(rvd->GetOutputDataObject(0), dir + "voronoi.vtu");
  WriteXML(rvd->GetOutputDataObject(1), dir + "voronoi_faces.vtp");
  WriteXML(quality->GetOutputDataObject(0), dir + "mesh.vtu");
  if (auto* energy = vtkTable::SafeDownCast(embedding->GetOutputDataObject(1)))
  {
    std::ofstream csv(dir + "energy.csv");
    csv << "iteration,E_em,E_reg,E_total\n";
    csv.precision(12);
    for (vtkIdType r = 0; r < energy->GetNumberOfRows(); ++r)
      csv << r << "," << energy->GetValueByName(r, "E_em").ToDouble() << ","
          << energy->GetValueByName(r, "E_reg").ToDouble() << ","
          << energy->GetValueByName(r, "E_total").ToDouble() << "\n";
  }

  vtkDataSet* meshIn = vtkDataSet::SafeDownCast(embedded);
  vtkDataObject* qualityOut = quality->GetOutputDataObject(0);
  vtkDataObject* rvdOut = rvd->GetOutputDataObject(0);
  double stretchRange[2] = { NAN, NAN };
  if (meshIn && meshIn->GetPointData()->GetArray("Stretch"))
    meshIn->GetPointData()->GetArray("Stretch")->GetRange(stretchRange);
  vtkDataObject* rdtOut = rdt->GetOutputDataObject(0);
  const double repairSeconds = FieldValue(rdtOut, "RepairSeconds");
  const double meshSeconds = pipeline.Seconds["sampling " + std::to_string(o.Sites) + " sites"] +
    pipeline.Seconds["restricted Voronoi diagram"] + pipeline.Seconds["restricted Delaunay mesh"];
  std::vector<std::pair<std::string, std::string>> report = {
    { "input", "\"" + (o.Input.empty() ? "preset:" + presetName : o.Input) + "\"" },
    { "metric", "\"" + o.Metric + "\"" },
    { "input_vertices", std::to_string(meshIn ? meshIn->GetNumberOfPoints() : 0) },
    { "input_elements", std::to_string(meshIn ? meshIn->GetNumberOfCells() : 0) },
    { "dim", std::to_string(o.Dim) },
    { "iterations", std::to_string(o.Iterations) },
    { "metric_scale", JsonNumber(FieldValue(embedded, "MetricScale")) },
    { "stretch_min", JsonNumber(stretchRange[0]) },
    { "stretch_max", JsonNumber(stretchRange[1]) },
    { "L_avg", JsonNumber(FieldValue(embedded, "L_avg")) },
    { "L_max", JsonNumber(FieldValue(embedded, "L_max")) },
    { "embed_seconds", JsonNumber(pipeline.Seconds["embedding in " + std::to_string(o.Dim) + "D"]) },
    { "factor_seconds", JsonNumber(FieldValue(embedded, "FactorSeconds")) },
    { "sites", std::to_string(o.Sites) },
    { "sample_iterations", std::to_string(o.SampleIterations) },
    { "warmup_iterations", std::to_string(o.WarmupIterations) },
    { "corner_sites", JsonNumber(FieldValue(sampler->GetOutputDataObject(0), "NumCornerSites")) },
    { "feature_line_sites",
      JsonNumber(FieldValue(sampler->GetOutputDataObject(0), "NumFeatureLineSites")) },
    { "sample_seconds", JsonNumber(pipeline.Seconds["sampling " + std::to_string(o.Sites) + " sites"]) },
    { "rvd_seconds", JsonNumber(pipeline.Seconds["restricted Voronoi diagram"]) },
    { "rdt_seconds", JsonNumber(pipeline.Seconds["restricted Delaunay mesh"] - repairSeconds) },
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
    { "mesh_seconds", JsonNumber(meshSeconds) },
    { "voronoi_cells", std::to_string(vtkDataSet::SafeDownCast(rvdOut)
          ? vtkDataSet::SafeDownCast(rvdOut)->GetNumberOfCells() : 0) },
    { "rvd_volume_error", JsonNumber(FieldValue(rvdOut, "RelativeVolumeError")) },
    { "mesh_elements", std::to_string(vtkDataSet::SafeDownCast(qualityOut)
          ? vtkDataSet::SafeDownCast(qualityOut)->GetNumberOfCells() : 0) },
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
  std::ofstream json(dir + "report.json");
  json << "{\n";
  for (std::size_t k = 0; k < report.size(); ++k)
    json << "  \"" << report[k].first << "\": " << report[k].second
         << (k + 1 < report.size() ? ",\n" : "\n");
  json << "}\n";
  if (!json)
    Fail("cannot write " + dir + "report.json");
  if (!o.Quiet)
    std::cerr << "[anisovoronoi] wrote embedded.vtu sites.vtp voronoi.vtu voronoi_faces.vtp "
                 "mesh.vtu energy.csv report.json to "
              << o.OutputDir << std::endl;
  return 0;
}
