// SPDX-License-Identifier: BSD-3-Clause
// vtkAnisoRestrictedDelaunay: converts its inputs, runs av::RunMeshingPipeline (RVD, RDT,
// site improvement rounds, repair) and builds the dual mesh with its point and field data.
#include "vtkAnisoRestrictedDelaunay.h"

#include "InputError.h"
#include "MeshQuality.h"   // InterpolateMetricInCell
#include "MeshingPipeline.h"
#include "MetricAlgebra.h" // SurfaceMetricNormals
#include "SharpFeatures.h"
#include "Stopwatch.h"
#include "vtkAnisoDataConversion.h"
#include "vtkAnisoFilterUtilities.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkAnisoRestrictedDelaunay);

namespace
{
using vtkAnisoFilterUtilities::AddFieldValue;

/// Output point data: the sites' arrays, recomputed for moved sites and extended to the
/// inserted ones ("CellId" / "Barycentric" are theirs, arrays the mesh also has are
/// interpolated, others 0; a moved site keeps its "FeatureKind", an inserted one is free). On a
/// surface the 6-component "Metric" is interpolated as the sampler does it
/// (InterpolateMetricInCell: each vertex's rank-2 metric moved into the cell's plane first);
/// plain barycentric weights would mix tensors whose null directions differ and give a metric
/// that is not the surface's (turbine, 4000 sites: G_avg 0.81 and 12.8 % of triangles below
/// 30 degrees in the CLI's report, against 0.89 and 0.25 % for the same mesh in the bench).
void ExtendPointData(vtkDataSet* sitesInput,
  vtkDataSet* meshInput,
  const av::SimplexMesh& mesh,
  const av::SiteSet& sites,
  const std::vector<std::uint8_t>& moved,
  vtkUnstructuredGrid* output)
{
  vtkPointData* in = sitesInput->GetPointData();
  vtkPointData* meshPD = meshInput->GetPointData();
  vtkPointData* out = output->GetPointData();
  const vtkIdType n0 = sitesInput->GetNumberOfPoints();
  const vtkIdType n = static_cast<vtkIdType>(sites.NumSites());
  const int nv = mesh.SimplexDim + 1;
  vtkNew<vtkIdList> cellPoints;
  cellPoints->SetNumberOfIds(nv);
  double weights[4];
  for (int a = 0; a < in->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* src = in->GetArray(a); // null for non-numeric arrays: not carried over
    if (!src)
    {
      continue;
    }
    vtkSmartPointer<vtkDataArray> dst = vtk::TakeSmartPointer(src->NewInstance());
    dst->SetName(src->GetName());
    dst->SetNumberOfComponents(src->GetNumberOfComponents());
    dst->SetNumberOfTuples(n);
    for (vtkIdType i = 0; i < n0; ++i)
    {
      dst->SetTuple(i, i, src);
    }
    const auto changed = [&](vtkIdType i) { return i >= n0 || moved[static_cast<std::size_t>(i)]; };
    const std::string name = src->GetName() ? src->GetName() : "";
    vtkDataArray* meshArray = name.empty() ? nullptr : meshPD->GetArray(name.c_str());
    if (meshArray && meshArray->GetNumberOfComponents() != src->GetNumberOfComponents())
    {
      meshArray = nullptr;
    }
    const int nc = src->GetNumberOfComponents();
    av::MetricField surfaceMetric;
    std::vector<Eigen::Vector3d> surfaceNormals;
    std::string error;
    const bool surfaceTensor = meshArray && name == "Metric" && nc == 6 &&
      mesh.SimplexDim == 2 && mesh.AmbientDim == 3 &&
      vtkAnisoDataConversion::ToMetricField(meshArray, mesh.NumPoints(), surfaceMetric, error);
    if (surfaceTensor)
      surfaceNormals = av::SurfaceMetricNormals(surfaceMetric);
    for (vtkIdType i = 0; i < n; ++i)
    {
      // A moved site keeps its kind: only a line site slides, and along its line.
      if (!changed(i) || (name == "FeatureKind" && i < n0))
      {
        continue;
      }
      const std::int32_t cell = sites.CellIds[i];
      if (name == "CellId" && nc == 1)
      {
        dst->SetComponent(i, 0, cell);
      }
      else if (name == "Barycentric" && nc == 4)
      {
        for (int c = 0; c < 4; ++c)
          dst->SetComponent(i, c, sites.Bary[4 * i + c]);
      }
      else if (surfaceTensor)
      {
        double m[6];
        av::InterpolateMetricInCell(
          mesh, surfaceMetric, surfaceNormals, cell, sites.Bary.data() + 4 * i, m);
        for (int c = 0; c < 6; ++c)
          dst->SetComponent(i, c, m[c]);
      }
      else if (meshArray)
      {
        for (int v = 0; v < nv; ++v)
        {
          cellPoints->SetId(v, mesh.Cell(cell)[v]);
          weights[v] = sites.Bary[4 * i + v];
        }
        dst->InterpolateTuple(i, cellPoints, meshArray, weights);
      }
      else
      {
        for (int c = 0; c < nc; ++c)
          dst->SetComponent(i, c, 0.0);
      }
    }
    out->AddArray(dst);
    if (in->GetTensors() == src)
    {
      out->SetActiveTensors(dst->GetName());
    }
    if (in->GetScalars() == src)
    {
      out->SetActiveScalars(dst->GetName());
    }
  }
}

/// The feature angle the sampler found its feature lines with (its "FeatureAngle" field value),
/// for the feature-edge flips on surfaces; 180 (none) for sites without it.
double SamplerFeatureAngle(vtkDataSet* sitesInput)
{
  vtkDataArray* angle =
    sitesInput->GetFieldData() ? sitesInput->GetFieldData()->GetArray("FeatureAngle") : nullptr;
  if (!angle || angle->GetNumberOfTuples() < 1 || angle->GetNumberOfComponents() != 1)
    return 180.0;
  const double a = angle->GetTuple1(0);
  return a > 0.0 && a < 180.0 ? a : 180.0;
}

/// The features the sampler placed its sites on ("FeatureEdges", "FeatureCorners" field data,
/// point ids of the embedded mesh): `found` false when the sites have none. False with `error`
/// when they do not fit `mesh`.
bool SamplerFeatures(vtkDataSet* sitesInput,
  const av::SimplexMesh& mesh,
  av::SharpFeatures& out,
  bool& found,
  std::string& error)
{
  std::vector<std::int32_t> e, c;
  if (!vtkAnisoDataConversion::FeatureFieldData(sitesInput->GetFieldData(), e, c, found, error))
    return false;
  if (!found)
    return true;
  found = false;
  try
  {
    out = av::SharpFeaturesFromEdges(mesh, e, c);
  }
  catch (const av::InputError& x)
  {
    error = std::string("sites: their FeatureEdges do not fit the embedded mesh (") + x.what() +
      "); connect the mesh the sites were sampled on";
    return false;
  }
  found = true;
  return true;
}

/// The sampler's corner and feature-line sites ("FeatureKind" != 0), which the improvement
/// rounds must not push off their features (feature-line sites, FeatureLinePoint, may slide
/// along straight creases of the final tet mesh); empty when the sites have no such array. False
/// (with `error`) when the array does not have one component per site.
bool FixedSitesFromFeatureKind(vtkDataSet* sitesInput,
  std::size_t numSites,
  std::vector<std::uint8_t>& fixed,
  std::string& error)
{
  vtkDataArray* kind = sitesInput->GetPointData()->GetArray("FeatureKind");
  if (!kind)
  {
    return true;
  }
  if (kind->GetNumberOfComponents() != 1 ||
    kind->GetNumberOfTuples() != static_cast<vtkIdType>(numSites))
  {
    error = "sites: the FeatureKind array must have one component per site";
    return false;
  }
  fixed.resize(numSites);
  for (std::size_t i = 0; i < fixed.size(); ++i)
  {
    const double k = kind->GetTuple1(static_cast<vtkIdType>(i));
    fixed[i] = k == 1.0 ? av::FeatureLinePoint : (k != 0.0 ? 1 : 0);
  }
  return true;
}

/// Points (the sites in input space) and cells of the dual mesh.
void SetMeshGeometry(const av::RestrictedDelaunayMesh& rdt,
  std::size_t numSites,
  vtkUnstructuredGrid* output)
{
  const int adim = rdt.AmbientDim, nv = rdt.SimplexDim + 1;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(numSites));
  for (std::size_t i = 0; i < numSites; ++i)
  {
    const double* x = rdt.Points.data() + i * adim;
    points->SetPoint(static_cast<vtkIdType>(i), x[0], x[1], adim == 3 ? x[2] : 0.0);
  }
  output->SetPoints(points);
  const std::size_t nc = rdt.NumCells();
  output->AllocateExact(static_cast<vtkIdType>(nc), nv);
  vtkIdType ids[4];
  const int type = rdt.SimplexDim == 3 ? VTK_TETRA : VTK_TRIANGLE;
  for (std::size_t c = 0; c < nc; ++c)
  {
    for (int a = 0; a < nv; ++a)
      ids[a] = rdt.Cells[c * nv + a];
    output->InsertNextCell(type, nv, ids);
  }
}

