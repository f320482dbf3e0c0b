// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAnisoTensorPipeline.h"

#include "vtkAnisoAdaptedBackgroundMesh.h"
#include "vtkAnisoDataConversion.h"
#include "vtkAnisoEmbedding.h"
#include "vtkAnisoFilterUtilities.h"
#include "vtkAnisoParticleSampler.h"
#include "vtkAnisoSimplexMesh.h"
#include "vtkAnisoTensorToMetric.h"

#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkDataSetAttributes.h>
#include <vtkDoubleArray.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkTable.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <sstream>
#include <vector>

namespace
{
/// Maps a stage's progress into the owner's range, forwards abort, records errors (an observed
/// ErrorEvent is not printed by VTK, so the owner reports it once, as its own).
class StageObserver : public vtkCommand
{
public:
  static StageObserver* New() { return new StageObserver; }
  void Execute(vtkObject* caller, unsigned long event, void* callData) override
  {
    if (event == vtkCommand::ProgressEvent && this->Owner)
    {
      const double p = callData ? *static_cast<double*>(callData) : 0.0;
      this->Owner->UpdateProgress(this->Begin + (this->End - this->Begin) * p);
      if (this->Owner->GetAbortExecute())
      {
        if (auto* alg = vtkAlgorithm::SafeDownCast(caller))
          alg->SetAbortExecute(1);
      }
    }
    else if (event == vtkCommand::ErrorEvent)
    {
      if (this->Error.empty() && callData)
        this->Error = static_cast<const char*>(callData);
    }
    else if (event == vtkCommand::WarningEvent && callData)
    {
      this->Warnings.emplace_back(static_cast<const char*>(callData));
    }
  }
  vtkAlgorithm* Owner = nullptr;
  double Begin = 0.0, End = 1.0;
  std::string Error;
  std::vector<std::string> Warnings;
};

// VTK error text looks like "ERROR: In file, line N\nvtkX (0x..): message": keep the message.
std::string StripLocation(const std::string& text)
{
  const auto pos = text.find("): ");
  std::string m = pos == std::string::npos ? text : text.substr(pos + 3);
  while (!m.empty() && (m.back() == '\n' || m.back() == ' '))
    m.pop_back();
  return m;
}
}

vtkAnisoTensorPipeline::vtkAnisoTensorPipeline()
{
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::TENSORS);
}

vtkAnisoTensorPipeline::~vtkAnisoTensorPipeline()
{
  this->SetFeaturePatchArray(nullptr);
}

int vtkAnisoTensorPipeline::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  return 1;
}

int vtkAnisoTensorPipeline::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  // The embedding is global: always the whole input.
  vtkAnisoDataConversion::RequestWholeInputs(inputVector, this->GetNumberOfInputPorts());
  return 1;
}

bool vtkAnisoTensorPipeline::RunStage(vtkAlgorithm* stage,
  const char* what,
  double begin,
  double end,
  std::string& error)
{
  vtkNew<StageObserver> observer;
  observer->Owner = this;
  observer->Begin = begin;
  observer->End = end;
  const unsigned long progressTag = stage->AddObserver(vtkCommand::ProgressEvent, observer);
  const unsigned long errorTag = stage->AddObserver(vtkCommand::ErrorEvent, observer);
  // Observed warnings are not printed by VTK: they are re-issued below under this filter.
  const unsigned long warningTag = stage->AddObserver(vtkCommand::WarningEvent, observer);
  // The executive's "returned failure for request" follow-up is swallowed the same way.
  vtkNew<StageObserver> executiveObserver;
  vtkExecutive* executive = stage->GetExecutive();
  const unsigned long execTag = executive->AddObserver(vtkCommand::ErrorEvent, executiveObserver);
  stage->Update();
  stage->RemoveObserver(progressTag);
  stage->RemoveObserver(errorTag);
  stage->RemoveObserver(warningTag);
  executive->RemoveObserver(execTag);
  for (const std::string& warning : observer->Warnings)
  {
    vtkWarningMacro(<< this->GetUserLabel() << ": " << what << ": " << StripLocation(warning));
  }
  if (!observer->Error.empty() || !executiveObserver->Error.empty())
  {
    error = std::string(this->GetUserLabel()) + ": " + what + ": " +
      StripLocation(observer->Error.empty() ? executiveObserver->Error : observer->Error);
    return false;
  }
  if (this->GetAbortExecute())
  {
    error = std::string(this->GetUserLabel()) + ": " + what + ": aborted";
    return false;
  }
  return true;
}

