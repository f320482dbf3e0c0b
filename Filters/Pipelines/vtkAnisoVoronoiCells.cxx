// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAnisoVoronoiCells.h"

#include "vtkAnisoRestrictedVoronoi.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkTable.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <vector>

vtkStandardNewMacro(vtkAnisoVoronoiCells);

namespace
{
/// sqrt(λmax / λmin) of a 6- or 9-component symmetric tensor; eigenvalues below 1e-12 λmax
/// (the null direction of a 2D or surface metric) are ignored. 1 for a null tensor.
double StretchRatio(const double* t, int nc)
{
  double m[3][3];
  if (nc == 6)
  {
    m[0][0] = t[0];
    m[1][1] = t[1];
    m[2][2] = t[2];
    m[0][1] = m[1][0] = t[3];
    m[1][2] = m[2][1] = t[4];
    m[0][2] = m[2][0] = t[5];
  }
  else
  {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        m[i][j] = 0.5 * (t[3 * i + j] + t[3 * j + i]);
  }
  double w[3], v[3][3];
  vtkMath::Diagonalize3x3(m, w, v);
  const double hi = std::max({ std::abs(w[0]), std::abs(w[1]), std::abs(w[2]) });
  double lo = hi;
  for (double x : w)
    if (std::abs(x) > 1e-12 * hi)
      lo = std::min(lo, std::abs(x));
  return hi > 0 ? std::sqrt(hi / lo) : 1.0;
}

/// Adds "Stretch" (per cell, from the cell's SiteId) to a cell data; false without SiteId.
bool AddStretch(vtkCellData* cd, const std::vector<double>& siteStretch)
{
  vtkDataArray* siteIds = cd->GetArray("SiteId");
  if (!siteIds)
    return false;
  vtkNew<vtkDoubleArray> stretch;
  stretch->SetName("Stretch");
  stretch->SetNumberOfTuples(siteIds->GetNumberOfTuples());
  for (vtkIdType c = 0; c < siteIds->GetNumberOfTuples(); ++c)
  {
    const auto s = static_cast<vtkIdType>(siteIds->GetTuple1(c));
    stretch->SetValue(c,
      s >= 0 && s < static_cast<vtkIdType>(siteStretch.size()) ? siteStretch[s] : 1.0);
  }
  cd->AddArray(stretch);
  return true;
}
}

vtkAnisoVoronoiCells::vtkAnisoVoronoiCells()
{
  this->SetNumberOfOutputPorts(3);
}

vtkAnisoVoronoiCells::~vtkAnisoVoronoiCells() = default;

int vtkAnisoVoronoiCells::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(),
    port == 0 ? "vtkUnstructuredGrid" : (port == 1 ? "vtkPolyData" : "vtkTable"));
  return 1;
}

int vtkAnisoVoronoiCells::RequestBackEnd(vtkUnstructuredGrid* embedded, vtkPolyData* sites,
  vtkTable* energy, vtkInformationVector* outputVector)
{
  vtkNew<vtkAnisoRestrictedVoronoi> voronoi;
  voronoi->SetInputData(0, embedded);
  voronoi->SetInputData(1, sites);
  voronoi->SetShrinkFactor(this->ShrinkFactor);
  std::string error;
  if (!this->RunStage(voronoi, "restricted Voronoi", 0.85, 0.99, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }

  // Stretch of each site's metric (the sampler interpolates "Metric" at the sites).
  vtkDataArray* metric = sites->GetPointData()->GetArray("Metric");
  if (!metric || (metric->GetNumberOfComponents() != 6 && metric->GetNumberOfComponents() != 9))
  {
    vtkErrorMacro("the sites carry no 6/9-component \"Metric\" array: cannot compute Stretch");
    return 0;
  }
  std::vector<double> siteStretch(metric->GetNumberOfTuples());
  for (vtkIdType s = 0; s < metric->GetNumberOfTuples(); ++s)
    siteStretch[s] = StretchRatio(metric->GetTuple(s), metric->GetNumberOfComponents());

  vtkUnstructuredGrid* cells = vtkUnstructuredGrid::GetData(outputVector, 0);
  vtkPolyData* faces = vtkPolyData::GetData(outputVector, 1);
  vtkTable* energyOut = vtkTable::GetData(outputVector, 2);
  cells->ShallowCopy(voronoi->GetOutputDataObject(0));
  faces->ShallowCopy(voronoi->GetOutputDataObject(1));
  if (energy)
    energyOut->ShallowCopy(energy);
  // Fresh field/cell data objects: the shallow copies share them with the internal filter.
  for (vtkDataObject* out : { static_cast<vtkDataObject*>(cells), static_cast<vtkDataObject*>(faces) })
  {
    vtkNew<vtkFieldData> fd;
    fd->ShallowCopy(out->GetFieldData());
    this->AddFrontFieldData(fd);
    out->SetFieldData(fd);
  }
  if (!AddStretch(cells->GetCellData(), siteStretch) ||
    !AddStretch(faces->GetCellData(), siteStretch))
  {
    vtkErrorMacro("restricted Voronoi output without SiteId");
    return 0;
  }
  cells->GetCellData()->SetActiveScalars("Stretch");
  return 1;
}

void vtkAnisoVoronoiCells::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ShrinkFactor: " << this->ShrinkFactor << "\n";
}
