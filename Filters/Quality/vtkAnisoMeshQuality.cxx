// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAnisoMeshQuality.h"

#include "MeshQuality.h"
#include "SurfaceFidelity.h"
#include "vtkAnisoDataConversion.h"
#include "vtkAnisoFilterUtilities.h"

#include <vtkCellData.h>
#include <vtkDataSet.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkTable.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

vtkStandardNewMacro(vtkAnisoMeshQuality);

namespace
{
/// The input's simplices (vertex / line cells dropped) on its exact points, with its point,
/// cell and field data, and the per-cell quality arrays.
void WriteQualityMesh(vtkDataSet* input,
  const av::SimplexMesh& mesh,
  const av::MeshQualityResult& q,
  vtkUnstructuredGrid* output)
{
  vtkAnisoDataConversion::CopySimplicesWithInputData(input, mesh, output);
  const std::size_t nc = mesh.NumCells();
  output->GetCellData()->AddArray(vtkAnisoDataConversion::MakeArray("G", q.G.data(), nc, 1));
  output->GetCellData()->AddArray(
    vtkAnisoDataConversion::MakeArray("MinAngle", q.MinAngle.data(), nc, 1));
  vtkNew<vtkUnsignedCharArray> inverted;
  inverted->SetName("Inverted");
  inverted->SetNumberOfTuples(static_cast<vtkIdType>(nc));
  std::copy(q.Inverted.begin(), q.Inverted.end(), inverted->GetPointer(0));
  output->GetCellData()->AddArray(inverted);
  output->GetCellData()->SetActiveScalars("G");
}

/// The fidelity figures of a triangle surface as field data (and cell data "Flipped").
void WriteSurfaceFidelity(const av::SurfaceFidelityResult& f, vtkUnstructuredGrid* output)
{
  using vtkAnisoFilterUtilities::AddFieldValue;
  vtkFieldData* fd = output->GetFieldData();
  AddFieldValue(fd, "euler", static_cast<double>(f.Topology.Euler));
  AddFieldValue(fd, "boundary_loops", static_cast<double>(f.Topology.BoundaryLoops));
  AddFieldValue(fd, "nonmanifold_edges", static_cast<double>(f.Topology.NonManifoldEdges));
  AddFieldValue(fd, "components", static_cast<double>(f.Topology.Components));
  AddFieldValue(fd, "self_intersections", static_cast<double>(f.SelfIntersections));
  if (!f.HasReference)
    return;
  const av::HausdorffResult& h = f.Hausdorff;
  const double toPercent = h.Diagonal > 0.0 ? 100.0 / h.Diagonal : 0.0;
  AddFieldValue(fd, "hausdorff", h.MaxPercent);
  AddFieldValue(fd, "hausdorff_to_input", toPercent * h.ForwardMax);
  AddFieldValue(fd, "hausdorff_from_input", toPercent * h.BackwardMax);
  AddFieldValue(fd, "flipped", static_cast<double>(f.Flipped));
  AddFieldValue(fd, "input_euler", static_cast<double>(f.ReferenceTopology.Euler));
  AddFieldValue(fd, "input_boundary_loops", static_cast<double>(f.ReferenceTopology.BoundaryLoops));
  vtkNew<vtkUnsignedCharArray> flipped;
  flipped->SetName("Flipped");
  flipped->SetNumberOfTuples(static_cast<vtkIdType>(f.FlippedFlags.size()));
  std::copy(f.FlippedFlags.begin(), f.FlippedFlags.end(), flipped->GetPointer(0));
  output->GetCellData()->AddArray(flipped);
}

/// The angle histogram: bin centers (degrees) and counts.
void WriteHistogram(const av::MeshQualitySummary& s, vtkTable* histogram)
{
  vtkNew<vtkDoubleArray> center;
  center->SetName("MinAngle");
  vtkNew<vtkIntArray> count;
  count->SetName("Count");
  for (std::size_t b = 0; b < s.AngleHistogram.size(); ++b)
  {
    center->InsertNextValue((static_cast<double>(b) + 0.5) * s.HistogramBinWidth);
    count->InsertNextValue(static_cast<int>(s.AngleHistogram[b]));
  }
  histogram->AddColumn(center);
  histogram->AddColumn(count);
}
}

vtkAnisoMeshQuality::vtkAnisoMeshQuality()
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(2);
  // Default: the active point tensors (FindPointTensorArray then falls back to "Metric").
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::TENSORS);
}

int vtkAnisoMeshQuality::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  if (port == 1)
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

int vtkAnisoMeshQuality::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkUnstructuredGrid" : "vtkTable");
  return 1;
}

int vtkAnisoMeshQuality::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  vtkAnisoDataConversion::RequestWholeInputs(inputVector, this->GetNumberOfInputPorts());
  return 1;
}

