// SPDX-License-Identifier: BSD-3-Clause
// vtkAnisoParticleSampler: converts the input, runs av::SampleParticles and builds the site
// polydata and the energy table.
#include "vtkAnisoParticleSampler.h"

#include "InputError.h"
#include "MeshQuality.h" // InterpolateMetricAtSites
#include "ParticleSampler.h"
#include "SharpFeatures.h"
#include "vtkAnisoDataConversion.h"
#include "vtkAnisoFilterUtilities.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataSet.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSignedCharArray.h>
#include <vtkTable.h>

#include <cmath>
#include <string>

vtkStandardNewMacro(vtkAnisoParticleSampler);

namespace
{
/// The kernel's options from the filter's parameters; progress and abort go through `filter`.
av::ParticleSamplerOptions MakeOptions(vtkAnisoParticleSampler* filter)
{
  av::ParticleSamplerOptions options;
  options.NumSites = static_cast<std::size_t>(filter->GetNumberOfSites());
  options.Iterations = filter->GetIterations();
  options.WarmupIterations = filter->GetWarmupIterations();
  options.PreserveSharpFeatures = filter->GetPreserveSharpFeatures();
  options.FeatureAngle = filter->GetFeatureAngle();
  options.Seed = static_cast<std::uint64_t>(static_cast<std::uint32_t>(filter->GetSeed()));
  options.KernelWidthFactor = filter->GetKernelWidthFactor();
  options.NeighborCutoff = filter->GetNeighborCutoff();
  options.Progress = [filter](double f)
  {
    filter->UpdateProgress(0.05 + 0.9 * f);
    return !filter->GetAbortExecute();
  };
  return options;
}

/// One vertex cell per site at its input-space position, with the point arrays "Embedding",
/// "CellId", "Barycentric", "FeatureKind" and ("Metric") the metric at the sites.
void FillSites(vtkPolyData* output, int ambientDim, const av::ParticleSamplerResult& result,
  const av::MetricField* siteMetric)
{
  const av::SiteSet& sites = result.Sites;
  const std::size_t n = sites.NumSites();
  const int dim = sites.Dim;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(n));
  vtkNew<vtkCellArray> verts;
  verts->AllocateExact(static_cast<vtkIdType>(n), static_cast<vtkIdType>(n));
  vtkNew<vtkIntArray> cellIds;
  cellIds->SetName("CellId");
  cellIds->SetNumberOfTuples(static_cast<vtkIdType>(n));
  for (std::size_t i = 0; i < n; ++i)
  {
    const double* x = sites.At(i);
    points->SetPoint(static_cast<vtkIdType>(i), x[0], x[1], ambientDim == 3 ? x[2] : 0.0);
    const vtkIdType id = static_cast<vtkIdType>(i);
    verts->InsertNextCell(1, &id);
    cellIds->SetValue(static_cast<vtkIdType>(i), sites.CellIds[i]);
  }
  output->SetPoints(points);
  output->SetVerts(verts);
  vtkPointData* pd = output->GetPointData();
  pd->AddArray(vtkAnisoDataConversion::MakeArray("Embedding", sites.Coords.data(), n, dim));
  pd->AddArray(cellIds);
  pd->AddArray(vtkAnisoDataConversion::MakeArray("Barycentric", sites.Bary.data(), n, 4));
  vtkNew<vtkSignedCharArray> kind;
  kind->SetName("FeatureKind");
  kind->SetNumberOfTuples(static_cast<vtkIdType>(n));
  for (std::size_t i = 0; i < n; ++i)
    kind->SetValue(static_cast<vtkIdType>(i), static_cast<signed char>(result.FeatureKind[i]));
  pd->AddArray(kind);
  if (siteMetric)
  {
    auto m = vtkAnisoDataConversion::MakeArray("Metric", siteMetric->Values.data(), n, 6);
    pd->AddArray(m);
    pd->SetActiveTensors("Metric");
  }
}

