// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAnisoAnisotropicMesh.h"

#include "vtkAnisoDataConversion.h"
#include "vtkAnisoMeshQuality.h"
#include "vtkAnisoRestrictedDelaunay.h"

#include <vtkDataSetAttributes.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkTable.h>
#include <vtkUnstructuredGrid.h>

vtkStandardNewMacro(vtkAnisoAnisotropicMesh);

vtkAnisoAnisotropicMesh::vtkAnisoAnisotropicMesh()
{
  this->SetNumberOfOutputPorts(2);
}

vtkAnisoAnisotropicMesh::~vtkAnisoAnisotropicMesh() = default;

int vtkAnisoAnisotropicMesh::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkUnstructuredGrid" : "vtkTable");
  return 1;
}

int vtkAnisoAnisotropicMesh::RequestBackEnd(
  vtkUnstructuredGrid* embedded, vtkPolyData* sites, vtkTable*, vtkInformationVector* outputVector)
{
  std::string error;
  vtkNew<vtkAnisoRestrictedDelaunay> delaunay;
  delaunay->SetInputData(0, embedded);
  delaunay->SetInputData(1, sites);
  delaunay->SetRepairInverted(this->RepairInverted);
  delaunay->SetRepairNonManifold(this->RepairNonManifold);
  delaunay->SetValidDual(this->ValidDual);
  delaunay->SetMaxRepairRounds(this->MaxRepairRounds);
  delaunay->SetImprovementRounds(this->ImprovementRounds);
  delaunay->SetOdtIterations(this->OdtIterations);
  delaunay->SetImproveMesh(this->ImproveMesh);
  delaunay->SetKeepFeatureSites(this->KeepFeatureSites);
  delaunay->SetInputArrayToProcess(1, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Metric");
  if (!this->RunStage(delaunay, "restricted Delaunay", 0.85, 0.95, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  vtkNew<vtkAnisoMeshQuality> quality;
  quality->SetInputData(delaunay->GetOutput());
  quality->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Metric");
  if (vtkAnisoDataConversion::IsSurfaceInThreeD(embedded))
    quality->SetReferenceSurfaceData(embedded); // Hausdorff distance and flipped triangles
  if (!this->RunStage(quality, "mesh quality", 0.95, 0.99, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  vtkUnstructuredGrid* mesh = vtkUnstructuredGrid::GetData(outputVector, 0);
  vtkTable* histogram = vtkTable::GetData(outputVector, 1);
  mesh->ShallowCopy(quality->GetOutputDataObject(0));
  histogram->ShallowCopy(quality->GetOutputDataObject(1));
  // Quality figures, then the dual's counts and the front's figures (fresh field data object).
  vtkNew<vtkFieldData> fd;
  fd->ShallowCopy(mesh->GetFieldData());
  vtkFieldData* dual = delaunay->GetOutput()->GetFieldData();
  for (int i = 0; i < dual->GetNumberOfArrays(); ++i)
  {
    const char* name = dual->GetAbstractArray(i)->GetName();
    if (name && !fd->GetAbstractArray(name))
      fd->AddArray(dual->GetAbstractArray(i));
  }
  this->AddFrontFieldData(fd);
  mesh->SetFieldData(fd);
  return 1;
}

void vtkAnisoAnisotropicMesh::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RepairInverted: " << (this->RepairInverted ? "On" : "Off") << "\n";
  os << indent << "RepairNonManifold: " << (this->RepairNonManifold ? "On" : "Off") << "\n";
  os << indent << "ValidDual: " << (this->ValidDual ? "On" : "Off") << "\n";
  os << indent << "MaxRepairRounds: " << this->MaxRepairRounds << "\n";
  os << indent << "ImprovementRounds: " << this->ImprovementRounds << "\n";
  os << indent << "OdtIterations: " << this->OdtIterations << "\n";
  os << indent << "ImproveMesh: " << (this->ImproveMesh ? "On" : "Off") << "\n";
  os << indent << "KeepFeatureSites: " << (this->KeepFeatureSites ? "On" : "Off") << "\n";
}
