// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAnisoSimplexMesh.h"

#include "SimplexSplitter.h"
#include "vtkAnisoDataConversion.h"
#include "vtkAnisoFilterUtilities.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataSet.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkIdTypeArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>
#include <map>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkAnisoSimplexMesh);

namespace
{
bool IsIgnored(int type)
{
  return type == VTK_EMPTY_CELL || type == VTK_VERTEX || type == VTK_POLY_VERTEX ||
    type == VTK_LINE || type == VTK_POLY_LINE || type == VTK_QUADRATIC_EDGE;
}

/// Plural, human name of a cell type for the summary.
std::string PluralName(int type)
{
  switch (type)
  {
    case VTK_TRIANGLE:
      return "triangles";
    case VTK_TETRA:
      return "tetrahedra";
    case VTK_QUAD:
      return "quads";
    case VTK_PIXEL:
      return "pixels";
    case VTK_HEXAHEDRON:
      return "hexahedra";
    case VTK_VOXEL:
      return "voxels";
    case VTK_WEDGE:
      return "wedges";
    case VTK_PYRAMID:
      return "pyramids";
    case VTK_QUADRATIC_TRIANGLE:
      return "quadratic triangles";
    case VTK_QUADRATIC_QUAD:
      return "quadratic quads";
    case VTK_QUADRATIC_TETRA:
      return "quadratic tetrahedra";
    case VTK_QUADRATIC_HEXAHEDRON:
      return "quadratic hexahedra";
    case VTK_QUADRATIC_WEDGE:
      return "quadratic wedges";
    case VTK_QUADRATIC_PYRAMID:
      return "quadratic pyramids";
    case VTK_BIQUADRATIC_QUAD:
      return "biquadratic quads";
    case VTK_TRIQUADRATIC_HEXAHEDRON:
      return "triquadratic hexahedra";
    default:
      return av::VtkCellTypeName(type) + " cells";
  }
}

void AddSummary(vtkFieldData* fd, const std::string& text)
{
  vtkNew<vtkStringArray> a;
  a->SetName("SplitSummary");
  a->InsertNextValue(text);
  fd->AddArray(a);
}

/// How many cells of each kind the input has.
struct CellCensus
{
  vtkIdType Ignored = 0, Triangles = 0, Tetras = 0, Others = 0;
  bool Polygons = false; ///< polygons or strips among the others (the kernel rejects them)
};

CellCensus CountCells(vtkDataSet* input)
{
  CellCensus n;
  for (vtkIdType c = 0; c < input->GetNumberOfCells(); ++c)
  {
    const int type = input->GetCellType(c);
    if (IsIgnored(type))
      ++n.Ignored;
    else if (type == VTK_TRIANGLE)
      ++n.Triangles;
    else if (type == VTK_TETRA)
      ++n.Tetras;
    else
    {
      ++n.Others;
      n.Polygons = n.Polygons || type == VTK_POLYGON || type == VTK_TRIANGLE_STRIP;
    }
  }
  return n;
}

/// An already simplicial input, passed through with the same points and ids (vertex and line
/// cells dropped); ParentCellId maps the output cells to the input's.
void PassThrough(vtkDataSet* input, const CellCensus& n, vtkUnstructuredGrid* output)
{
  const vtkIdType numPoints = input->GetNumberOfPoints();
  const vtkIdType numCells = input->GetNumberOfCells();
  if (n.Ignored == 0 && input->IsA("vtkUnstructuredGrid"))
  {
    output->ShallowCopy(input);
  }
  else
  {
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    points->SetNumberOfPoints(numPoints);
    for (vtkIdType i = 0; i < numPoints; ++i)
      points->SetPoint(i, input->GetPoint(i));
    output->SetPoints(points);
    output->GetPointData()->ShallowCopy(input->GetPointData());
    output->GetFieldData()->ShallowCopy(input->GetFieldData());
    output->AllocateExact(numCells - n.Ignored, n.Tetras > 0 ? 4 : 3);
    output->GetCellData()->CopyAllocate(input->GetCellData(), numCells - n.Ignored);
    vtkNew<vtkIdList> ids;
    for (vtkIdType c = 0; c < numCells; ++c)
    {
      const int type = input->GetCellType(c);
      if (IsIgnored(type))
        continue;
      input->GetCellPoints(c, ids);
      const vtkIdType out = output->InsertNextCell(type, ids);
      output->GetCellData()->CopyData(input->GetCellData(), c, out);
    }
  }
  vtkNew<vtkIdTypeArray> parentIds;
  parentIds->SetName("ParentCellId");
  parentIds->SetNumberOfTuples(output->GetNumberOfCells());
  for (vtkIdType c = 0, k = 0; c < numCells; ++c)
  {
    if (!IsIgnored(input->GetCellType(c)))
      parentIds->SetValue(k++, c);
  }
  output->GetCellData()->AddArray(parentIds);
}

/// The input cells in the kernel's VTK-like layout (vertex and line cells left out).
struct KernelCells
{
  std::vector<double> Coords;
  std::vector<std::uint8_t> Types;
  std::vector<std::int64_t> Offsets{ 0 };
  std::vector<std::int64_t> Connectivity;
  std::vector<vtkIdType> KernelToInput;
};

KernelCells ToKernelCells(vtkDataSet* input)
{
  const vtkIdType numPoints = input->GetNumberOfPoints();
  const vtkIdType numCells = input->GetNumberOfCells();
  KernelCells k;
  k.Coords.resize(static_cast<std::size_t>(numPoints) * 3);
  for (vtkIdType i = 0; i < numPoints; ++i)
    input->GetPoint(i, k.Coords.data() + 3 * i);
  k.Types.reserve(numCells);
  k.KernelToInput.reserve(numCells);
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < numCells; ++c)
  {
    const int type = input->GetCellType(c);
    if (IsIgnored(type))
      continue;
    input->GetCellPoints(c, ids);
    for (vtkIdType j = 0; j < ids->GetNumberOfIds(); ++j)
      k.Connectivity.push_back(ids->GetId(j));
    k.Offsets.push_back(static_cast<std::int64_t>(k.Connectivity.size()));
    k.Types.push_back(static_cast<std::uint8_t>(type));
    k.KernelToInput.push_back(c);
  }
  return k;
}