/// "InsertedSite" point data and "Inverted" cell data.
void AddRepairFlags(const av::DelaunayRepairResult& repaired, vtkUnstructuredGrid* output)
{
  const av::RestrictedDelaunayMesh& rdt = repaired.Delaunay;
  const std::size_t ns = repaired.Sites.NumSites(), nc = rdt.NumCells();
  vtkNew<vtkUnsignedCharArray> insertedFlag;
  insertedFlag->SetName("InsertedSite");
  insertedFlag->SetNumberOfTuples(static_cast<vtkIdType>(ns));
  for (std::size_t i = 0; i < ns; ++i)
  {
    insertedFlag->SetValue(static_cast<vtkIdType>(i), i >= repaired.NumInputSites ? 1 : 0);
  }
  output->GetPointData()->AddArray(insertedFlag);
  vtkNew<vtkUnsignedCharArray> inverted;
  inverted->SetName("Inverted");
  inverted->SetNumberOfTuples(static_cast<vtkIdType>(nc));
  std::copy(rdt.Inverted.begin(), rdt.Inverted.end(), inverted->GetPointer(0));
  output->GetCellData()->AddArray(inverted);
}

/// The counts and timings of the run as one-value field data.
void AddRunFieldData(const av::MeshingPipelineResult& result, double seconds, vtkFieldData* fd)
{
  const av::DelaunayRepairResult& repaired = result.Repaired;
  const av::RestrictedDelaunayMesh& rdt = repaired.Delaunay;
  AddFieldValue(fd, "NumInverted", static_cast<double>(rdt.NumInverted));
  AddFieldValue(fd, "NumNonManifoldFaces", static_cast<double>(rdt.NumNonManifoldFaces));
  AddFieldValue(fd, "NumOpenInteriorFaces", static_cast<double>(rdt.NumOpenInteriorFaces));
  AddFieldValue(fd, "NumUnusedSites", static_cast<double>(rdt.NumUnusedSites));
  AddFieldValue(fd, "NumInsertedSites", static_cast<double>(repaired.NumInserted));
  AddFieldValue(fd, "RepairRounds", static_cast<double>(repaired.Rounds));
  AddFieldValue(fd, "RepairStalled", repaired.Stalled ? 1.0 : 0.0);
  AddFieldValue(fd, "NumInvertedBeforeRepair", static_cast<double>(repaired.InitialInverted));
  AddFieldValue(
    fd, "NumNonManifoldFacesBeforeRepair", static_cast<double>(repaired.InitialNonManifoldFaces));
  AddFieldValue(fd, "RepairSeconds", result.RepairSeconds);
  AddFieldValue(fd, "ValidDualReplaced", result.ValidDual.Replaced ? 1.0 : 0.0);
  AddFieldValue(fd, "ValidDualSeconds", result.ValidDualSeconds);
  AddFieldValue(fd, "NumSliversPerturbed", static_cast<double>(result.NumSlivers));
  AddFieldValue(fd, "NumMovedSites", static_cast<double>(result.NumMovedSites));
  AddFieldValue(fd, "NumOdtMovedSites", static_cast<double>(result.NumOdtMovedSites));
  AddFieldValue(fd, "DelaunaySeconds", seconds);
  const av::MeshImprovementResult& im = result.Improvement;
  AddFieldValue(fd, "NumInvertedBeforeMeshImprovement",
    static_cast<double>(result.InvertedBeforeImprovement));
  AddFieldValue(fd, "NumImprovementFlips",
    static_cast<double>(im.NumFlips23 + im.NumEdgeRemovals + im.NumFlips22));
  AddFieldValue(fd, "NumImprovementMoves", static_cast<double>(im.NumSmoothed));
  AddFieldValue(fd, "NumImprovementMeanMoves", static_cast<double>(im.NumMeanSmoothed));
  // Triangles: a split appends a site, a collapse leaves its vertex as an unused point.
  AddFieldValue(fd, "NumImprovementSplits", static_cast<double>(im.NumSplits));
  AddFieldValue(fd, "NumImprovementCollapses", static_cast<double>(im.NumCollapses));
  // Tets: an insertion appends a site where flips and moves leave a tet below 15 degrees.
  AddFieldValue(fd, "NumImprovementInsertions", static_cast<double>(im.NumInsertions));
  AddFieldValue(fd, "NumImprovementBoundarySnaps", static_cast<double>(im.NumBoundarySnaps));
  AddFieldValue(fd, "MeshImprovementSeconds", result.MeshImprovementSeconds);
  // Surfaces: site pairs consecutive along the feature lines, and how many of their edges the
  // flips made and could not make.
  AddFieldValue(fd, "NumFeatureEdgesRequired", static_cast<double>(result.FeatureEdges.Required));
  AddFieldValue(fd, "NumFeatureEdgesRecovered", static_cast<double>(result.FeatureEdges.Recovered));
  AddFieldValue(fd, "NumFeatureEdgesMissing", static_cast<double>(result.FeatureEdges.Missing));
  // Surfaces with an open boundary: boundary vertices off the input's boundary, before and
  // after, and the triangles that closed those notches.
  AddFieldValue(fd, "NumBoundaryNotches", static_cast<double>(result.BoundaryNotches.Notches));
  AddFieldValue(fd, "NumBoundaryNotchesClosed", static_cast<double>(result.BoundaryNotches.Closed));
  AddFieldValue(fd, "NumBoundaryNotchesLeft", static_cast<double>(result.BoundaryNotches.Left));
}

