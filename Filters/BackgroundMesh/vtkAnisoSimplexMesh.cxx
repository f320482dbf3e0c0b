#include "vtkAnisoSimplexMesh.h"

#include "SimplexSplitter.h"

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

  // Census of cell types.
  vtkIdType ignored = 0, triangles = 0, tetras = 0, others = 0;
  bool polygons = false;
  for (vtkIdType c = 0; c < numCells; ++c)
  {
    const int type = input->GetCellType(c);
    if (IsIgnored(type))
      ++ignored;
    else if (type == VTK_TRIANGLE)
      ++triangles;
    else if (type == VTK_TETRA)
      ++tetras;
    else
    {
      ++others;
      polygons = polygons || type == VTK_POLYGON || type == VTK_TRIANGLE_STRIP;
    }
  }
  if (ignored == numCells)
  {
    vtkErrorMacro("the input has only vertex/line cells: nothing to split into simplices");
    return 0;
  }
  if (ignored > 0)
  {
    vtkWarningMacro(<< ignored << " vertex/line cell(s) were ignored");
  }

  vtkNew<vtkIdTypeArray> parentIds;
  parentIds->SetName("ParentCellId");

  // Already simplicial: pass through with the same points and ids.
  if (others == 0 && (triangles == 0 || tetras == 0))
  {
    if (ignored == 0 && input->IsA("vtkUnstructuredGrid"))
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
      output->AllocateExact(numCells - ignored, tetras > 0 ? 4 : 3);
      output->GetCellData()->CopyAllocate(input->GetCellData(), numCells - ignored);
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
    parentIds->SetNumberOfTuples(output->GetNumberOfCells());
    for (vtkIdType c = 0, k = 0; c < numCells; ++c)
    {
      if (!IsIgnored(input->GetCellType(c)))
        parentIds->SetValue(k++, c);
    }
    output->GetCellData()->AddArray(parentIds);
    this->NumberOfOutputSimplices = output->GetNumberOfCells();
    std::ostringstream os;
    os << "nothing split: the input is already " << (tetras > 0 ? "tetrahedra" : "triangles")
       << " (" << this->NumberOfOutputSimplices << " cells)";
    this->SplitSummary = os.str();
    AddSummary(output->GetFieldData(), this->SplitSummary);
    return 1;
  }

  // VTK layout of the cells handed to the kernel (vertex/line cells left out).
  std::vector<double> coords(static_cast<std::size_t>(numPoints) * 3);
  for (vtkIdType i = 0; i < numPoints; ++i)
    input->GetPoint(i, coords.data() + 3 * i);
  std::vector<std::uint8_t> types;
  std::vector<std::int64_t> offsets{ 0 };
  std::vector<std::int64_t> connectivity;
  std::vector<vtkIdType> kernelToInput;
  types.reserve(numCells);
  kernelToInput.reserve(numCells);
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < numCells; ++c)
  {
    const int type = input->GetCellType(c);
    if (IsIgnored(type))
      continue;
    input->GetCellPoints(c, ids);
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
      connectivity.push_back(ids->GetId(k));
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    types.push_back(static_cast<std::uint8_t>(type));
    kernelToInput.push_back(c);
  }
  this->UpdateProgress(0.2);
  if (this->GetAbortExecute())
  {
    return 1;
  }

  av::SimplexSplitResult split;
  try
  {
    split = av::SplitIntoSimplices(coords.data(),
      static_cast<std::size_t>(numPoints),
      types.data(),
      offsets.data(),
      connectivity.data(),
      types.size(),
      3);
  }
  catch (const av::InputError& e)
  {
    vtkErrorMacro(<< e.what()
                  << (polygons ? " (triangulate polygons and strips first with "
                                 "vtkTriangleFilter, ParaView: Triangulate)"
                               : ""));
    return 0;
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("splitting into simplices failed: " << e.what());
    return 0;
  }
  this->UpdateProgress(0.6);

  // Points and point data (added points interpolated with their parent weights).
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

  // Cells and cell data (copied from the parent cell).
  const vtkIdType numSimplices = static_cast<vtkIdType>(mesh.NumCells());
  const int nv = mesh.VerticesPerCell();
  const int cellType = mesh.SimplexDim == 3 ? VTK_TETRA : VTK_TRIANGLE;
  output->AllocateExact(numSimplices, nv);
  vtkCellData* inCD = input->GetCellData();
  vtkCellData* outCD = output->GetCellData();
  outCD->CopyAllocate(inCD, numSimplices);
  parentIds->SetNumberOfTuples(numSimplices);
  std::map<int, vtkIdType> splitCellsByType;
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
  for (std::size_t k = 0; k < types.size(); ++k)
  {
    if (types[k] != VTK_TRIANGLE && types[k] != VTK_TETRA)
      ++splitCellsByType[types[k]];
  }

  // The summary.
  this->NumberOfSplitCells = others;
  this->NumberOfOutputSimplices = numSimplices;
  this->NumberOfAddedPoints = static_cast<vtkIdType>(split.NumAddedPoints);
  const vtkIdType dropped = numPoints - (numOut - this->NumberOfAddedPoints);
  std::ostringstream os;
  os << "split ";
  bool first = true;
  for (const auto& kv : splitCellsByType)
  {
    os << (first ? "" : ", ") << kv.second << " " << PluralName(kv.first);
    first = false;
  }
  os << " into " << piecesOfSplitCells << " "
     << (mesh.SimplexDim == 3 ? "tetrahedra" : "triangles");
  os << " (" << split.NumAddedPoints << " centre points added";
  if (dropped > 0)
    os << ", " << dropped << " unused or mid-edge points dropped";
  if (split.NumDroppedSimplices > 0)
    os << ", " << split.NumDroppedSimplices << " zero-measure pieces dropped";
  os << ")";
  if (triangles + tetras > 0)
    os << "; " << (triangles + tetras) << " simplices kept";
  this->SplitSummary = os.str();
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