int vtkAnisoMeshQuality::RequestData(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0]);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector, 0);
  vtkTable* histogram = vtkTable::GetData(outputVector, 1);
  if (vtkAnisoDataConversion::NothingToCompute(request, outputVector, input))
  {
    return 1; // not this piece, or empty in: empty out
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
  av::MeshQualityResult q;
  if (!vtkAnisoFilterUtilities::RunKernel(
        this, "mesh quality", [&] { q = av::EvaluateMeshQuality(mesh, metric); }))
  {
    return 0;
  }
  WriteQualityMesh(input, mesh, q, output);
  if (!this->RunSurfaceFidelity(mesh, inputVector, output))
  {
    return 0;
  }

  const av::MeshQualitySummary& s = q.Summary;
  this->GMin = s.GMin;
  this->GAvg = s.GAvg;
  this->ThetaMin = s.ThetaMin;
  this->ThetaAvg = s.ThetaAvg;
  this->PercentBad = s.PercentBad;
  vtkFieldData* fd = output->GetFieldData();
  using vtkAnisoFilterUtilities::AddFieldValue;
  AddFieldValue(fd, "G_min", s.GMin);
  AddFieldValue(fd, "G_avg", s.GAvg);
  AddFieldValue(fd, "theta_min", s.ThetaMin);
  AddFieldValue(fd, "theta_avg", s.ThetaAvg);
  AddFieldValue(fd, "pct_bad", s.PercentBad);
  AddFieldValue(fd, "inverted", static_cast<double>(s.NumInverted));
  AddFieldValue(fd, "edges_in_unit_range", s.PercentEdgesInUnitRange);
  AddFieldValue(fd, "NumberOfCells", static_cast<double>(s.NumCells));
  WriteHistogram(s, histogram);
  return 1;
}

bool vtkAnisoMeshQuality::RunSurfaceFidelity(const av::SimplexMesh& mesh,
  vtkInformationVector** inputVector,
  vtkUnstructuredGrid* output)
{
  this->HausdorffPercent = -1.0;
  this->NumberOfSelfIntersections = -1;
  this->NumberOfFlipped = -1;
  vtkDataSet* referenceInput = inputVector[1]->GetNumberOfInformationObjects() > 0
    ? vtkDataSet::GetData(inputVector[1])
    : nullptr;
  const bool surface = mesh.SimplexDim == 2 && mesh.AmbientDim == 3;
  if (!this->SurfaceFidelity)
  {
    return true;
  }
  if (!surface)
  {
    if (referenceInput)
      vtkWarningMacro(<< "the reference surface is ignored: the fidelity measures are for "
                         "triangle surfaces in 3D, and this mesh is "
                      << (mesh.SimplexDim == 3 ? "tetrahedral" : "a flat 2D domain"));
    return true;
  }
  av::SimplexMesh reference;
  const bool hasReference = referenceInput && referenceInput->GetNumberOfCells() > 0;
  if (referenceInput && !hasReference)
  {
    vtkErrorMacro(<< "the reference surface (input 1) is empty");
    return false;
  }
  if (hasReference)
  {
    std::string error;
    if (!vtkAnisoDataConversion::ToSimplexMesh(referenceInput, reference, error))
    {
      vtkErrorMacro(<< "reference surface (input 1): " << error);
      return false;
    }
    if (reference.SimplexDim != 2 || reference.AmbientDim != 3)
    {
      vtkErrorMacro(<< "reference surface (input 1): needs a triangle surface in 3D, got "
                    << (reference.SimplexDim == 3 ? "tetrahedra" : "a flat 2D domain"));
      return false;
    }
  }
  av::SurfaceFidelityResult f;
  if (!vtkAnisoFilterUtilities::RunKernel(this,
        "surface fidelity",
        [&]
        {
          f = av::EvaluateSurfaceFidelity(
            mesh, hasReference ? &reference : nullptr, this->HausdorffSamplesPerEdge);
        }))
  {
    return false;
  }
  WriteSurfaceFidelity(f, output);
  this->NumberOfSelfIntersections = static_cast<vtkIdType>(f.SelfIntersections);
  if (f.HasReference)
  {
    this->HausdorffPercent = f.Hausdorff.MaxPercent;
    this->NumberOfFlipped = static_cast<vtkIdType>(f.Flipped);
  }
  return true;
}

void vtkAnisoMeshQuality::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "G_min / G_avg (last run): " << this->GMin << " / " << this->GAvg << "\n";
  os << indent << "theta_min / theta_avg (last run): " << this->ThetaMin << " / " << this->ThetaAvg
     << "\n";
  os << indent << "PercentBad (last run): " << this->PercentBad << "\n";
  os << indent << "SurfaceFidelity: " << (this->SurfaceFidelity ? "On" : "Off") << "\n";
  os << indent << "HausdorffSamplesPerEdge: " << this->HausdorffSamplesPerEdge << "\n";
  os << indent << "HausdorffPercent (last run): " << this->HausdorffPercent << "\n";
  os << indent << "NumberOfSelfIntersections (last run): " << this->NumberOfSelfIntersections
     << "\n";
  os << indent << "NumberOfFlipped (last run): " << this->NumberOfFlipped << "\n";
}