/// The pipeline options of the filter's parameters; progress and abort go through `self`.
av::MeshingPipelineOptions MeshingOptions(vtkAnisoRestrictedDelaunay* self,
  const std::vector<std::uint8_t>* fixedSites)
{
  av::MeshingPipelineOptions options;
  options.ImproveRounds = self->GetImprovementRounds();
  options.OdtIterations = self->GetOdtIterations();
  options.FixedSites = fixedSites;
  options.Repair = self->GetRepairInverted();
  options.MaxRepairRounds = self->GetMaxRepairRounds();
  options.RepairNonManifold = self->GetRepairNonManifold();
  options.ValidDual = self->GetValidDual();
  options.ImproveMesh = self->GetImproveMesh();
  options.Improvement.PlanarBoundary = self->GetImproveBoundary();
  options.Improvement.MeanSmoothingSweeps = self->GetMeanSmoothingSweeps();
  options.OdtKeepsFixedSites = self->GetKeepFeatureSites();
  options.CloseBoundaryNotches = self->GetCloseBoundaryNotches();
  options.Progress = [self](av::MeshingStep step)
  {
    if (self->GetAbortExecute())
    {
      return false;
    }
    switch (step)
    {
      case av::MeshingStep::Voronoi:
        self->UpdateProgress(0.5);
        break;
      case av::MeshingStep::Delaunay:
        self->UpdateProgress(0.6);
        break;
      case av::MeshingStep::Improvement:
        self->UpdateProgress(0.8);
        break;
      case av::MeshingStep::ImprovementRound:
        break;
    }
    return true;
  };
  return options;
}

