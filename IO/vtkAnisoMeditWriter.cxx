// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAnisoMeditWriter.h"

#include "MeditBinaryIO.h"
#include "vtkAnisoDataConversion.h"
#include "vtkAnisoFilterUtilities.h"

#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkErrorCode.h>
#include <vtkIdList.h>
#include <vtkInformation.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>

#include <vector>

vtkStandardNewMacro(vtkAnisoMeditWriter);

vtkAnisoMeditWriter::vtkAnisoMeditWriter() = default;

int vtkAnisoMeditWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  return 1;
}

namespace
{
/// The tetrahedra (or, without them, the triangles) of `input` as Medit cells with their
/// references; with tetrahedra, triangles become boundary faces. Returns the skipped cells.
vtkIdType ToMeditCells(vtkDataSet* input, vtkDataArray* cellRefs, av::MeditMesh& m)
{
  const vtkIdType nc = input->GetNumberOfCells();
  bool hasTets = false;
  for (vtkIdType c = 0; c < nc && !hasTets; ++c)
  {
    hasTets = input->GetCellType(c) == VTK_TETRA;
  }
  m.Mesh.SimplexDim = hasTets ? 3 : 2;
  vtkIdType skipped = 0;
  auto pts = vtkSmartPointer<vtkIdList>::New();
  for (vtkIdType c = 0; c < nc; ++c)
  {
    const int type = input->GetCellType(c);
    const bool isTet = type == VTK_TETRA, isTri = type == VTK_TRIANGLE;
    if (!isTet && !isTri)
    {
      ++skipped;
      continue;
    }
    input->GetCellPoints(c, pts);
    const int ref = cellRefs ? static_cast<int>(cellRefs->GetComponent(c, 0)) : 0;
    std::vector<std::int32_t>& ids = (hasTets && isTri) ? m.Faces : m.Mesh.Cells;
    std::vector<std::int32_t>& refs = (hasTets && isTri) ? m.FaceRefs : m.CellRefs;
    for (vtkIdType j = 0; j < pts->GetNumberOfIds(); ++j)
    {
      ids.push_back(static_cast<std::int32_t>(pts->GetId(j)));
    }
    refs.push_back(ref);
  }
  return skipped;
}

/// The points in `dim` coordinates, with their references.
void ToMeditPoints(vtkDataSet* input, vtkDataArray* pointRefs, int dim, av::MeditMesh& m)
{
  const vtkIdType np = input->GetNumberOfPoints();
  m.Mesh.AmbientDim = dim;
  m.Mesh.Points.resize(static_cast<std::size_t>(np) * dim);
  m.PointRefs.resize(static_cast<std::size_t>(np));
  for (vtkIdType i = 0; i < np; ++i)
  {
    const double* p = input->GetPoint(i);
    std::copy(p, p + dim, m.Mesh.Points.data() + i * dim);
    m.PointRefs[i] = pointRefs ? static_cast<int>(pointRefs->GetComponent(i, 0)) : 0;
  }
}
}

void vtkAnisoMeditWriter::WriteData()
{
  vtkDataSet* input = vtkDataSet::SafeDownCast(this->GetInput());
  if (!input)
  {
    vtkErrorMacro("No vtkDataSet input.");
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return;
  }
  if (this->FileName.empty())
  {
    vtkErrorMacro("FileName is not set.");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return;
  }
  const vtkIdType np = input->GetNumberOfPoints();
  av::MeditMesh m;
  const vtkIdType skipped =
    ToMeditCells(input, input->GetCellData()->GetArray(this->RefArrayName.c_str()), m);
  if (skipped > 0)
  {
    vtkWarningMacro("Skipped " << skipped << " cells that are neither tetrahedra nor triangles.");
  }
  if (m.Mesh.Cells.empty())
  {
    vtkErrorMacro("The input has no tetrahedra or triangles to write.");
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return;
  }
  const bool hasTets = m.Mesh.SimplexDim == 3;
  bool flat = !hasTets;
  for (vtkIdType i = 0; i < np && flat; ++i)
  {
    flat = input->GetPoint(i)[2] == 0.0;
  }
  int dim = this->Dimension == 0 ? (flat ? 2 : 3) : this->Dimension;
  if (dim < 2)
  {
    dim = 3;
  }
  if (dim == 2 && hasTets)
  {
    vtkErrorMacro("Dimension 2 was requested but the input has tetrahedra.");
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return;
  }
  ToMeditPoints(input, input->GetPointData()->GetArray(this->RefArrayName.c_str()), dim, m);

  av::MetricField field;
  if (!this->SolFileName.empty())
  {
    vtkDataArray* metric = input->GetPointData()->GetArray(this->MetricArrayName.c_str());
    std::string error;
    if (!metric)
    {
      error = "SolFileName is set but the input has no 6- or 9-component point array named '" +
        this->MetricArrayName + "'.";
    }
    if (!error.empty() ||
      !vtkAnisoDataConversion::ToMetricField(metric, static_cast<std::size_t>(np), field, error))
    {
      vtkErrorMacro(<< error);
      this->SetErrorCode(vtkErrorCode::UnknownError);
      return;
    }
  }
  if (!vtkAnisoFilterUtilities::RunKernel(this,
        ("writing " + this->FileName).c_str(),
        [&]
        {
          av::WriteMeditMeshFile(this->FileName, m);
          if (!this->SolFileName.empty())
          {
            av::WriteMeditSolFile(this->SolFileName, av::MeditSolFromMetric(field, dim));
          }
        }))
  {
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
  }
}

void vtkAnisoMeditWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "SolFileName: " << this->SolFileName << "\n";
  os << indent << "MetricArrayName: " << this->MetricArrayName << "\n";
  os << indent << "RefArrayName: " << this->RefArrayName << "\n";
  os << indent << "Dimension: " << this->Dimension << "\n";
}
