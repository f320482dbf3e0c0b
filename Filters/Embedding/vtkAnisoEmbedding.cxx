// SPDX-License-Identifier: BSD-3-Clause
// vtkAnisoEmbedding: converts the mesh and metric, runs MetricScaling, EmbeddingSolver and
// EdgeLengthError, and builds the embedded mesh and the energy table.
#include "vtkAnisoEmbedding.h"

#include "EdgeLengthError.h"
#include "EmbeddingErrorReport.h"
#include "EmbeddingSolver.h"
#include "MetricScaling.h"
#include "Stopwatch.h"
#include "vtkAnisoDataConversion.h"
#include "vtkAnisoFilterUtilities.h"

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

#include <algorithm>

vtkStandardNewMacro(vtkAnisoEmbedding);

namespace
{
/// The solver's parameters from the filter's; the progress callback reports and honors aborts.
av::EmbeddingOptions MakeOptions(vtkAnisoEmbedding* self)
{
  av::EmbeddingOptions options;
  options.TargetDim = self->GetTargetDimension();
  options.Iterations = self->GetIterations();
  options.MaxIterations = self->GetMaxIterations();
  options.ConvergenceTolerance = self->GetConvergenceTolerance();
  options.TargetAverageErrorPercent = self->GetTargetAverageError();
  options.GlobalSolver = self->GetGlobalSolver() == vtkAnisoEmbedding::DIRECT_SOLVER
    ? av::EmbeddingGlobalSolver::Direct
    : self->GetGlobalSolver() == vtkAnisoEmbedding::ITERATIVE_SOLVER
    ? av::EmbeddingGlobalSolver::Iterative
    : av::EmbeddingGlobalSolver::Automatic;
  options.Mu = self->GetMu();
  options.ScaleFreeRegularizer = self->GetScaleFreeRegularizer();
  options.Seed = static_cast<std::uint64_t>(self->GetSeed());
  options.RelativeEnergyTolerance = self->GetRelativeEnergyTolerance();
  options.ElementMeasureWeighting = self->GetElementMeasureWeighting();
  options.ElementMetric = self->GetElementMetric() == vtkAnisoEmbedding::EDGE_LENGTHS
    ? av::EmbeddingElementMetric::EdgeLengths
    : av::EmbeddingElementMetric::VertexMean;
  switch (self->GetInitialization())
  {
    case vtkAnisoEmbedding::RANDOM:
      options.Initialization = av::EmbeddingInitialization::Random;
      break;
    case vtkAnisoEmbedding::SMOOTH:
      options.Initialization = av::EmbeddingInitialization::Smooth;
      break;
    default:
      options.Initialization = av::EmbeddingInitialization::MetricAligned;
  }
  options.AndersonWindow = self->GetAndersonWindow();
  options.SinglePrecisionSolve = self->GetSinglePrecisionSolve();
  options.SeparateBodies = self->GetSeparateBodies();
  options.Progress = [self](const av::EmbeddingProgress& p) {
    self->UpdateProgress(0.05 + 0.9 * p.Iteration / std::max(1, p.Iterations));
    return !self->GetAbortExecute();
  };
  return options;
}

/// The simplicial mesh of `input` and the metric `array` (what FindPointTensorArray chose).
bool ConvertInputs(vtkAnisoEmbedding* self, vtkDataSet* input, vtkDataArray* chosen,
  int association, av::SimplexMesh& mesh, av::MetricField& metric)
{
  std::string error, note;
  if (!vtkAnisoDataConversion::ToSimplexMesh(input, mesh, error, &note))
  {
    vtkErrorWithObjectMacro(self, << error);
    return false;
  }
  if (!note.empty())
  {
    vtkWarningWithObjectMacro(self, << note);
  }
  if (self->GetTargetDimension() <= mesh.AmbientDim)
  {
    vtkErrorWithObjectMacro(self, "TargetDimension " << self->GetTargetDimension()
                                  << " must be larger than the input dimension "
                                  << mesh.AmbientDim);
    return false;
  }
  vtkDataArray* metricArray =
    vtkAnisoDataConversion::FindPointTensorArray(chosen, association, input);
  if (!vtkAnisoDataConversion::ToMetricField(metricArray, mesh.NumPoints(), metric, error))
  {
    vtkErrorWithObjectMacro(self, << error);
    return false;
  }
  return true;
}

/// The input mesh with the input's exact points (FromSimplexMesh writes z = 0 for flat 2D
/// domains), its point, cell and field data, the embedding and the per-cell error.
void BuildEmbeddedMesh(vtkDataSet* input, const av::SimplexMesh& mesh, const char* arrayName,
  const av::Embedding& embedded, const av::EdgeLengthErrorResult& errors,
  vtkUnstructuredGrid* output)
{
  vtkAnisoDataConversion::CopySimplicesWithInputData(input, mesh, output);
  output->GetPointData()->AddArray(vtkAnisoDataConversion::MakeArray(
    arrayName, embedded.Coords.data(), mesh.NumPoints(), embedded.Dim));
  output->GetCellData()->AddArray(vtkAnisoDataConversion::MakeArray("EdgeLengthError",
    errors.CellMaxPercent.data(), errors.CellMaxPercent.size(), 1));
}

/// The figures of the run as one-value field data.
void AddFigures(vtkFieldData* fd, const av::EdgeLengthErrorResult& errors, double metricScale,
  const av::EmbeddingResult& result, double seconds)
{
  using vtkAnisoFilterUtilities::AddFieldValue;
  AddFieldValue(fd, "L_avg", errors.AveragePercent);
  AddFieldValue(fd, "L_max", errors.MaxPercent);
  AddFieldValue(fd, "MetricScale", metricScale);
  AddFieldValue(fd, "EmbeddingDimension", result.Embedded.Dim);
  AddFieldValue(fd, "EmbeddingIterations", result.IterationsDone);
  AddFieldValue(fd, "EmbeddingConverged", result.Converged ? 1 : 0);
  AddFieldValue(fd, "IterativeSolve", result.IterativeSolve ? 1 : 0);
  AddFieldValue(fd, "SwitchedToDirect", result.SwitchedToDirect ? 1 : 0);
  AddFieldValue(fd, "AlignedStart", result.AlignedStart ? 1 : 0);
  AddFieldValue(fd, "AlignedStartResidual", result.AlignedStartResidual);
  AddFieldValue(fd, "FactorSeconds", result.FactorSeconds);
  AddFieldValue(fd, "SolveSeconds", result.SolveSeconds);
  AddFieldValue(fd, "DoublePrecisionRetries", result.DoublePrecisionRetries);
  AddFieldValue(fd, "ElementMetricFallbacks", static_cast<double>(result.ElementMetricFallbacks));
  AddFieldValue(fd, "EmbeddingSeconds", seconds);
}

/// Output 1: the energies per iteration (0 = initial state).
void BuildEnergyTable(const std::vector<av::EmbeddingEnergy>& history, vtkTable* table)
{
  vtkNew<vtkIntArray> iteration;
  iteration->SetName("Iteration");
  vtkNew<vtkDoubleArray> eem, ereg, etot;
  eem->SetName("E_em");
  ereg->SetName("E_reg");
  etot->SetName("E_total");
  for (std::size_t k = 0; k < history.size(); ++k)
  {
    iteration->InsertNextValue(static_cast<int>(k));
    eem->InsertNextValue(history[k].Embedding);
    ereg->InsertNextValue(history[k].Regularization);
    etot->InsertNextValue(history[k].Total);
  }
  table->AddColumn(iteration);
  table->AddColumn(eem);
  table->AddColumn(ereg);
  table->AddColumn(etot);
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
  this->NumberOfInputBodies = 0;
  if (vtkAnisoDataConversion::NothingToCompute(request, outputVector, input))
  {
    return 1; // not this piece, or empty in: empty out
  }
  int association = -1;
  vtkDataArray* chosen = this->GetInputArrayToProcess(0, inputVector, association);
  av::SimplexMesh mesh;
  av::MetricField metric;
  if (!ConvertInputs(this, input, chosen, association, mesh, metric))
  {
    return 0;
  }
  // Extra coordinates can only lengthen edges: eigenvalues below 1 are scaled up (paper §6).
  this->MetricScale = 1.0;
  if (!vtkAnisoFilterUtilities::RunKernel(this, "metric scaling", [&] {
        this->MetricScale =
          av::ScaleMetricForEmbedding(mesh, metric, this->AutoScaleMetric).Scale;
      }))
  {
    return 0;
  }

  const av::EmbeddingOptions options = MakeOptions(this);
  const av::Stopwatch clock;
  av::EmbeddingResult result;
  av::EdgeLengthErrorResult errors;
  av::LargeErrorSummary summary;
  if (!vtkAnisoFilterUtilities::RunKernel(this, "embedding", [&] {
        this->UpdateProgress(0.01);
        av::EmbeddingSolver solver(mesh, metric, options);
        result = solver.Run();
        if (result.Aborted)
        {
          vtkWarningMacro("embedding aborted after " << result.IterationsDone << " iterations");
        }
        errors = av::ComputeEdgeLengthError(mesh, metric, result.Embedded, false, true);
        summary = av::SummarizeLargeCellErrors(mesh, errors.CellMaxPercent,
          this->ErrorWarningThreshold > 0.0 ? this->ErrorWarningThreshold : VTK_DOUBLE_MAX);
      }))
  {
    return 0;
  }
  // Parts that touch without shared points (an FE contact assembly, unmerged nodes): say how
  // they were treated, a user may have meant one domain.
  this->NumberOfInputBodies = static_cast<vtkIdType>(result.NumBodies);
  if (this->NumberOfInputBodies > 1)
  {
    vtkWarningMacro(<< "the input has " << this->NumberOfInputBodies
                    << " separate bodies (cells connected through shared points), as a contact "
                       "assembly has. "
                    << (this->SeparateBodies
                           ? "They are embedded apart and sampled and meshed as separate "
                             "domains: no Voronoi cell or mesh element spans two of them, and "
                             "the meshes do not conform where the bodies touch. To mesh one "
                             "domain, merge the coincident points first (Clean to Grid)."
                           : "SeparateBodies is off: where they touch, Voronoi cells and mesh "
                             "elements may span two bodies."));
  }
  // Never silent: say where the embedding could not fit the metric.
  this->CellsAboveErrorThreshold = static_cast<vtkIdType>(summary.NumAbove);
  if (this->ErrorWarningThreshold > 0.0 && summary.NumAbove > 0)
  {
    vtkWarningMacro(<< av::DescribeLargeCellErrors(summary));
  }
  const double seconds = clock.Seconds();
  // Against the unprepared metric too, when metric preparation left it ("RawMetric", at the
  // prepared metric's complexity): preparation must not be a way to make L_avg easy.
  av::EdgeLengthErrorResult rawErrors;
  vtkDataArray* rawArray = input->GetPointData()->GetArray("RawMetric");
  av::MetricField raw;
  std::string rawError;
  const bool withRaw = rawArray &&
    vtkAnisoDataConversion::ToMetricField(rawArray, mesh.NumPoints(), raw, rawError);
  if (withRaw &&
    !vtkAnisoFilterUtilities::RunKernel(this, "edge length error against the raw metric", [&] {
      for (double& v : raw.Values)
        v *= this->MetricScale;
      rawErrors = av::ComputeEdgeLengthError(mesh, raw, result.Embedded);
    }))
  {
    return 0;
  }
  this->AverageEdgeLengthError = errors.AveragePercent;
  this->MaximumEdgeLengthError = errors.MaxPercent;

  BuildEmbeddedMesh(input, mesh, this->EmbeddingArrayName ? this->EmbeddingArrayName : "Embedding",
    result.Embedded, errors, output);
  AddFigures(output->GetFieldData(), errors, this->MetricScale, result, seconds);
  if (withRaw)
  {
    vtkAnisoFilterUtilities::AddFieldValue(output->GetFieldData(), "L_avg_raw", rawErrors.AveragePercent);
    vtkAnisoFilterUtilities::AddFieldValue(output->GetFieldData(), "L_max_raw", rawErrors.MaxPercent);
  }
  vtkAnisoFilterUtilities::AddFieldValue(output->GetFieldData(), "CellsAboveErrorThreshold",
    static_cast<double>(summary.NumAbove));
  vtkAnisoFilterUtilities::AddFieldValue(
    output->GetFieldData(), "InputBodies", static_cast<double>(this->NumberOfInputBodies));
  BuildEnergyTable(result.EnergyHistory, energyTable);
  this->UpdateProgress(1.0);
  return 1;
}

void vtkAnisoEmbedding::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "TargetDimension: " << this->TargetDimension << "\n";
  os << indent << "Iterations: " << this->Iterations << "\n";
  os << indent << "MaxIterations: " << this->MaxIterations << "\n";
  os << indent << "ConvergenceTolerance: " << this->ConvergenceTolerance << "\n";
  os << indent << "TargetAverageError: " << this->TargetAverageError << "\n";
  os << indent << "GlobalSolver: "
     << (this->GlobalSolver == DIRECT_SOLVER      ? "Direct"
          : this->GlobalSolver == ITERATIVE_SOLVER ? "Iterative"
                                                   : "Automatic")
     << "\n";
  os << indent << "ErrorWarningThreshold: " << this->ErrorWarningThreshold << "\n";
  os << indent << "Mu: " << this->Mu << "\n";
  os << indent << "ScaleFreeRegularizer: " << this->ScaleFreeRegularizer << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "RelativeEnergyTolerance: " << this->RelativeEnergyTolerance << "\n";
  os << indent << "ElementMeasureWeighting: " << this->ElementMeasureWeighting << "\n";
  os << indent << "ElementMetric: "
     << (this->ElementMetric == VERTEX_MEAN ? "VertexMean" : "EdgeLengths") << "\n";
  os << indent << "Initialization: "
     << (this->Initialization == RANDOM ? "Random"
                                        : (this->Initialization == SMOOTH ? "Smooth" : "MetricAligned"))
     << "\n";
  os << indent << "AndersonWindow: " << this->AndersonWindow << "\n";
  os << indent << "SinglePrecisionSolve: " << this->SinglePrecisionSolve << "\n";
  os << indent << "SeparateBodies: " << this->SeparateBodies << "\n";
  os << indent << "AutoScaleMetric: " << this->AutoScaleMetric << "\n";
  os << indent << "EmbeddingArrayName: "
     << (this->EmbeddingArrayName ? this->EmbeddingArrayName : "") << "\n";
}