/// Given features (FeaturePatchArray, FeatureCornerArray) of `input` as converted to `mesh`
/// (its triangles in input order); false with `error` on a missing or bad array.
bool GivenFeatures(vtkAnisoParticleSampler* self,
  vtkDataSet* input,
  const av::SimplexMesh& mesh,
  av::SharpFeatures& features,
  std::string& error)
{
  const std::string patches = self->GetFeaturePatchArray() ? self->GetFeaturePatchArray() : "";
  const std::string corners = self->GetFeatureCornerArray() ? self->GetFeatureCornerArray() : "";
  vtkDataArray* ids = input->GetCellData()->GetArray(patches.c_str());
  if (!ids || ids->GetNumberOfComponents() != 1)
  {
    error = "FeaturePatchArray: no one-component cell array \"" + patches + "\" on the input";
    return false;
  }
  std::vector<std::int32_t> patch;
  patch.reserve(mesh.NumCells());
  for (vtkIdType c = 0; c < input->GetNumberOfCells(); ++c)
  {
    const int type = input->GetCellType(c);
    if (type != VTK_TRIANGLE && type != VTK_TETRA) // the cells ToSimplexMesh keeps, in order
      continue;
    const double id = ids->GetTuple1(c);
    if (!(std::abs(id) < 2147483647.0))
    {
      error = "FeaturePatchArray: cell " + std::to_string(c) + " has the patch id " +
        std::to_string(id) + ", not an integer";
      return false;
    }
    patch.push_back(static_cast<std::int32_t>(id));
  }
  std::vector<std::uint8_t> flags;
  if (!corners.empty())
  {
    vtkDataArray* marks = input->GetPointData()->GetArray(corners.c_str());
    if (!marks || marks->GetNumberOfComponents() != 1)
    {
      error = "FeatureCornerArray: no one-component point array \"" + corners + "\" on the input";
      return false;
    }
    flags.resize(mesh.NumPoints());
    for (std::size_t p = 0; p < flags.size(); ++p)
    {
      const double mark = marks->GetTuple1(static_cast<vtkIdType>(p));
      if (!std::isfinite(mark))
      {
        error = "FeatureCornerArray: point " + std::to_string(p) + " has a non-finite value";
        return false;
      }
      flags[p] = mark != 0.0 ? 1 : 0;
    }
  }
  try
  {
    features = av::SharpFeaturesFromPatches(
      mesh, patch, flags.empty() ? nullptr : &flags, self->GetFeatureAngle());
  }
  catch (const av::InputError& e)
  {
    error = std::string("FeaturePatchArray: ") + e.what();
    return false;
  }
  return true;
}

/// The run's summary values as one-value field arrays.
void AddSummary(vtkFieldData* fd, const av::ParticleSamplerResult& result)
{
  using vtkAnisoFilterUtilities::AddFieldValue;
  AddFieldValue(fd, "Sigma", result.Sigma);
  AddFieldValue(fd, "EmbeddedMeasure", result.EmbeddedMeasure);
  AddFieldValue(fd, "MeanNeighbors", result.MeanNeighbors);
  AddFieldValue(fd, "SamplerIterations", result.IterationsDone);
  AddFieldValue(fd, "SamplerWarmupIterations", result.WarmupIterationsDone);
  AddFieldValue(fd, "SamplerSeconds", result.Seconds);
  AddFieldValue(fd, "NumCornerSites", static_cast<double>(result.NumCornerSites));
  AddFieldValue(fd, "NumFeatureLineSites", static_cast<double>(result.NumFeatureLineSites));
  AddFieldValue(fd, "NumCoincidentRemoved", static_cast<double>(result.NumCoincidentRemoved));
}

/// "Iteration", "Energy": the energy history at the final kernel.
void FillEnergyTable(vtkTable* energyTable, const av::ParticleSamplerResult& result)
{
  vtkNew<vtkIntArray> iteration;
  iteration->SetName("Iteration");
  vtkNew<vtkDoubleArray> energy;
  energy->SetName("Energy");
  for (std::size_t k = 0; k < result.Energy.size(); ++k)
  {
    iteration->InsertNextValue(static_cast<int>(k));
    energy->InsertNextValue(result.Energy[k]);
  }
  energyTable->AddColumn(iteration);
  energyTable->AddColumn(energy);
}
}

vtkAnisoParticleSampler::vtkAnisoParticleSampler()
{
  this->SetNumberOfOutputPorts(2);
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Embedding");
}

vtkAnisoParticleSampler::~vtkAnisoParticleSampler()
{
  this->SetFeaturePatchArray(nullptr);
  this->SetFeatureCornerArray(nullptr);
}

int vtkAnisoParticleSampler::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  return 1;
}

int vtkAnisoParticleSampler::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkPolyData" : "vtkTable");
  return 1;
}

int vtkAnisoParticleSampler::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  vtkAnisoDataConversion::RequestWholeInputs(inputVector, this->GetNumberOfInputPorts());
  return 1;
}