/// What the repair left (or, with RepairInverted off, did not try), as a warning.
void WarnAboutBadElements(vtkAnisoRestrictedDelaunay* self,
  const av::DelaunayRepairResult& repaired)
{
  const av::RestrictedDelaunayMesh& rdt = repaired.Delaunay;
  if (rdt.NumInverted == 0 && rdt.NumNonManifoldFaces == 0)
  {
    return;
  }
  const char* why = !self->GetRepairInverted() ? "(RepairInverted is off)"
    : repaired.Stalled                         ? "left: the repair stopped because insertions "
                                                 "made more elements inverted than they "
                                                 "removed (the embedding is too poor here: "
                                                 "more embedding iterations or a finer input "
                                                 "mesh help); the best state is kept"
                                               : "left after the repair (more repair rounds, "
                                                 "more sites or a better embedding reduce them)";
  vtkWarningWithObjectMacro(self,
    "the dual mesh has " << rdt.NumInverted << " inverted element(s) and "
                         << rdt.NumNonManifoldFaces << " non-manifold face(s) " << why);
}

} // namespace

vtkAnisoRestrictedDelaunay::vtkAnisoRestrictedDelaunay()
{
  this->SetNumberOfInputPorts(2);
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Embedding");
  this->SetInputArrayToProcess(1, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Metric");
}

void vtkAnisoRestrictedDelaunay::SetSourceConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(1, output);
}

