// SPDX-License-Identifier: BSD-3-Clause
// MetricScaling: c = 1 / λ_min when λ_min < 1 (paper §6), checks, and the scaling itself.
#include "MetricScaling.h"

#include "MetricAlgebra.h"

#include <sstream>

namespace av
{

MetricScaling ScaleMetricForEmbedding(
  const SimplexMesh& mesh, MetricField& metric, bool allowScaling)
{
  MetricScaling r;
  double maxEig = 0.0;
  EigenvalueRange(metric, mesh.AmbientDim == 2, r.SmallestEigenvalue, maxEig);
  if (mesh.SimplexDim != mesh.AmbientDim)
  {
    return r; // surfaces: rank-2 tangent metrics, not scaled
  }
  if (!(r.SmallestEigenvalue > 0))
  {
    std::ostringstream s;
    s << "the metric is not positive definite (smallest eigenvalue " << r.SmallestEigenvalue
      << "); convert the tensor field with vtkAnisoTensorToMetric first";
    throw InputError(s.str());
  }
  if (r.SmallestEigenvalue < 1.0)
  {
    if (!allowScaling)
    {
      std::ostringstream s;
      s << "the metric's smallest eigenvalue is " << r.SmallestEigenvalue
        << " < 1: an embedding that keeps the input coordinates cannot shorten edges; "
           "enable AutoScaleMetric or scale the metric";
      throw InputError(s.str());
    }
    r.Scale = 1.0 / r.SmallestEigenvalue;
    for (double& v : metric.Values)
    {
      v *= r.Scale;
    }
  }
  return r;
}

} // namespace av