/// Points (added ones interpolated with their parent weights), cells and cell data (copied
/// from the parent) of the split mesh. Returns the number of simplices cut from non-simplices.
vtkIdType WriteSplitMesh(vtkDataSet* input,
  const av::SimplexSplitResult& split,
  const std::vector<vtkIdType>& kernelToInput,
  vtkUnstructuredGrid* output)
{
  const av::SimplexMesh& mesh = split.Mesh;
  const vtkIdType numOut = static_cast<vtkIdType>(mesh.NumPoints());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(numOut);
  for (vtkIdType i = 0; i < numOut; ++i)
    points->SetPoint(i, mesh.Point(static_cast<std::size_t>(i)));
  output->SetPoints(points);
  vtkPointData* inPD = input->GetPointData();
  vtkPointData* outPD = output->GetPointData();
  outPD->InterpolateAllocate(inPD, numOut);
  vtkNew<vtkIdList> parents;
  std::vector<double> weights;
  for (vtkIdType i = 0; i < numOut; ++i)
  {
    const std::int64_t b = split.PointParentOffsets[i];
    const std::int64_t e = split.PointParentOffsets[i + 1];
    parents->SetNumberOfIds(static_cast<vtkIdType>(e - b));
    weights.assign(split.PointWeights.begin() + b, split.PointWeights.begin() + e);
    for (std::int64_t k = b; k < e; ++k)
      parents->SetId(static_cast<vtkIdType>(k - b), split.PointParents[k]);
    outPD->InterpolatePoint(inPD, i, parents, weights.data());
  }
  output->GetFieldData()->ShallowCopy(input->GetFieldData());
  // Feature edges and corners name the input's point ids, which the split renumbers.
  vtkAnisoDataConversion::RemoveFeatureFieldData(output->GetFieldData());

  const vtkIdType numSimplices = static_cast<vtkIdType>(mesh.NumCells());
  const int nv = mesh.VerticesPerCell();
  const int cellType = mesh.SimplexDim == 3 ? VTK_TETRA : VTK_TRIANGLE;
  output->AllocateExact(numSimplices, nv);
  vtkCellData* inCD = input->GetCellData();
  vtkCellData* outCD = output->GetCellData();
  outCD->CopyAllocate(inCD, numSimplices);
  vtkNew<vtkIdTypeArray> parentIds;
  parentIds->SetName("ParentCellId");
  parentIds->SetNumberOfTuples(numSimplices);
  vtkIdType piecesOfSplitCells = 0;
  vtkIdType cellIds[4];
  for (vtkIdType c = 0; c < numSimplices; ++c)
  {
    const std::int32_t* cell = mesh.Cell(static_cast<std::size_t>(c));
    for (int k = 0; k < nv; ++k)
      cellIds[k] = cell[k];
    output->InsertNextCell(cellType, nv, cellIds);
    const vtkIdType parent = kernelToInput[split.CellParent[c]];
    outCD->CopyData(inCD, parent, c);
    parentIds->SetValue(c, parent);
    const int type = input->GetCellType(parent);
    if (type != VTK_TRIANGLE && type != VTK_TETRA)
      ++piecesOfSplitCells;
  }
  outCD->AddArray(parentIds);
  return piecesOfSplitCells;
}

