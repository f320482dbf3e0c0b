// SPDX-License-Identifier: BSD-3-Clause
// vtkAnisoRestrictedVoronoi: converts the inputs, runs the RVD and cell kernels
// (RestrictedVoronoi, RestrictedVoronoiCells) and turns the cells into VTK data sets.
#include "vtkAnisoRestrictedVoronoi.h"

#include "RestrictedVoronoi.h"
#include "RestrictedVoronoiCells.h"
#include "Stopwatch.h"
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
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkAnisoRestrictedVoronoi);

namespace
{
/// A named cell-data array from per-cell (or per-face) values.
template <class ArrayT, class T>
void AddCellArray(vtkDataSet* ds, const char* name, const std::vector<T>& values)
{
  vtkNew<ArrayT> a;
  a->SetName(name);
  a->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i)
    a->SetValue(static_cast<vtkIdType>(i), static_cast<typename ArrayT::ValueType>(values[i]));
  ds->GetCellData()->AddArray(a);
}

/// The cells' points (shared by both outputs).
vtkSmartPointer<vtkPoints> MakePoints(const av::RestrictedVoronoiCells& cells)
{
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(cells.NumPoints()));
  std::copy(cells.Points.begin(), cells.Points.end(),
    static_cast<vtkDoubleArray*>(points->GetData())->GetPointer(0));
  return points;
}

/// Output 0: VTK_POLYHEDRON (3D, with their face streams) or VTK_POLYGON (2D) cells with SiteId,
/// Measure, EmbeddedMeasure and, when some cells are element pieces, ElementId.
void FillCellOutput(const av::RestrictedVoronoiCells& cells, vtkPoints* points, vtkUnstructuredGrid* output)
{
  const bool volume = cells.SimplexDim == 3;
  const std::size_t nc = cells.NumCells();
  vtkNew<vtkCellArray> cellArray;
  vtkNew<vtkIdTypeArray> faceStream, faceLocations;
  vtkNew<vtkUnsignedCharArray> types;
  types->SetNumberOfTuples(static_cast<vtkIdType>(nc));
  std::vector<vtkIdType> ids;
  for (std::size_t c = 0; c < nc; ++c)
  {
    if (volume)
    {
      ids.clear();
      for (std::int64_t i = cells.CellPointOffsets[c]; i < cells.CellPointOffsets[c + 1]; ++i)
        ids.push_back(i);
      cellArray->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
      faceLocations->InsertNextValue(faceStream->GetNumberOfTuples());
      const std::int64_t f0 = cells.CellFaceOffsets[c], f1 = cells.CellFaceOffsets[c + 1];
      faceStream->InsertNextValue(f1 - f0);
      for (std::int64_t f = f0; f < f1; ++f)
      {
        faceStream->InsertNextValue(cells.FaceOffsets[f + 1] - cells.FaceOffsets[f]);
        for (std::int64_t i = cells.FaceOffsets[f]; i < cells.FaceOffsets[f + 1]; ++i)
          faceStream->InsertNextValue(cells.FaceVertices[i]);
      }
      types->SetValue(static_cast<vtkIdType>(c), VTK_POLYHEDRON);
    }
    else
    {
      const std::int64_t l0 = cells.CellLoopOffsets[c], l1 = cells.CellLoopOffsets[c + 1];
      ids.assign(cells.LoopPoints.begin() + l0, cells.LoopPoints.begin() + l1);
      cellArray->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
      types->SetValue(static_cast<vtkIdType>(c), VTK_POLYGON);
    }
  }
  output->SetPoints(points);
  if (volume)
    output->SetCells(types, cellArray, faceLocations, faceStream);
  else
    output->SetCells(types, cellArray);
  AddCellArray<vtkIntArray>(output, "SiteId", cells.CellSite);
  output->GetCellData()->SetActiveScalars("SiteId");
  AddCellArray<vtkDoubleArray>(output, "Measure", cells.CellMeasure);
  AddCellArray<vtkDoubleArray>(output, "EmbeddedMeasure", cells.CellEmbeddedMeasure);
  // ElementId only names something for element pieces; merged cells would carry -1 only.
  if (std::any_of(
        cells.CellElement.begin(), cells.CellElement.end(), [](std::int32_t e) { return e >= 0; }))
    AddCellArray<vtkIntArray>(output, "ElementId", cells.CellElement);
}

/// Output 1: the faces (polygons) or edges (lines) of every cell with SiteId, FaceKind,
/// NeighborSiteId.
void FillFaceOutput(const av::RestrictedVoronoiCells& cells, vtkPoints* points, vtkPolyData* faces)
{
  vtkNew<vtkCellArray> polys;
  std::vector<vtkIdType> ids;
  std::vector<int> site(cells.NumFaces());
  for (std::size_t c = 0; c < cells.NumCells(); ++c)
    for (std::int64_t f = cells.CellFaceOffsets[c]; f < cells.CellFaceOffsets[c + 1]; ++f)
    {
      ids.assign(cells.FaceVertices.begin() + cells.FaceOffsets[f],
        cells.FaceVertices.begin() + cells.FaceOffsets[f + 1]);
      polys->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
      site[f] = cells.CellSite[c];
    }
  faces->SetPoints(points);
  if (cells.SimplexDim == 3)
    faces->SetPolys(polys);
  else
    faces->SetLines(polys);
  AddCellArray<vtkIntArray>(faces, "SiteId", site);
  AddCellArray<vtkIntArray>(faces, "FaceKind", cells.FaceKind);
  faces->GetCellData()->SetActiveScalars("FaceKind");
  AddCellArray<vtkIntArray>(faces, "NeighborSiteId", cells.FaceNeighbor);
}
} // namespace