void vtkAnisoTensorPipeline::AddFrontFieldData(vtkFieldData* fd) const
{
  using vtkAnisoFilterUtilities::AddFieldValue;
  AddFieldValue(fd, "L_avg", this->AverageEdgeLengthError);
  AddFieldValue(fd, "L_max", this->MaximumEdgeLengthError);
  AddFieldValue(fd, "MetricScale", this->MetricScale);
  const char* names[6] = { "L_avg_raw", "L_max_raw", "MetricPrepMedianChange",
    "MetricPrepP95Change", "MetricPrepChangedFraction", "ImpliedSites" };
  for (int k = 0; k < 6; ++k)
    if (this->FrontFigures[k] >= 0.0)
      AddFieldValue(fd, names[k], this->FrontFigures[k]);
  vtkNew<vtkStringArray> mode;
  mode->SetName("FieldMode");
  mode->InsertNextValue((this->FieldModeUsed == METRIC_FIELD ? std::string("Metric Field")
                                                             : std::string("Tensor Field")) +
    (this->FieldModeReason.empty() ? "" : " (" + this->FieldModeReason + ")"));
  fd->AddArray(mode);
}

int vtkAnisoTensorPipeline::ResolveFieldMode(vtkDataArray* chosen,
  int association,
  vtkDataSet* input)
{
  this->FieldModeReason.clear();
  if (this->FieldMode != AUTOMATIC)
  {
    return this->FieldMode;
  }
  // Every metric producer of this project names its point array "Metric" (analytic source and
  // filter, tensor to metric, the Medit .sol reader); converting a metric as if it were a
  // stress would change it (Gaussian2D's stretch 1-3.84 became 1-9.2).
  vtkDataArray* candidate = chosen
    ? (association == vtkDataObject::FIELD_ASSOCIATION_POINTS ? chosen : nullptr)
    : input->GetPointData()->GetTensors();
  if (candidate && candidate->GetName() && std::string(candidate->GetName()) == "Metric")
  {
    this->FieldModeReason = "automatic: the point array \"Metric\" already is a metric";
    return METRIC_FIELD;
  }
  this->FieldModeReason = "automatic: the array is not a point array named \"Metric\"";
  return TENSOR_FIELD;
}

