// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAnisoFRDReader.h"

#include "vtkAnisoDataConversion.h"
#include "vtkAnisoFilterUtilities.h"

#include "FrdReader.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <vector>

vtkStandardNewMacro(vtkAnisoFRDReader);

vtkAnisoFRDReader::vtkAnisoFRDReader()
{
  this->SetNumberOfInputPorts(0);
}

int vtkAnisoFRDReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector);
  if (this->FileName.empty())
  {
    vtkErrorMacro("FileName is not set.");
    return 0;
  }
  av::FrdData d;
  if (!vtkAnisoFilterUtilities::RunKernel(
        this, ("reading " + this->FileName).c_str(), [&] { d = av::ReadFrd(this->FileName); }))
  {
    return 0;
  }
  const std::vector<int> steps = d.Steps();
  this->NumberOfSteps = static_cast<int>(steps.size());
  if (!this->ReadAllSteps && !steps.empty() && this->StepIndex >= this->NumberOfSteps)
  {
    vtkErrorMacro("StepIndex " << this->StepIndex << " is out of range: " << this->FileName
                               << " has " << this->NumberOfSteps << " step(s).");
    return 0;
  }

  const vtkIdType np = static_cast<vtkIdType>(d.NumNodes());
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(np);
  std::copy(d.Points.begin(),
    d.Points.end(),
    static_cast<vtkDoubleArray*>(points->GetData())->GetPointer(0));

  const vtkIdType ne = static_cast<vtkIdType>(d.NumElements());
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->AllocateExact(ne, static_cast<vtkIdType>(d.Connectivity.size()));
  std::vector<int> types(static_cast<std::size_t>(ne));
  vtkIdType ids[20];
  for (vtkIdType e = 0; e < ne; ++e)
  {
    const int t = d.ElementTypes[e];
    const int* order = av::FrdToVTKNodeOrder(t);
    const int n = av::FrdNodesPerElement(t);
    const std::int32_t* conn = d.Connectivity.data() + d.Offsets[e];
    for (int i = 0; i < n; ++i)
    {
      ids[i] = conn[order[i]];
    }
    cells->InsertNextCell(n, ids);
    types[e] = av::FrdToVTKCellType(t);
  }
  output->SetPoints(points);
  output->SetCells(types.data(), cells);

  output->GetPointData()->AddArray(vtkAnisoDataConversion::MakeIntArray("NodeId", d.NodeIds));
  auto corner = vtkSmartPointer<vtkUnsignedCharArray>::New();
  corner->SetName("IsCornerNode");
  corner->SetNumberOfTuples(np);
  std::copy(d.IsCornerNode.begin(), d.IsCornerNode.end(), corner->GetPointer(0));
  output->GetPointData()->AddArray(corner);
  output->GetCellData()->AddArray(vtkAnisoDataConversion::MakeIntArray("ElementId", d.ElementIds));
  output->GetCellData()->AddArray(
    vtkAnisoDataConversion::MakeIntArray("Material", d.ElementMaterials));
  output->GetCellData()->AddArray(vtkAnisoDataConversion::MakeIntArray("Group", d.ElementGroups));

  for (const av::FrdResult& r : d.Results)
  {
    const bool selected = this->ReadAllSteps || r.Step == steps[this->StepIndex];
    if (!selected)
    {
      continue;
    }
    auto a = vtkSmartPointer<vtkDoubleArray>::New();
    const std::string name = this->ReadAllSteps ? r.Name + "_" + std::to_string(r.Step) : r.Name;
    a->SetName(name.c_str());
    a->SetNumberOfComponents(r.NumComponents);
    a->SetNumberOfTuples(np);
    std::copy(r.Values.begin(), r.Values.end(), a->GetPointer(0));
    for (int c = 0; c < r.NumComponents && c < static_cast<int>(r.ComponentNames.size()); ++c)
    {
      a->SetComponentName(c, r.ComponentNames[c].c_str());
    }
    output->GetPointData()->AddArray(a);
    if (r.IsVector && !output->GetPointData()->GetVectors())
    {
      output->GetPointData()->SetActiveVectors(name.c_str());
    }
    if (r.IsSymmetricTensor && !output->GetPointData()->GetTensors())
    {
      output->GetPointData()->SetActiveTensors(name.c_str());
    }
    if (!this->ReadAllSteps && !output->GetFieldData()->GetArray("StepValue"))
    {
      auto v = vtkSmartPointer<vtkDoubleArray>::New();
      v->SetName("StepValue");
      v->InsertNextValue(r.Value);
      output->GetFieldData()->AddArray(v);
    }
  }
  return 1;
}

void vtkAnisoFRDReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "StepIndex: " << this->StepIndex << "\n";
  os << indent << "ReadAllSteps: " << this->ReadAllSteps << "\n";
  os << indent << "NumberOfSteps: " << this->NumberOfSteps << "\n";
}