vtkAnisoRestrictedVoronoi::vtkAnisoRestrictedVoronoi()
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(2);
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Embedding");
}

void vtkAnisoRestrictedVoronoi::SetSourceConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(1, output);
}

int vtkAnisoRestrictedVoronoi::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  return 1;
}

int vtkAnisoRestrictedVoronoi::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkUnstructuredGrid" : "vtkPolyData");
  return 1;
}

int vtkAnisoRestrictedVoronoi::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // Every process needs the whole mesh and all sites; only the clipping work is split.
  vtkAnisoDataConversion::RequestWholeInputs(inputVector, this->GetNumberOfInputPorts());
  return 1;
}

int vtkAnisoRestrictedVoronoi::RequestData(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0]);
  vtkDataSet* sitesInput = vtkDataSet::GetData(inputVector[1]);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector, 0);
  vtkPolyData* faces = vtkPolyData::GetData(outputVector, 1);
  if (!input || input->GetNumberOfPoints() == 0 || input->GetNumberOfCells() == 0 || !sitesInput ||
    sitesInput->GetNumberOfPoints() == 0)
  {
    return 1; // empty in, empty out
  }
  const av::Stopwatch filterTime;

  av::SimplexMesh mesh;
  av::Embedding embedding;
  av::SiteSet sites;
  std::string error, note;
  if (!vtkAnisoDataConversion::ToVoronoiInputs(input, this->GetInputArrayToProcess(0, inputVector),
        sitesInput, mesh, embedding, sites, error, &note))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  if (!note.empty())
  {
    vtkWarningMacro(<< note);
  }
  this->UpdateProgress(0.1);

  av::RestrictedVoronoiOptions options;
  options.ComputeGeometry = true;
  options.KeepEmbeddedPoints = false;
  options.MergeBySite = this->MergeBySite;
  // Distributed run: this piece clips one contiguous block of elements.
  int piece = 0, numberOfPieces = 1;
  vtkAnisoDataConversion::RequestedPiece(request, outputVector, piece, numberOfPieces);
  const std::int64_t numberOfElements = static_cast<std::int64_t>(mesh.NumCells());
  options.ElementBegin = numberOfElements * piece / numberOfPieces;
  options.ElementEnd = numberOfElements * (piece + 1) / numberOfPieces;
  av::RestrictedVoronoiDiagram rvd;
  double kernelSeconds = 0.0;
  if (!vtkAnisoFilterUtilities::RunKernel(this, "restricted Voronoi diagram", [&] {
        av::ValidateRestrictedVoronoiInput(mesh, embedding, sites);
        const av::Stopwatch kernelTime;
        rvd = av::ComputeRestrictedVoronoi(mesh, embedding, sites, options);
        kernelSeconds = kernelTime.Seconds();
      }))
  {
    return 0;
  }
  if (this->GetAbortExecute())
  {
    return 1;
  }
  this->UpdateProgress(0.6);

  av::RestrictedVoronoiCellOptions cellOptions;
  cellOptions.MergeBySite = this->MergeBySite;
  cellOptions.ShrinkFactor = this->ShrinkFactor;
  cellOptions.Abort = [this] { return this->GetAbortExecute() != 0; };
  av::RestrictedVoronoiCells cells;
  if (!vtkAnisoFilterUtilities::RunKernel(this, "restricted Voronoi cells",
        [&] { cells = av::BuildRestrictedVoronoiCells(mesh, rvd, cellOptions); }))
  {
    return 0;
  }
  this->UpdateProgress(0.9);

  const vtkSmartPointer<vtkPoints> points = MakePoints(cells);
  FillCellOutput(cells, points, output);
  FillFaceOutput(cells, points, faces);
  const double total = cells.TotalMeasure, domain = cells.DomainMeasure;
  this->TotalMeasure = total;
  this->DomainMeasure = domain;
  const double seconds = filterTime.Seconds();
  const std::size_t nonEmpty = cells.NumNonEmptySites;
  for (vtkDataObject* o :
    { static_cast<vtkDataObject*>(output), static_cast<vtkDataObject*>(faces) })
  {
    using vtkAnisoFilterUtilities::AddFieldValue;
    vtkFieldData* fd = o->GetFieldData();
    AddFieldValue(fd, "TotalMeasure", total);
    AddFieldValue(fd, "DomainMeasure", domain);
    AddFieldValue(fd, "RelativeVolumeError", domain > 0 ? std::abs(total - domain) / domain : 0.0);
    AddFieldValue(fd, "NumberOfVoronoiCells", static_cast<double>(nonEmpty));
    AddFieldValue(fd, "NumberOfEmptySites", static_cast<double>(sites.NumSites() - nonEmpty));
    AddFieldValue(fd, "VoronoiKernelSeconds", kernelSeconds);
    AddFieldValue(fd, "VoronoiSeconds", seconds);
    AddFieldValue(fd, "PieceNumber", piece);
    AddFieldValue(fd, "NumberOfPieces", numberOfPieces);
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkAnisoRestrictedVoronoi::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MergeBySite: " << this->MergeBySite << "\n";
  os << indent << "ShrinkFactor: " << this->ShrinkFactor << "\n";
}
