#include "vtkAnisoEmbedding.h"

#include "EdgeLengthError.h"
#include "EmbeddingSolver.h"
#include "MetricAlgebra.h"
#include "vtkAnisoDataConversion.h"

#include <vtkCellData.h>
#include <vtkDataSet.h>
#include <vtkDataSetAttributes.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkTable.h>
#include <vtkUnstructuredGrid.h>

#include <chrono>
#include <sstream>

vtkStandardNewMacro(vtkAnisoEmbedding);

namespace
{
void AddFieldValue(vtkFieldData* fd, const char* name, double value)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}
}

vtkAnisoEmbedding::vtkAnisoEmbedding()
{
  this->SetNumberOfOutputPorts(2);
  this->SetEmbeddingArrayName("Embedding");
  // Default: the active point tensors (FindPointTensorArray then falls back to "Metric").
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::TENSORS);
}

vtkAnisoEmbedding::~vtkAnisoEmbedding()
{
  this->SetEmbeddingArrayName(nullptr);
}

int vtkAnisoEmbedding::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  return 1;
}

int vtkAnisoEmbedding::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkUnstructuredGrid" : "vtkTable");
  return 1;
}

int vtkAnisoEmbedding::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  vtkAnisoDataConversion::RequestWholeInputs(inputVector, this->GetNumberOfInputPorts());
  return 1;
}

