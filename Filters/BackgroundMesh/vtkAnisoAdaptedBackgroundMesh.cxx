// SPDX-License-Identifier: BSD-3-Clause
// vtkAnisoAdaptedBackgroundMesh: converts the mesh and metric, runs AdaptBackgroundMesh, and
// builds the adapted mesh with the input's point data carried through the parent weights.
#include "vtkAnisoAdaptedBackgroundMesh.h"

#include "MetricAdaptedMesh.h"
#include "vtkAnisoDataConversion.h"
#include "vtkAnisoFilterUtilities.h"

#include <vtkCellData.h>
#include <vtkDataSet.h>
#include <vtkDataSetAttributes.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkIdTypeArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>

#include <string>

vtkStandardNewMacro(vtkAnisoAdaptedBackgroundMesh);

namespace
{
av::AdaptedMeshOptions MakeOptions(vtkAnisoAdaptedBackgroundMesh* self)
{
  av::AdaptedMeshOptions o;
  o.NumberOfSites = self->GetNumberOfSites();
  o.TargetLength = self->GetTargetEdgeLength();
  o.CollapseRatio = self->GetCollapseRatio();
  o.Refine = self->GetRefine();
  o.Coarsen = self->GetCoarsen();
  o.FeatureAngle = self->GetFeatureAngle();
  o.SurfaceDeviationAngle = self->GetSurfaceDeviationAngle();
  o.MinQuality = self->GetMinimumQuality();
  o.MaxPoints = static_cast<std::size_t>(self->GetMaximumNumberOfPoints());
  return o;
}

/// Point data through the parent weights, the metric array replaced by the kernel's (SPD)
/// values, cell data from the parent cells, field data from the input.
void BuildOutput(vtkDataSet* input,
  vtkDataArray* metricArray,
  const av::AdaptedMeshResult& r,
  vtkUnstructuredGrid* output)
{
  output->ShallowCopy(vtkAnisoDataConversion::FromSimplexMesh(r.Mesh));
  const vtkIdType np = static_cast<vtkIdType>(r.Mesh.NumPoints());
  vtkPointData* inPD = input->GetPointData();
  vtkPointData* outPD = output->GetPointData();
  outPD->InterpolateAllocate(inPD, np);
  vtkNew<vtkIdList> ids;
  double w[4];
  for (vtkIdType i = 0; i < np; ++i)
  {
    ids->SetNumberOfIds(0);
    int n = 0;
    for (int k = 0; k < 4; ++k)
    {
      const std::int32_t id = r.ParentIds[4 * i + k];
      if (id >= 0)
      {
        ids->InsertNextId(id);
        w[n++] = r.ParentWeights[4 * i + k];
      }
    }
    outPD->InterpolatePoint(inPD, i, ids, w);
  }
  vtkDataArray* outMetric = outPD->GetArray(metricArray->GetName());
  if (outMetric && outMetric->GetNumberOfComponents() == metricArray->GetNumberOfComponents())
  {
    const bool full = outMetric->GetNumberOfComponents() == 9;
    for (vtkIdType i = 0; i < np; ++i)
    {
      const double* m = r.Metric.At(static_cast<std::size_t>(i));
      if (full)
      {
        const double t[9] = { m[0], m[3], m[5], m[3], m[1], m[4], m[5], m[4], m[2] };
        outMetric->SetTuple(i, t);
      }
      else
        outMetric->SetTuple(i, m);
    }
    outPD->SetActiveTensors(metricArray->GetName());
  }
  const vtkIdType nc = static_cast<vtkIdType>(r.Mesh.NumCells());
  vtkCellData* inCD = input->GetCellData();
  vtkCellData* outCD = output->GetCellData();
  outCD->CopyAllocate(inCD, nc);
  vtkNew<vtkIdTypeArray> parents;
  parents->SetName("ParentCellId");
  parents->SetNumberOfTuples(nc);
  for (vtkIdType c = 0; c < nc; ++c)
  {
    outCD->CopyData(inCD, r.CellParent[c], c);
    parents->SetValue(c, r.CellParent[c]);
  }
  outCD->AddArray(parents);
  output->GetFieldData()->ShallowCopy(input->GetFieldData());
  // A new mesh: the input's feature edges and corners (point ids) do not apply to it.
  vtkAnisoDataConversion::RemoveFeatureFieldData(output->GetFieldData());
}

/// The input as an AdaptBackgroundMesh result with nothing changed (each point its own parent).
av::AdaptedMeshResult IdentityResult(av::SimplexMesh mesh, av::MetricField metric)
{
  av::AdaptedMeshResult r;
  const std::size_t np = mesh.NumPoints(), nc = mesh.NumCells();
  r.ParentIds.assign(4 * np, -1);
  r.ParentWeights.assign(4 * np, 0.0);
  for (std::size_t i = 0; i < np; ++i)
  {
    r.ParentIds[4 * i] = static_cast<std::int32_t>(i);
    r.ParentWeights[4 * i] = 1.0;
  }
  r.CellParent.resize(nc);
  for (std::size_t c = 0; c < nc; ++c)
    r.CellParent[c] = static_cast<std::int32_t>(c);
  r.Mesh = std::move(mesh);
  r.Metric = std::move(metric);
  return r;
}
}