bool vtkAnisoTensorPipeline::ChooseFieldArray(vtkInformationVector** inputVector,
  vtkDataSet* input,
  vtkSmartPointer<vtkDataSet>& copy,
  std::string& arrayName,
  int& association)
{
  // The chosen array, by name on a shallow copy (an unnamed one gets a name there).
  association = -1;
  vtkDataArray* chosen = this->GetInputArrayToProcess(0, inputVector, association);
  vtkInformation* arrayInfo = this->GetInputArrayInformation(0);
  if (!chosen && arrayInfo && arrayInfo->Has(vtkDataObject::FIELD_NAME()) &&
    arrayInfo->Get(vtkDataObject::FIELD_NAME()) && *arrayInfo->Get(vtkDataObject::FIELD_NAME()))
  {
    vtkErrorMacro(
      "the input has no array named '" << arrayInfo->Get(vtkDataObject::FIELD_NAME()) << "'");
    return false;
  }
  this->FieldModeUsed = this->ResolveFieldMode(chosen, association, input);
  copy = vtk::TakeSmartPointer(input->NewInstance());
  copy->ShallowCopy(input);
  if (chosen)
  {
    if (association != vtkDataObject::FIELD_ASSOCIATION_POINTS &&
      association != vtkDataObject::FIELD_ASSOCIATION_CELLS)
    {
      vtkErrorMacro("the tensor array must be a point or a cell array");
      return false;
    }
    arrayName = chosen->GetName() && *chosen->GetName() ? chosen->GetName() : "AnisoTensor";
    if (!chosen->GetName() || !*chosen->GetName())
    {
      vtkSmartPointer<vtkDataArray> named = vtk::TakeSmartPointer(chosen->NewInstance());
      named->ShallowCopy(chosen);
      named->SetName(arrayName.c_str());
      (association == vtkDataObject::FIELD_ASSOCIATION_POINTS
          ? static_cast<vtkDataSetAttributes*>(copy->GetPointData())
          : static_cast<vtkDataSetAttributes*>(copy->GetCellData()))
        ->AddArray(named);
    }
  }
  if (this->FieldModeUsed == METRIC_FIELD)
  {
    vtkDataArray* metric = vtkAnisoDataConversion::FindPointTensorArray(chosen, association, input);
    if (!metric || (chosen && association != vtkDataObject::FIELD_ASSOCIATION_POINTS))
    {
      vtkErrorMacro("FieldMode MetricField needs a point metric array (6 or 9 components); "
                    "use TensorField for cell tensors");
      return false;
    }
    arrayName = metric->GetName() && *metric->GetName() ? metric->GetName() : arrayName;
    association = vtkDataObject::FIELD_ASSOCIATION_POINTS;
  }
  return true;
}

vtkSmartPointer<vtkDataSet> vtkAnisoTensorPipeline::RunMetricStages(vtkDataSet* input,
  const std::string& arrayName,
  int association,
  std::string& metricName,
  double& tensorScale)
{
  std::string error;
  vtkNew<vtkAnisoSimplexMesh> simplexMesh;
  simplexMesh->SetInputData(input);
  simplexMesh->ReportSplitOff();
  if (!this->RunStage(simplexMesh, "simplex mesh", 0.0, 0.02, error))
  {
    vtkErrorMacro(<< error);
    return nullptr;
  }
  vtkSmartPointer<vtkDataSet> withMetric = simplexMesh->GetOutput();
  metricName = arrayName;
  tensorScale = 1.0;
  if (this->FieldModeUsed == TENSOR_FIELD)
  {
    vtkNew<vtkAnisoTensorToMetric> tensorToMetric;
    tensorToMetric->SetInputData(withMetric);
    if (!arrayName.empty())
      tensorToMetric->SetInputArrayToProcess(0, 0, 0, association, arrayName.c_str());
    tensorToMetric->SetMinimumEigenvalue(this->MinimumEigenvalue);
    tensorToMetric->SetMaximumAnisotropy(this->MaximumAnisotropy);
    tensorToMetric->SetSmoothingIterations(this->SmoothingIterations);
    tensorToMetric->SetNumberOfSites(this->NumberOfCells);
    tensorToMetric->SetSizeMode(this->SizeMode);
    tensorToMetric->SetSizeBlend(this->SizeBlend);
    tensorToMetric->SetHMin(this->HMin);
    tensorToMetric->SetHMax(this->HMax);
    tensorToMetric->SetMinCellsAcross(this->MinCellsAcross);
    tensorToMetric->SetGradation(this->Gradation);
    tensorToMetric->SetGradationFactor(this->GradationFactor);
    tensorToMetric->SetMetricArrayName("Metric");
    if (!this->RunStage(tensorToMetric, "tensor to metric", 0.02, 0.05, error))
    {
      vtkErrorMacro(<< error);
      return nullptr;
    }
    withMetric = vtkDataSet::SafeDownCast(tensorToMetric->GetOutputDataObject(0));
    tensorScale = tensorToMetric->GetMetricScale();
    metricName = "Metric";
  }
  else
  {
    // The sampler interpolates the active point tensors: make the metric active (on a copy).
    vtkSmartPointer<vtkDataSet> active = vtk::TakeSmartPointer(withMetric->NewInstance());
    active->ShallowCopy(withMetric);
    if (!metricName.empty())
      active->GetPointData()->SetActiveTensors(metricName.c_str());
    withMetric = active;
  }
  if (!withMetric ||
    (!metricName.empty() && !withMetric->GetPointData()->GetArray(metricName.c_str())))
  {
    vtkErrorMacro("the metric point array is missing after the simplex split");
    return nullptr;
  }
  return withMetric;
}