int vtkAnisoEmbedding::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0]);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector, 0);
  vtkTable* energyTable = vtkTable::GetData(outputVector, 1);
  if (vtkAnisoDataConversion::IsSecondaryPiece(request, outputVector))
  {
    return 1; // whole result on piece 0 only
  }
  if (!input || input->GetNumberOfPoints() == 0 || input->GetNumberOfCells() == 0)
  {
    return 1; // empty in, empty out
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
  if (this->TargetDimension <= mesh.AmbientDim)
  {
    vtkErrorMacro("TargetDimension " << this->TargetDimension
                                     << " must be larger than the input dimension "
                                     << mesh.AmbientDim);
    return 0;
  }
  int association = -1;
  vtkDataArray* chosen = this->GetInputArrayToProcess(0, inputVector, association);
  vtkDataArray* metricArray =
    vtkAnisoDataConversion::FindPointTensorArray(chosen, association, input);
  av::MetricField metric;
  if (!vtkAnisoDataConversion::ToMetricField(metricArray, mesh.NumPoints(), metric, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }

  // Extra coordinates can only lengthen edges: eigenvalues below 1 are scaled up (paper §6).
  double minEig = 0, maxEig = 0;
  av::EigenvalueRange(metric, mesh.AmbientDim == 2, minEig, maxEig);
  this->MetricScale = 1.0;
  if (mesh.SimplexDim == mesh.AmbientDim && !(minEig > 0))
  {
    vtkErrorMacro("the metric is not positive definite (smallest eigenvalue "
      << minEig << "); convert the tensor field with vtkAnisoTensorToMetric first");
    return 0;
  }
  const double usedMin = minEig;
  if (mesh.SimplexDim == mesh.AmbientDim && usedMin < 1.0)
  {
    if (!this->AutoScaleMetric)
    {
      vtkErrorMacro("the metric's smallest eigenvalue is " << usedMin
        << " < 1: an embedding that keeps the input coordinates cannot shorten edges; "
           "enable AutoScaleMetric or scale the metric");
      return 0;
    }
    this->MetricScale = 1.0 / usedMin;
    for (double& v : metric.Values)
      v *= this->MetricScale;
  }

  av::EmbeddingOptions options;
  options.TargetDim = this->TargetDimension;
  options.Iterations = this->Iterations;
  options.Mu = this->Mu;
  options.Seed = static_cast<std::uint64_t>(this->Seed);
  options.RelativeEnergyTolerance = this->RelativeEnergyTolerance;
  options.ElementMeasureWeighting = this->ElementMeasureWeighting;
  options.Initialisation = this->Initialisation == RANDOM ? av::EmbeddingInitialisation::Random
                                                          : av::EmbeddingInitialisation::Smooth;
  options.AndersonWindow = this->AndersonWindow;
  options.SinglePrecisionSolve = this->SinglePrecisionSolve;
  options.Progress = [this](const av::EmbeddingProgress& p) {
    this->UpdateProgress(0.05 + 0.9 * p.Iteration / std::max(1, p.Iterations));
    return !this->GetAbortExecute();
  };

  const auto start = std::chrono::steady_clock::now();
  av::EmbeddingResult result;
  av::EdgeLengthErrorResult errors;
  try
  {
    this->UpdateProgress(0.01);
    av::EmbeddingSolver solver(mesh, metric, options);
    result = solver.Run();
    if (result.Aborted)
    {
      vtkWarningMacro("embedding aborted after " << result.IterationsDone << " iterations");
    }
    errors = av::ComputeEdgeLengthError(mesh, metric, result.Embedded, false, true);
  }
  catch (const av::InputError& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("embedding failed: " << e.what());
    return 0;
  }
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  this->AverageEdgeLengthError = errors.AveragePercent;
  this->MaximumEdgeLengthError = errors.MaxPercent;

  // Output: the simplicial mesh with the input's point data (same point ids).
  output->ShallowCopy(vtkAnisoDataConversion::FromSimplexMesh(mesh));
  {
    // Keep the input's exact points (FromSimplexMesh writes z = 0 for flat 2D domains).
    vtkNew<vtkPoints> pts;
    pts->SetDataTypeToDouble();
    pts->SetNumberOfPoints(input->GetNumberOfPoints());
    for (vtkIdType i = 0; i < input->GetNumberOfPoints(); ++i)
      pts->SetPoint(i, input->GetPoint(i));
    output->SetPoints(pts);
  }
  output->GetPointData()->ShallowCopy(input->GetPointData());
  if (static_cast<std::size_t>(input->GetNumberOfCells()) == mesh.NumCells())
  {
    output->GetCellData()->ShallowCopy(input->GetCellData());
  }
  output->GetFieldData()->ShallowCopy(input->GetFieldData());
  output->GetPointData()->AddArray(vtkAnisoDataConversion::MakeArray(
    this->EmbeddingArrayName ? this->EmbeddingArrayName : "Embedding",
    result.Embedded.Coords.data(), mesh.NumPoints(), result.Embedded.Dim));
  output->GetCellData()->AddArray(vtkAnisoDataConversion::MakeArray("EdgeLengthError",
    errors.CellMaxPercent.data(), errors.CellMaxPercent.size(), 1));
  vtkFieldData* fd = output->GetFieldData();
  AddFieldValue(fd, "L_avg", errors.AveragePercent);
  AddFieldValue(fd, "L_max", errors.MaxPercent);
  AddFieldValue(fd, "MetricScale", this->MetricScale);
  AddFieldValue(fd, "EmbeddingDimension", result.Embedded.Dim);
  AddFieldValue(fd, "EmbeddingIterations", result.IterationsDone);
  AddFieldValue(fd, "FactorSeconds", result.FactorSeconds);
  AddFieldValue(fd, "SolveSeconds", result.SolveSeconds);
  AddFieldValue(fd, "DoublePrecisionRetries", result.DoublePrecisionRetries);
  AddFieldValue(fd, "EmbeddingSeconds", seconds);

  // Output 1: the energy history.
  vtkNew<vtkIntArray> iteration;
  iteration->SetName("Iteration");
  vtkNew<vtkDoubleArray> eem, ereg, etot;
  eem->SetName("E_em");
  ereg->SetName("E_reg");
  etot->SetName("E_total");
  for (std::size_t k = 0; k < result.EnergyHistory.size(); ++k)
  {
    iteration->InsertNextValue(static_cast<int>(k));
    eem->InsertNextValue(result.EnergyHistory[k].Embedding);
    ereg->InsertNextValue(result.EnergyHistory[k].Regularisation);
    etot->InsertNextValue(result.EnergyHistory[k].Total);
  }
  energyTable->AddColumn(iteration);
  energyTable->AddColumn(eem);
  energyTable->AddColumn(ereg);
  energyTable->AddColumn(etot);
  this->UpdateProgress(1.0);
  return 1;
}

void vtkAnisoEmbedding::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "TargetDimension: " << this->TargetDimension << "\n";
  os << indent << "Iterations: " << this->Iterations << "\n";
  os << indent << "Mu: " << this->Mu << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "RelativeEnergyTolerance: " << this->RelativeEnergyTolerance << "\n";
  os << indent << "ElementMeasureWeighting: " << this->ElementMeasureWeighting << "\n";
  os << indent << "Initialisation: " << (this->Initialisation == RANDOM ? "Random" : "Smooth")
     << "\n";
  os << indent << "AndersonWindow: " << this->AndersonWindow << "\n";
  os << indent << "SinglePrecisionSolve: " << this->SinglePrecisionSolve << "\n";
  os << indent << "AutoScaleMetric: " << this->AutoScaleMetric << "\n";
  os << indent << "EmbeddingArrayName: "
     << (this->EmbeddingArrayName ? this->EmbeddingArrayName : "") << "\n";
}