int vtkAnisoRestrictedDelaunay::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  return 1;
}

int vtkAnisoRestrictedDelaunay::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  vtkAnisoDataConversion::RequestWholeInputs(inputVector, this->GetNumberOfInputPorts());
  return 1;
}

int vtkAnisoRestrictedDelaunay::RequestData(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0]);
  vtkDataSet* sitesInput = vtkDataSet::GetData(inputVector[1]);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector, 0);
  if (vtkAnisoDataConversion::NothingToCompute(request, outputVector, input) || !sitesInput ||
    sitesInput->GetNumberOfPoints() == 0)
  {
    return 1; // not this piece, or empty in: empty out
  }
  const av::Stopwatch watch;

  av::SimplexMesh mesh;
  av::Embedding embedding;
  av::SiteSet sites;
  std::string error;
  std::vector<std::uint8_t> fixedSites;
  av::SharpFeatures features;
  bool haveFeatures = false;
  if (!vtkAnisoDataConversion::ToVoronoiInputs(input,
        this->GetInputArrayToProcess(0, inputVector),
        sitesInput,
        mesh,
        embedding,
        sites,
        error) ||
    !FixedSitesFromFeatureKind(sitesInput, sites.NumSites(), fixedSites, error) ||
    !SamplerFeatures(sitesInput, mesh, features, haveFeatures, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  av::MetricField metric;
  if (this->ImproveMesh)
  {
    vtkDataArray* metricArray = this->GetInputArrayToProcess(1, inputVector);
    // ParaView leaves the name at its XML default, the index "1", until the array domain sees
    // the input's arrays (a pvbatch script that builds the proxy before its input ran): then the
    // metric that Aniso Embedding passes through, "Metric". A name the user gave is kept.
    vtkInformation* chosen = this->GetInputArrayInformation(1);
    const char* requested = chosen && chosen->Has(vtkDataObject::FIELD_NAME())
      ? chosen->Get(vtkDataObject::FIELD_NAME())
      : nullptr;
    if (!metricArray && requested && std::string(requested) == "1" && input->GetPointData())
      metricArray = input->GetPointData()->GetArray("Metric");
    if (!metricArray)
    {
      vtkWarningMacro(<< "ImproveMesh: the embedded mesh has no metric point array (input array "
                         "1, default \"Metric\"); the mesh is not improved");
    }
    else if (!vtkAnisoDataConversion::ToMetricField(
               metricArray, mesh.NumPoints(), metric, error))
    {
      vtkErrorMacro(<< error);
      return 0;
    }
  }
  this->UpdateProgress(0.1);

  av::MeshingPipelineResult result;
  if (!vtkAnisoFilterUtilities::RunKernel(this,
        "restricted Delaunay mesh",
        [&]
        {
          av::MeshingPipelineOptions options =
            MeshingOptions(this, fixedSites.empty() ? nullptr : &fixedSites);
          options.Metric = metric.Values.empty() ? nullptr : &metric;
          options.FeatureAngle = SamplerFeatureAngle(sitesInput);
          options.Features = haveFeatures ? &features : nullptr;
          result = av::RunMeshingPipeline(mesh, embedding, sites, options);
        }))
  {
    return 0;
  }
  if (result.Aborted)
  {
    return 1;
  }

  const av::DelaunayRepairResult& repaired = result.Repaired;
  SetMeshGeometry(repaired.Delaunay, repaired.Sites.NumSites(), output);
  // Point ids are site ids: the sites' point data carries over unchanged, extended for the
  // inserted sites.
  if (repaired.NumInserted == 0 && result.NumMovedSites == 0)
  {
    output->GetPointData()->ShallowCopy(sitesInput->GetPointData());
  }
  else
  {
    ExtendPointData(sitesInput, input, mesh, repaired.Sites, result.Moved, output);
  }
  AddRepairFlags(repaired, output);
  this->NumberOfInverted = static_cast<vtkIdType>(repaired.Delaunay.NumInverted);
  this->NumberOfNonManifoldFaces = static_cast<vtkIdType>(repaired.Delaunay.NumNonManifoldFaces);
  this->NumberOfInsertedSites = static_cast<vtkIdType>(repaired.NumInserted);
  this->NumberOfRepairRounds = repaired.Rounds;
  AddRunFieldData(result, watch.Seconds(), output->GetFieldData());
  WarnAboutBadElements(this, repaired);
  this->UpdateProgress(1.0);
  return 1;
}

void vtkAnisoRestrictedDelaunay::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RepairInverted: " << (this->RepairInverted ? "On" : "Off") << "\n";
  os << indent << "RepairNonManifold: " << (this->RepairNonManifold ? "On" : "Off") << "\n";
  os << indent << "ValidDual: " << (this->ValidDual ? "On" : "Off") << "\n";
  os << indent << "ImproveMesh: " << (this->ImproveMesh ? "On" : "Off") << "\n";
  os << indent << "ImproveBoundary: " << (this->ImproveBoundary ? "On" : "Off") << "\n";
  os << indent << "MeanSmoothingSweeps: " << this->MeanSmoothingSweeps << "\n";
  os << indent << "KeepFeatureSites: " << (this->KeepFeatureSites ? "On" : "Off") << "\n";
  os << indent << "CloseBoundaryNotches: " << (this->CloseBoundaryNotches ? "On" : "Off") << "\n";
  os << indent << "MaxRepairRounds: " << this->MaxRepairRounds << "\n";
  os << indent << "ImprovementRounds: " << this->ImprovementRounds << "\n";
  os << indent << "OdtIterations: " << this->OdtIterations << "\n";
  os << indent << "NumberOfInsertedSites (last run): " << this->NumberOfInsertedSites << "\n";
  os << indent << "NumberOfRepairRounds (last run): " << this->NumberOfRepairRounds << "\n";
  os << indent << "NumberOfInverted (last run): " << this->NumberOfInverted << "\n";
  os << indent << "NumberOfNonManifoldFaces (last run): " << this->NumberOfNonManifoldFaces << "\n";
}