/// "split 560 hexahedra into 3360 tetrahedra (... center points added ...)".
std::string SplitSummaryText(const std::vector<std::uint8_t>& types,
  const av::SimplexSplitResult& split,
  vtkIdType piecesOfSplitCells,
  vtkIdType dropped,
  vtkIdType keptSimplices)
{
  std::map<int, vtkIdType> splitCellsByType;
  for (std::uint8_t t : types)
  {
    if (t != VTK_TRIANGLE && t != VTK_TETRA)
      ++splitCellsByType[t];
  }
  std::ostringstream os;
  os << "split ";
  bool first = true;
  for (const auto& kv : splitCellsByType)
  {
    os << (first ? "" : ", ") << kv.second << " " << PluralName(kv.first);
    first = false;
  }
  os << " into " << piecesOfSplitCells << " "
     << (split.Mesh.SimplexDim == 3 ? "tetrahedra" : "triangles");
  os << " (" << split.NumAddedPoints << " center points added";
  if (dropped > 0)
    os << ", " << dropped << " unused or mid-edge points dropped";
  if (split.NumDroppedSimplices > 0)
    os << ", " << split.NumDroppedSimplices << " zero-measure pieces dropped";
  os << ")";
  if (keptSimplices > 0)
    os << "; " << keptSimplices << " simplices kept";
  return os.str();
}
}

vtkAnisoSimplexMesh::vtkAnisoSimplexMesh() = default;

int vtkAnisoSimplexMesh::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  return 1;
}

int vtkAnisoSimplexMesh::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0]);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector);
  this->SplitSummary.clear();
  this->NumberOfSplitCells = 0;
  this->NumberOfOutputSimplices = 0;
  this->NumberOfAddedPoints = 0;
  if (!input || !output || input->GetNumberOfPoints() == 0 || input->GetNumberOfCells() == 0)
  {
    return 1; // empty in, empty out
  }
  const vtkIdType numPoints = input->GetNumberOfPoints();
  const vtkIdType numCells = input->GetNumberOfCells();
  const CellCensus census = CountCells(input);
  if (census.Ignored == numCells)
  {
    vtkErrorMacro("the input has only vertex/line cells: nothing to split into simplices");
    return 0;
  }
  if (census.Ignored > 0)
  {
    vtkWarningMacro(<< census.Ignored << " vertex/line cell(s) were ignored");
  }
  if (census.Others == 0 && (census.Triangles == 0 || census.Tetras == 0))
  {
    PassThrough(input, census, output);
    this->NumberOfOutputSimplices = output->GetNumberOfCells();
    std::ostringstream os;
    os << "nothing split: the input is already " << (census.Tetras > 0 ? "tetrahedra" : "triangles")
       << " (" << this->NumberOfOutputSimplices << " cells)";
    this->SplitSummary = os.str();
    AddSummary(output->GetFieldData(), this->SplitSummary);
    return 1;
  }

  const KernelCells cells = ToKernelCells(input);
  this->UpdateProgress(0.2);
  if (this->GetAbortExecute())
  {
    return 1;
  }
  av::SimplexSplitResult split;
  if (!vtkAnisoFilterUtilities::RunKernel(this,
        "splitting into simplices",
        [&]
        {
          try
          {
            split = av::SplitIntoSimplices(cells.Coords.data(),
              static_cast<std::size_t>(numPoints),
              cells.Types.data(),
              cells.Offsets.data(),
              cells.Connectivity.data(),
              cells.Types.size(),
              3);
          }
          catch (const av::InputError& e)
          {
            throw av::InputError(std::string(e.what()) +
              (census.Polygons ? " (triangulate polygons and strips first with "
                                 "vtkTriangleFilter, ParaView: Triangulate)"
                               : ""));
          }
        }))
  {
    return 0;
  }
  this->UpdateProgress(0.6);

  const vtkIdType pieces = WriteSplitMesh(input, split, cells.KernelToInput, output);
  this->NumberOfSplitCells = census.Others;
  this->NumberOfOutputSimplices = static_cast<vtkIdType>(split.Mesh.NumCells());
  this->NumberOfAddedPoints = static_cast<vtkIdType>(split.NumAddedPoints);
  const vtkIdType dropped =
    numPoints - (static_cast<vtkIdType>(split.Mesh.NumPoints()) - this->NumberOfAddedPoints);
  this->SplitSummary =
    SplitSummaryText(cells.Types, split, pieces, dropped, census.Triangles + census.Tetras);
  AddSummary(output->GetFieldData(), this->SplitSummary);
  if (this->ReportSplit)
  {
    vtkWarningMacro(<< this->SplitSummary);
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkAnisoSimplexMesh::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ReportSplit: " << this->ReportSplit << "\n";
  os << indent << "SplitSummary: " << this->SplitSummary << "\n";
}