int vtkAnisoParticleSampler::RequestData(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkTable* energyTable = vtkTable::GetData(outputVector, 1);
  if (vtkAnisoDataConversion::NothingToCompute(request, outputVector, input))
  {
    return 1; // not this piece, or empty in: empty out
  }
  if (this->NumberOfSites <= 0)
  {
    vtkErrorMacro("NumberOfSites must be at least 1");
    return 0;
  }

  av::SimplexMesh mesh;
  std::string error, note;
  if (!vtkAnisoDataConversion::ToSimplexMesh(input, mesh, error, &note))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  if (!note.empty())
  {
    vtkWarningMacro(<< note);
  }
  av::Embedding embedding;
  if (!vtkAnisoDataConversion::ToEmbedding(
        this->GetInputArrayToProcess(0, inputVector), mesh, embedding, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  // The metric is optional: interpolated at the sites for the quality measures downstream.
  vtkDataArray* metricArray = vtkAnisoDataConversion::FindPointTensorArray(nullptr, -1, input);
  av::MetricField metric;
  const bool haveMetric = metricArray &&
    vtkAnisoDataConversion::ToMetricField(metricArray, mesh.NumPoints(), metric, error);

  av::ParticleSamplerOptions options = MakeOptions(this);
  av::SharpFeatures given;
  if (this->PreserveSharpFeatures && this->FeaturePatchArray && *this->FeaturePatchArray)
  {
    if (!GivenFeatures(this, input, mesh, given, error))
    {
      vtkErrorMacro(<< error);
      return 0;
    }
    options.Features = &given;
  }
  else if (this->PreserveSharpFeatures)
  {
    // Feature lines that came with the input (a Medit file's Ridges and Corners).
    std::vector<std::int32_t> edges, corners;
    bool found = false;
    if (!vtkAnisoDataConversion::FeatureFieldData(
          input->GetFieldData(), edges, corners, found, error))
    {
      vtkErrorMacro(<< error);
      return 0;
    }
    if (found)
    {
      try
      {
        given = av::SharpFeaturesFromEdges(mesh, edges, corners);
      }
      catch (const av::InputError& e)
      {
        vtkErrorMacro(<< "the input's FeatureEdges / FeatureCorners field data: " << e.what());
        return 0;
      }
      options.Features = &given;
    }
  }
  av::ParticleSamplerResult result;
  av::MetricField siteMetric;
  if (!vtkAnisoFilterUtilities::RunKernel(this, "particle sampling",
        [&]
        {
          this->UpdateProgress(0.01);
          result = av::SampleParticles(mesh, embedding, options);
          if (haveMetric)
          {
            siteMetric = av::InterpolateMetricAtSites(mesh, metric, result.Sites);
          }
        }))
  {
    return 0;
  }
  if (!result.FeatureWarning.empty())
  {
    vtkWarningMacro(<< result.FeatureWarning);
  }
  if (result.Aborted)
  {
    vtkWarningMacro("sampling aborted after " << result.IterationsDone << " iterations");
  }
  this->Sigma = result.Sigma;

  FillSites(output, mesh.AmbientDim, result, haveMetric ? &siteMetric : nullptr);
  AddSummary(output->GetFieldData(), result);
  // The angle its feature lines were found with: the Delaunay filter finds the same lines.
  vtkAnisoFilterUtilities::AddFieldValue(output->GetFieldData(),
    "FeatureAngle",
    this->PreserveSharpFeatures ? this->FeatureAngle : 180.0);
  // The features the sites were placed on, for vtkAnisoRestrictedDelaunay.
  if (result.Features.NumEdges() > 0 || !result.Features.Corners.empty())
    vtkAnisoDataConversion::AddFeatureFieldData(
      output->GetFieldData(), result.Features.Edges, result.Features.Corners);
  FillEnergyTable(energyTable, result);
  this->UpdateProgress(1.0);
  return 1;
}

void vtkAnisoParticleSampler::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfSites: " << this->NumberOfSites << "\n";
  os << indent << "Iterations: " << this->Iterations << "\n";
  os << indent << "WarmupIterations: " << this->WarmupIterations << "\n";
  os << indent << "PreserveSharpFeatures: " << (this->PreserveSharpFeatures ? "on" : "off") << "\n";
  os << indent << "FeatureAngle: " << this->FeatureAngle << "\n";
  os << indent << "FeaturePatchArray: " << (this->FeaturePatchArray ? this->FeaturePatchArray : "")
     << "\n";
  os << indent
     << "FeatureCornerArray: " << (this->FeatureCornerArray ? this->FeatureCornerArray : "")
     << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "KernelWidthFactor: " << this->KernelWidthFactor << "\n";
  os << indent << "NeighborCutoff: " << this->NeighborCutoff << "\n";
}
