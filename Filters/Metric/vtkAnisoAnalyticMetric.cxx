// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAnisoAnalyticMetric.h"

#include "AnalyticMetrics.h"
#include "MetricAlgebra.h"
#include "vtkAnisoFilterUtilities.h"

#include <vtkDataSet.h>
#include <vtkDoubleArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkSMPTools.h>

#include <atomic>
#include <cmath>

vtkStandardNewMacro(vtkAnisoAnalyticMetric);

vtkAnisoAnalyticMetric::vtkAnisoAnalyticMetric()
{
  this->SetMetricArrayName("Metric");
}

vtkAnisoAnalyticMetric::~vtkAnisoAnalyticMetric()
{
  this->SetMetricArrayName(nullptr);
}

bool vtkAnisoAnalyticMetric::SetPresetByName(const char* name)
{
  return vtkAnisoFilterUtilities::RunKernel(this,
    "SetPresetByName",
    [&] { this->SetPreset(static_cast<int>(av::AnalyticPresetFromName(name ? name : ""))); });
}

int vtkAnisoAnalyticMetric::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0]);
  vtkDataSet* output = vtkDataSet::GetData(outputVector);
  output->ShallowCopy(input);
  const vtkIdType n = input->GetNumberOfPoints();
  if (n == 0)
  {
    return 1;
  }
  const auto preset = static_cast<av::AnalyticPreset>(this->Preset);
  vtkNew<vtkDoubleArray> metric;
  metric->SetName(this->MetricArrayName ? this->MetricArrayName : "Metric");
  metric->SetNumberOfComponents(6);
  metric->SetNumberOfTuples(n);
  vtkNew<vtkDoubleArray> stretch;
  stretch->SetName("Stretch");
  stretch->SetNumberOfTuples(n);
  // GetPoint is thread-safe after one serial call (it may build internal caches).
  double p0[3];
  input->GetPoint(0, p0);
  std::atomic<vtkIdType> badPoint{ -1 };
  vtkSMPTools::For(0,
    n,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        double p[3];
        input->GetPoint(i, p);
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
        {
          badPoint = i;
          continue;
        }
        double s;
        Eigen::Vector3d u;
        av::AnalyticStretchAt(preset, p, s, u);
        const Eigen::Matrix3d m = av::AnalyticMetricAt(preset, p);
        av::PackSymmetric(m, metric->GetPointer(6 * i));
        stretch->SetValue(i, s);
      }
    });
  if (badPoint >= 0)
  {
    vtkErrorMacro("point " << badPoint << " has a non-finite coordinate");
    return 0;
  }
  output->GetPointData()->AddArray(metric);
  output->GetPointData()->AddArray(stretch);
  output->GetPointData()->SetActiveTensors(metric->GetName());
  return 1;
}

void vtkAnisoAnalyticMetric::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent
     << "Preset: " << av::AnalyticPresetName(static_cast<av::AnalyticPreset>(this->Preset)) << "\n";
  os << indent << "MetricArrayName: " << (this->MetricArrayName ? this->MetricArrayName : "")
     << "\n";
}