int vtkAnisoTensorPipeline::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0]);
  if (!input || input->GetNumberOfPoints() == 0 || input->GetNumberOfCells() == 0)
  {
    return 1; // empty in, empty out
  }
  this->AverageEdgeLengthError = this->MaximumEdgeLengthError = 0.0;
  std::fill(this->FrontFigures, this->FrontFigures + 6, -1.0);
  this->MetricScale = 1.0;
  vtkSmartPointer<vtkDataSet> copy;
  std::string arrayName, metricName;
  int association = -1;
  double tensorScale = 1.0;
  if (!this->ChooseFieldArray(inputVector, input, copy, arrayName, association))
  {
    return 0;
  }
  // Say which mode ran: the same array read as a tensor or as a metric gives other cells.
  {
    std::ostringstream text;
    text << this->GetUserLabel() << ": Field Mode "
         << (this->FieldModeUsed == METRIC_FIELD ? "Metric Field" : "Tensor Field") << " on '"
         << (arrayName.empty() ? std::string("(active point tensors)") : arrayName) << "'"
         << (this->FieldModeReason.empty() ? "" : " (" + this->FieldModeReason + ")") << "\n";
    vtkOutputWindowDisplayText(text.str().c_str());
  }
  vtkSmartPointer<vtkDataSet> withMetric =
    this->RunMetricStages(copy, arrayName, association, metricName, tensorScale);
  if (!withMetric)
  {
    return 0;
  }

  std::string error;
  const bool adapt = this->AdaptBackgroundMesh == ADAPT_ALWAYS ||
    (this->AdaptBackgroundMesh == ADAPT_WHEN_COARSE && this->FieldModeUsed == TENSOR_FIELD);
  if (adapt)
  {
    vtkNew<vtkAnisoAdaptedBackgroundMesh> adapted;
    adapted->SetInputData(withMetric);
    if (!metricName.empty())
      adapted->SetInputArrayToProcess(
        0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, metricName.c_str());
    adapted->SetNumberOfSites(this->NumberOfCells);
    adapted->SetTargetEdgeLength(this->BackgroundEdgeLength);
    adapted->SetOnlyWhenCoarse(this->AdaptBackgroundMesh == ADAPT_WHEN_COARSE);
    adapted->SetFeatureAngle(this->FeatureAngle);
    if (!this->RunStage(adapted, "adapted background mesh", 0.05, 0.1, error))
    {
      vtkErrorMacro(<< error);
      return 0;
    }
    withMetric = adapted->GetOutput();
  }
  vtkNew<vtkAnisoEmbedding> embedding;
  embedding->SetInputData(withMetric);
  if (!metricName.empty())
    embedding->SetInputArrayToProcess(
      0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, metricName.c_str());
  embedding->SetTargetDimension(this->TargetDimension);
  embedding->SetIterations(this->Iterations);
  embedding->SetSeed(this->Seed);
  if (!this->RunStage(embedding, "embedding", 0.05, 0.6, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  vtkUnstructuredGrid* embedded = embedding->GetOutput();
  this->AverageEdgeLengthError = embedding->GetAverageEdgeLengthError();
  this->MaximumEdgeLengthError = embedding->GetMaximumEdgeLengthError();
  this->MetricScale = tensorScale * embedding->GetMetricScale();
  const char* figureNames[6] = { "L_avg_raw", "L_max_raw", "MetricPrepMedianChange",
    "MetricPrepP95Change", "MetricPrepChangedFraction", "ImpliedSites" };
  for (int k = 0; k < 6; ++k)
  {
    vtkDataArray* a = embedded->GetFieldData()->GetArray(figureNames[k]);
    this->FrontFigures[k] = a && a->GetNumberOfTuples() > 0 ? a->GetTuple1(0) : -1.0;
  }

  vtkNew<vtkAnisoParticleSampler> sampler;
  sampler->SetInputData(embedded);
  sampler->SetNumberOfSites(this->NumberOfCells);
  sampler->SetIterations(this->SamplingIterations);
  sampler->SetWarmupIterations(this->SamplingWarmupIterations);
  sampler->SetPreserveSharpFeatures(this->PreserveSharpFeatures);
  sampler->SetFeatureAngle(this->FeatureAngle);
  sampler->SetFeaturePatchArray(this->FeaturePatchArray);
  sampler->SetSeed(this->Seed);
  if (!this->RunStage(sampler, "particle sampler", 0.6, 0.85, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  vtkPolyData* sites = vtkPolyData::SafeDownCast(sampler->GetOutputDataObject(0));
  vtkTable* energy = vtkTable::SafeDownCast(embedding->GetOutputDataObject(1));
  if (!sites || sites->GetNumberOfPoints() == 0)
  {
    vtkErrorMacro("particle sampler: no site was produced");
    return 0;
  }
  const int ok = this->RequestBackEnd(embedded, sites, energy, outputVector);
  if (ok)
    this->UpdateProgress(1.0);
  return ok;
}

void vtkAnisoTensorPipeline::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FieldMode: "
     << (this->FieldMode == METRIC_FIELD
            ? "MetricField"
            : (this->FieldMode == AUTOMATIC ? "Automatic" : "TensorField"))
     << "\n";
  os << indent << "NumberOfCells: " << this->NumberOfCells << "\n";
  os << indent << "TargetDimension: " << this->TargetDimension << "\n";
  os << indent << "Iterations: " << this->Iterations << "\n";
  os << indent << "SamplingIterations: " << this->SamplingIterations << "\n";
  os << indent << "SamplingWarmupIterations: " << this->SamplingWarmupIterations << "\n";
  os << indent << "PreserveSharpFeatures: " << (this->PreserveSharpFeatures ? "on" : "off") << "\n";
  os << indent << "FeatureAngle: " << this->FeatureAngle << "\n";
  os << indent << "FeaturePatchArray: " << (this->FeaturePatchArray ? this->FeaturePatchArray : "")
     << "\n";
  os << indent << "MaximumAnisotropy: " << this->MaximumAnisotropy << "\n";
  os << indent << "MinimumEigenvalue: " << this->MinimumEigenvalue << "\n";
  os << indent << "SmoothingIterations: " << this->SmoothingIterations << "\n";
  os << indent << "SizeMode: " << this->SizeMode << "\n";
  os << indent << "SizeBlend: " << this->SizeBlend << "\n";
  os << indent << "HMin: " << this->HMin << "\n";
  os << indent << "HMax: " << this->HMax << "\n";
  os << indent << "MinCellsAcross: " << this->MinCellsAcross << "\n";
  os << indent << "Gradation: " << (this->Gradation ? "on" : "off") << "\n";
  os << indent << "GradationFactor: " << this->GradationFactor << "\n";
  os << indent << "AdaptBackgroundMesh: " << this->AdaptBackgroundMesh << "\n";
  os << indent << "BackgroundEdgeLength: " << this->BackgroundEdgeLength << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
}
