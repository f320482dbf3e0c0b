// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAnisoAnalyticMetricSource.h"

#include "AnalyticMetrics.h"
#include "StructuredMeshes.h"
#include "TetMesher.h"
#include "vtkAnisoAnalyticMetric.h"
#include "vtkAnisoDataConversion.h"
#include "vtkAnisoFilterUtilities.h"

#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkAnisoAnalyticMetricSource);

vtkAnisoAnalyticMetricSource::vtkAnisoAnalyticMetricSource()
{
  this->SetNumberOfInputPorts(0);
}

bool vtkAnisoAnalyticMetricSource::SetPresetByName(const char* name)
{
  return vtkAnisoFilterUtilities::RunKernel(this,
    "SetPresetByName",
    [&] { this->SetPreset(static_cast<int>(av::AnalyticPresetFromName(name ? name : ""))); });
}

int vtkAnisoAnalyticMetricSource::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector);
  if (this->Resolution != 0 && this->Resolution < 3)
  {
    vtkErrorMacro("Resolution must be 0 (paper sizes) or at least 3, not " << this->Resolution);
    return 0;
  }
  const auto preset = static_cast<av::AnalyticPreset>(this->Preset);
  const av::AnalyticDomain domain = av::RecommendedDomain(preset);
  av::SimplexMesh mesh;
  if (!vtkAnisoFilterUtilities::RunKernel(this,
        "preset mesh",
        [&]
        {
          if (domain.IsBall)
          {
            const std::size_t target = this->Resolution > 0
              ? static_cast<std::size_t>(std::pow(this->Resolution, 3))
              : domain.BallVertices;
            mesh = av::TetrahedralizeSphere(domain.Radius, std::max<std::size_t>(target, 20));
            return;
          }
          int n[3] = { domain.GridVertices[0], domain.GridVertices[1], domain.GridVertices[2] };
          if (this->Resolution > 0)
          {
            const int shortest =
              domain.AmbientDim == 2 ? std::min(n[0], n[1]) : std::min(n[0], std::min(n[1], n[2]));
            for (int d = 0; d < 3; ++d)
              n[d] = std::max(2,
                static_cast<int>(
                  std::lround(static_cast<double>(n[d]) * this->Resolution / shortest)));
          }
          mesh = domain.AmbientDim == 2
            ? av::MakeTriangleGrid(n[0], n[1], domain.Lo, domain.Hi)
            : av::MakeKuhnTetGrid(n[0], n[1], n[2], domain.Lo, domain.Hi);
        }))
  {
    return 0;
  }
  this->UpdateProgress(0.5);
  vtkSmartPointer<vtkUnstructuredGrid> grid = vtkAnisoDataConversion::FromSimplexMesh(mesh);
  vtkNew<vtkAnisoAnalyticMetric> metric;
  metric->SetPreset(this->Preset);
  metric->SetInputData(grid);
  metric->Update();
  output->ShallowCopy(metric->GetOutput());
  return 1;
}

void vtkAnisoAnalyticMetricSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent
     << "Preset: " << av::AnalyticPresetName(static_cast<av::AnalyticPreset>(this->Preset)) << "\n";
  os << indent << "Resolution: " << this->Resolution << "\n";
}
