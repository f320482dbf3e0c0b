// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAnisoTetMesher.h"

#include "TetMesher.h"
#include "vtkAnisoDataConversion.h"
#include "vtkAnisoFilterUtilities.h"

#include <vtkAlgorithm.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>

vtkStandardNewMacro(vtkAnisoTetMesher);

vtkAnisoTetMesher::vtkAnisoTetMesher() = default;

int vtkAnisoTetMesher::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

int vtkAnisoTetMesher::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector);
  const bool haveInput = input && input->GetNumberOfPoints() > 0;
  if (this->Shape == BALL && this->TargetVertices < 20)
  {
    vtkErrorMacro("a ball needs TargetVertices >= 20");
    return 0;
  }
  if (this->Shape == BOX && this->TargetVertices < 8)
  {
    vtkErrorMacro("a box needs TargetVertices >= 8");
    return 0;
  }
  if (this->Shape != BALL && this->Shape != BOX && !haveInput)
  {
    return 1; // empty in, empty out
  }
  av::SimplexMesh surface;
  if (this->Shape != BALL && this->Shape != BOX)
  {
    std::string error, note;
    if (!vtkAnisoDataConversion::ToSimplexMesh(input, surface, error, &note))
    {
      vtkErrorMacro("input surface: " << error);
      return 0;
    }
    if (surface.SimplexDim != 2 || surface.AmbientDim != 3)
    {
      vtkErrorMacro("the input must be a closed triangle surface in 3D");
      return 0;
    }
  }
  av::SimplexMesh tets;
  if (!vtkAnisoFilterUtilities::RunKernel(this,
        "tetrahedral meshing",
        [&]
        {
          if (this->Shape == BALL)
          {
            tets = av::TetrahedralizeSphere(
              this->Radius, static_cast<std::size_t>(this->TargetVertices));
            for (std::size_t i = 0; i < tets.NumPoints(); ++i)
              for (int d = 0; d < 3; ++d)
                tets.Points[3 * i + d] += this->Center[d];
          }
          else if (this->Shape == BOX)
          {
            double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
            if (haveInput)
            {
              double b[6];
              input->GetBounds(b);
              for (int d = 0; d < 3; ++d)
              {
                lo[d] = b[2 * d];
                hi[d] = b[2 * d + 1];
              }
            }
            tets = av::TetrahedralizeBox(lo, hi, static_cast<std::size_t>(this->TargetVertices));
          }
          else
          {
            av::TetMeshOptions options;
            options.RadiusEdgeRatio = this->RadiusEdgeRatio;
            options.MaxVolume = this->TargetVertices > 0
              ? av::MaxVolumeForVertexCount(surface, static_cast<std::size_t>(this->TargetVertices))
              : this->MaxVolume;
            tets = av::TetrahedralizeClosedSurface(surface, options);
          }
        }))
  {
    return 0;
  }
  output->ShallowCopy(vtkAnisoDataConversion::FromSimplexMesh(tets));
  return 1;
}

void vtkAnisoTetMesher::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Shape: " << this->Shape << "\n";
  os << indent << "TargetVertices: " << this->TargetVertices << "\n";
  os << indent << "MaxVolume: " << this->MaxVolume << "\n";
  os << indent << "RadiusEdgeRatio: " << this->RadiusEdgeRatio << "\n";
  os << indent << "Center: " << this->Center[0] << " " << this->Center[1] << " " << this->Center[2]
     << "\n";
  os << indent << "Radius: " << this->Radius << "\n";
}
