// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAnisoOFFReader.h"

#include "OffReader.h"

#include <vtkCellArray.h>
#include <vtkIdTypeArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

vtkStandardNewMacro(vtkAnisoOFFReader);

vtkAnisoOFFReader::vtkAnisoOFFReader()
{
  this->SetNumberOfInputPorts(0);
}

int vtkAnisoOFFReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (this->FileName.empty())
  {
    vtkErrorMacro("FileName is not set.");
    return 0;
  }
  av::SimplexMesh surface;
  try
  {
    surface = av::ReadOff(this->FileName);
  }
  catch (const av::InputError& e)
  {
    vtkErrorMacro("Cannot read " << this->FileName << ": " << e.what());
    return 0;
  }
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(surface.NumPoints()));
  for (std::size_t i = 0; i < surface.NumPoints(); ++i)
    points->SetPoint(static_cast<vtkIdType>(i), surface.Point(i));
  // Connectivity in VTK's offsets + ids layout, filled once (no per-cell insertion).
  const auto numCells = static_cast<vtkIdType>(surface.NumCells());
  vtkNew<vtkIdTypeArray> offsets, ids;
  offsets->SetNumberOfValues(numCells + 1);
  ids->SetNumberOfValues(3 * numCells);
  for (vtkIdType c = 0; c <= numCells; ++c)
    offsets->SetValue(c, 3 * c);
  for (vtkIdType k = 0; k < 3 * numCells; ++k)
    ids->SetValue(k, surface.Cells[static_cast<std::size_t>(k)]);
  vtkNew<vtkCellArray> triangles;
  triangles->SetData(offsets, ids);
  output->SetPoints(points);
  output->SetPolys(triangles);
  return 1;
}

void vtkAnisoOFFReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
}