vtkAnisoAdaptedBackgroundMesh::vtkAnisoAdaptedBackgroundMesh()
{
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::TENSORS);
}

int vtkAnisoAdaptedBackgroundMesh::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  return 1;
}

int vtkAnisoAdaptedBackgroundMesh::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  vtkAnisoDataConversion::RequestWholeInputs(inputVector, this->GetNumberOfInputPorts());
  return 1;
}

int vtkAnisoAdaptedBackgroundMesh::RequestData(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0]);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector);
  if (vtkAnisoDataConversion::NothingToCompute(request, outputVector, input))
  {
    return 1; // not this piece, or empty in: empty out
  }
  av::SimplexMesh mesh;
  av::MetricField metric;
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
  int association = -1;
  vtkDataArray* chosen = this->GetInputArrayToProcess(0, inputVector, association);
  vtkDataArray* metricArray =
    vtkAnisoDataConversion::FindPointTensorArray(chosen, association, input);
  if (!vtkAnisoDataConversion::ToMetricField(metricArray, mesh.NumPoints(), metric, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  this->UpdateProgress(0.05);
  av::BackgroundResolution given;
  if (!vtkAnisoFilterUtilities::RunKernel(this,
        "background resolution",
        [&] {
          given = av::MeasureBackgroundResolution(
            mesh, metric, this->NumberOfSites, this->TargetEdgeLength);
        }))
  {
    return 0;
  }
  this->InputMeanEdgeLength = given.MeanEdgeLength;
  this->Adapted = !this->OnlyWhenCoarse || av::CoarserThanOutput(given);
  using vtkAnisoFilterUtilities::AddFieldValue;
  if (!this->Adapted)
  {
    // Fine enough already: the input mesh as it is (same points, cells and data).
    BuildOutput(input, metricArray, IdentityResult(std::move(mesh), std::move(metric)), output);
    output->GetFieldData()->ShallowCopy(input->GetFieldData());
    AddFieldValue(output->GetFieldData(), "BackgroundAdapted", 0.0);
    AddFieldValue(output->GetFieldData(), "BackgroundInputMeanEdgeLength", given.MeanEdgeLength);
    this->NumberOfSplits = this->NumberOfCollapses = 0;
    this->Seconds = 0.0;
    this->UpdateProgress(1.0);
    return 1;
  }
  av::AdaptedMeshResult r;
  if (!vtkAnisoFilterUtilities::RunKernel(this,
        "background mesh adaptation",
        [&] { r = av::AdaptBackgroundMesh(mesh, metric, MakeOptions(this)); }))
  {
    return 0;
  }
  if (r.HitPointLimit)
  {
    vtkWarningMacro("refinement stopped at MaximumNumberOfPoints ("
      << this->MaximumNumberOfPoints << "): some edges are still longer than the target (longest "
      << r.MaxEdgeLength << " output edges)");
  }
  this->UpdateProgress(0.8);
  BuildOutput(input, metricArray, r, output);
  this->MetricScale = r.MetricScale;
  this->MaxEdgeLength = r.MaxEdgeLength;
  this->NumberOfSplits = static_cast<vtkIdType>(r.NumSplits);
  this->NumberOfCollapses = static_cast<vtkIdType>(r.NumCollapses);
  this->Seconds = r.Seconds;
  vtkFieldData* fd = output->GetFieldData();
  AddFieldValue(fd, "BackgroundAdapted", 1.0);
  AddFieldValue(fd, "BackgroundInputMeanEdgeLength", given.MeanEdgeLength);
  AddFieldValue(fd, "BackgroundMetricScale", r.MetricScale);
  AddFieldValue(fd, "BackgroundMaxEdgeLength", r.MaxEdgeLength);
  AddFieldValue(fd, "BackgroundMeanEdgeLength", r.MeanEdgeLength);
  AddFieldValue(fd, "BackgroundSplits", static_cast<double>(r.NumSplits));
  AddFieldValue(fd, "BackgroundCollapses", static_cast<double>(r.NumCollapses));
  AddFieldValue(fd, "BackgroundInputPoints", static_cast<double>(mesh.NumPoints()));
  AddFieldValue(fd, "BackgroundSeconds", r.Seconds);
  this->UpdateProgress(1.0);
  return 1;
}

void vtkAnisoAdaptedBackgroundMesh::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfSites: " << this->NumberOfSites << "\n";
  os << indent << "TargetEdgeLength: " << this->TargetEdgeLength << "\n";
  os << indent << "OnlyWhenCoarse: " << this->OnlyWhenCoarse << "\n";
  os << indent << "CollapseRatio: " << this->CollapseRatio << "\n";
  os << indent << "Refine: " << this->Refine << "\n";
  os << indent << "Coarsen: " << this->Coarsen << "\n";
  os << indent << "FeatureAngle: " << this->FeatureAngle << "\n";
  os << indent << "SurfaceDeviationAngle: " << this->SurfaceDeviationAngle << "\n";
  os << indent << "MinimumQuality: " << this->MinimumQuality << "\n";
  os << indent << "MaximumNumberOfPoints: " << this->MaximumNumberOfPoints << "\n";
}
