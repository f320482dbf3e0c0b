// SPDX-License-Identifier: BSD-3-Clause
#include "BoundaryLayerMetric.h"

#include "InputError.h"

#include <algorithm>
#include <cmath>

namespace av
{

std::string BoundaryLayerProfileName(BoundaryLayerProfile profile)
{
  return profile == BoundaryLayerProfile::Linear ? "linear" : "exponential";
}

void CheckBoundaryLayerOptions(const BoundaryLayerMetricOptions& o)
{
  if (!(o.Stretch >= 1.0) || !std::isfinite(o.Stretch))
    throw InputError("boundary-layer metric: the stretch must be a finite number >= 1");
  if (!(o.TangentSize > 0.0) || !std::isfinite(o.TangentSize))
    throw InputError("boundary-layer metric: the tangent size must be finite and > 0");
  if (!(o.Thickness > 0.0) || !std::isfinite(o.Thickness))
    throw InputError("boundary-layer metric: the thickness must be finite and > 0");
}

double BoundaryLayerNormalSize(const BoundaryLayerMetricOptions& o, double z)
{
  const double h0 = o.TangentSize, hw = h0 / o.Stretch;
  if (o.Profile == BoundaryLayerProfile::Linear)
    return hw + (h0 - hw) * z;
  return h0 - (h0 - hw) * std::exp(-z / o.Thickness);
}

double BoundaryLayerNormalLength(const BoundaryLayerMetricOptions& o, double z)
{
  const double h0 = o.TangentSize, hw = h0 / o.Stretch, a = h0 - hw;
  if (a <= 0.0)
    return z / h0; // isotropic: no layer
  if (o.Profile == BoundaryLayerProfile::Linear)
    return std::log1p(a * z / hw) / a; // integral of dz / (hw + a z)
  // integral of dz / (h0 - a e^{-z/d}) = (d / h0) ln((h0 e^{z/d} - a) / hw); written with
  // expm1 so that small z keeps its digits: h0 e^{z/d} - a = hw + h0 (e^{z/d} - 1).
  const double d = o.Thickness;
  return d / h0 * std::log1p(h0 * std::expm1(z / d) / hw);
}

Eigen::Matrix3d BoundaryLayerMetricAt(const BoundaryLayerMetricOptions& o, const double* p)
{
  const double h0 = o.TangentSize, hz = BoundaryLayerNormalSize(o, p[2]);
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  m(0, 0) = m(1, 1) = 1.0 / (h0 * h0);
  m(2, 2) = 1.0 / (hz * hz);
  return m;
}

MetricField EvaluateBoundaryLayerMetric(const BoundaryLayerMetricOptions& o, const SimplexMesh& mesh)
{
  CheckBoundaryLayerOptions(o);
  if (mesh.AmbientDim != 3)
    throw InputError("boundary-layer metric: needs a 3D mesh");
  MetricField f;
  const std::size_t n = mesh.NumPoints();
  f.Values.assign(6 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
  {
    const Eigen::Matrix3d m = BoundaryLayerMetricAt(o, mesh.Points.data() + 3 * i);
    double* v = f.Values.data() + 6 * i;
    v[0] = m(0, 0);
    v[1] = m(1, 1);
    v[2] = m(2, 2); // off-diagonal terms stay 0
  }
  return f;
}

std::vector<double> BoundaryLayerLevels(const BoundaryLayerMetricOptions& o, double fraction)
{
  CheckBoundaryLayerOptions(o);
  if (!(fraction > 0.0) || !(fraction <= 1.0))
    throw InputError("boundary-layer levels: the step fraction must be in (0, 1]");
  std::vector<double> z{ 0.0 };
  while (z.back() < 1.0)
    z.push_back(std::min(1.0, z.back() + fraction * BoundaryLayerNormalSize(o, z.back())));
  // A sliver of a last layer would be a needlessly flat element: merge it downwards.
  if (z.size() > 2 && 1.0 - z[z.size() - 2] < 0.25 * fraction * BoundaryLayerNormalSize(o, z[z.size() - 2]))
    z.erase(z.end() - 2);
  return z;
}

Embedding BoundaryLayerIsometricEmbedding(const BoundaryLayerMetricOptions& o,
  const SimplexMesh& mesh, int dim, double scale)
{
  CheckBoundaryLayerOptions(o);
  if (mesh.AmbientDim != 3 || dim < 3 || !(scale > 0.0))
    throw InputError("boundary-layer embedding: needs a 3D mesh, dim >= 3 and a scale > 0");
  Embedding e;
  e.Dim = dim;
  const std::size_t n = mesh.NumPoints();
  e.Coords.assign(n * static_cast<std::size_t>(dim), 0.0);
  const double s = std::sqrt(scale);
  for (std::size_t i = 0; i < n; ++i)
  {
    const double* p = mesh.Points.data() + 3 * i;
    double* q = e.Coords.data() + i * static_cast<std::size_t>(dim);
    q[0] = s * p[0] / o.TangentSize;
    q[1] = s * p[1] / o.TangentSize;
    q[2] = s * BoundaryLayerNormalLength(o, p[2]);
  }
  return e;
}

} // namespace av
