// SPDX-License-Identifier: BSD-3-Clause
#include "ReferenceEmbedding.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace av
{
namespace
{
/// The coordinate the stretch depends on: x (Cube1, Cube2) or r = |(x, y)| (Cube3, SphereCylindrical).
bool IsRadial(AnalyticPreset preset)
{
  return preset == AnalyticPreset::Cube3 || preset == AnalyticPreset::SphereCylindrical;
}

double Parameter(AnalyticPreset preset, const double* p)
{
  return IsRadial(preset) ? std::sqrt(p[0] * p[0] + p[1] * p[1]) : p[0];
}

/// H'(t) = sqrt(S(t)^2 - 1); the stretch of both families depends on t alone, so it is read at
/// the point (t, 0, 0).
double Slope(AnalyticPreset preset, double t)
{
  const double p[3] = { t, 0.0, 0.0 };
  double s = 1.0;
  Eigen::Vector3d u;
  AnalyticStretchAt(preset, p, s, u);
  const double s2m1 = s * s - 1.0;
  if (!(s2m1 > -1e-12))
  {
    throw InputError("ComputeReferenceEmbedding: stretch " + std::to_string(s) + " below 1 at t = " +
      std::to_string(t) + " (no real isometric graph embedding)");
  }
  return std::sqrt(std::max(0.0, s2m1));
}

/// H(t) - H(t0): a table of kPanels panels, then one panel from the last table node to t.
class GraphHeight
{
public:
  GraphHeight(AnalyticPreset preset, double t0, double t1)
    : Preset(preset)
    , T0(t0)
    , Step(t1 > t0 ? (t1 - t0) / kPanels : 0.0)
    , H(kPanels + 1, 0.0)
  {
    for (int k = 0; k < kPanels; ++k)
    {
      this->H[k + 1] = this->H[k] + this->Panel(t0 + k * this->Step, t0 + (k + 1) * this->Step);
    }
  }

  double operator()(double t) const
  {
    if (this->Step <= 0.0)
    {
      return 0.0;
    }
    const int k = std::min(kPanels - 1, std::max(0, static_cast<int>((t - this->T0) / this->Step)));
    const double tk = this->T0 + k * this->Step;
    return this->H[k] + this->Panel(tk, t);
  }

private:
  static constexpr int kPanels = 1 << 16;

  /// Integral of the slope over [a, b] with t = a + (b - a) u^2 (the slope has a square-root
  /// zero where S = 1, e.g. Cube1 at x = 0; in u the integrand is smooth), Simpson on two halves.
  double Panel(double a, double b) const
  {
    const double w = b - a;
    double g[5];
    for (int i = 0; i < 5; ++i)
    {
      const double u = 0.25 * i;
      g[i] = 2.0 * w * u * Slope(this->Preset, a + w * u * u);
    }
    return (g[0] + 4.0 * g[1] + 2.0 * g[2] + 4.0 * g[3] + g[4]) / 12.0;
  }

  AnalyticPreset Preset;
  double T0;
  double Step;
  std::vector<double> H;
};
} // namespace

bool HasReferenceEmbedding(AnalyticPreset preset)
{
  switch (preset)
  {
    case AnalyticPreset::Gaussian2D:
    case AnalyticPreset::Cube1:
    case AnalyticPreset::Cube2:
    case AnalyticPreset::Cube3:
    case AnalyticPreset::SphereCylindrical:
      return true;
    case AnalyticPreset::SphereCosine:
      return false;
  }
  return false;
}

Embedding ComputeReferenceEmbedding(AnalyticPreset preset, const SimplexMesh& mesh, int dim)
{
  const std::string name = AnalyticPresetName(preset);
  if (!HasReferenceEmbedding(preset))
  {
    throw InputError("ComputeReferenceEmbedding: preset '" + name +
      "' has no closed-form embedding (supported: gaussian2d, cube1, cube2, cube3, sphere-cyl)");
  }
  const int m = preset == AnalyticPreset::Gaussian2D ? 2 : 3;
  if (mesh.AmbientDim != m)
  {
    throw InputError("ComputeReferenceEmbedding: preset '" + name + "' needs a mesh in " +
      std::to_string(m) + "D, got AmbientDim " + std::to_string(mesh.AmbientDim));
  }
  if (dim < m + 1 || dim > 20)
  {
    throw InputError("ComputeReferenceEmbedding: dimension " + std::to_string(dim) +
      " out of range [" + std::to_string(m + 1) + ", 20]");
  }
  const std::size_t np = mesh.NumPoints();
  for (std::size_t i = 0; i < np; ++i)
  {
    for (int d = 0; d < m; ++d)
    {
      if (!std::isfinite(mesh.Point(i)[d]))
      {
        throw InputError("ComputeReferenceEmbedding: point " + std::to_string(i) + " is not finite");
      }
    }
  }

  Embedding out;
  out.Dim = dim;
  out.Coords.assign(np * static_cast<std::size_t>(dim), 0.0);
  for (std::size_t i = 0; i < np; ++i)
  {
    std::copy(mesh.Point(i), mesh.Point(i) + m, out.Coords.data() + i * dim);
  }
  if (preset == AnalyticPreset::Gaussian2D)
  {
    for (std::size_t i = 0; i < np; ++i)
    {
      out.Coords[i * dim + 2] = GaussianHeight(mesh.Point(i)[0], mesh.Point(i)[1]);
    }
    return out;
  }
  double t0 = std::numeric_limits<double>::max(), t1 = -t0;
  for (std::size_t i = 0; i < np; ++i)
  {
    const double t = Parameter(preset, mesh.Point(i));
    t0 = std::min(t0, t);
    t1 = std::max(t1, t);
  }
  if (np == 0)
  {
    return out;
  }
  const GraphHeight height(preset, t0, t1);
  for (std::size_t i = 0; i < np; ++i)
  {
    out.Coords[i * dim + 3] = height(Parameter(preset, mesh.Point(i)));
  }
  return out;
}

} // namespace av
