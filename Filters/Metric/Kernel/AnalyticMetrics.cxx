// SPDX-License-Identifier: BSD-3-Clause
#include "AnalyticMetrics.h"

#include "MetricAlgebra.h"

#include <cmath>

namespace av
{

namespace
{
constexpr double kGaussSigma = 0.3;
// a = s e^{1/2} sqrt(3.85^2 - 1): max |grad h| = sqrt(3.85^2 - 1).
const double kGaussAmplitude = kGaussSigma * std::exp(0.5) * std::sqrt(3.85 * 3.85 - 1.0);

void Radial(double x, double y, Eigen::Vector3d& u, double& r)
{
  r = std::sqrt(x * x + y * y);
  if (r > 1e-300)
  {
    u = Eigen::Vector3d(x / r, y / r, 0.0);
  }
  else
  {
    u = Eigen::Vector3d(1.0, 0.0, 0.0);
  }
}
} // namespace

std::vector<AnalyticPreset> AllAnalyticPresets()
{
  return { AnalyticPreset::Gaussian2D,
    AnalyticPreset::Cube1,
    AnalyticPreset::Cube2,
    AnalyticPreset::Cube3,
    AnalyticPreset::SphereCylindrical,
    AnalyticPreset::SphereCosine };
}

std::string AnalyticPresetName(AnalyticPreset preset)
{
  switch (preset)
  {
    case AnalyticPreset::Gaussian2D:
      return "gaussian2d";
    case AnalyticPreset::Cube1:
      return "cube1";
    case AnalyticPreset::Cube2:
      return "cube2";
    case AnalyticPreset::Cube3:
      return "cube3";
    case AnalyticPreset::SphereCylindrical:
      return "sphere-cyl";
    case AnalyticPreset::SphereCosine:
      return "sphere-cos";
  }
  return "unknown";
}

AnalyticPreset AnalyticPresetFromName(const std::string& name)
{
  for (AnalyticPreset p : AllAnalyticPresets())
  {
    if (AnalyticPresetName(p) == name)
    {
      return p;
    }
  }
  if (name == "spherecylindrical")
  {
    return AnalyticPreset::SphereCylindrical;
  }
  if (name == "spherecosine")
  {
    return AnalyticPreset::SphereCosine;
  }
  throw InputError("unknown analytic metric '" + name +
    "'; valid: gaussian2d, cube1, cube2, cube3, sphere-cyl, sphere-cos");
}

AnalyticDomain RecommendedDomain(AnalyticPreset preset)
{
  AnalyticDomain d;
  switch (preset)
  {
    case AnalyticPreset::Gaussian2D:
      d.AmbientDim = 2;
      d.Lo[0] = d.Lo[1] = -1.0;
      d.Hi[0] = d.Hi[1] = 1.0;
      d.Lo[2] = d.Hi[2] = 0.0;
      d.GridVertices[0] = d.GridVertices[1] = 101;
      d.GridVertices[2] = 1;
      d.PaperStretchMax = 3.85;
      break;
    case AnalyticPreset::Cube1:
      d.PaperStretchMax = 10.0;
      break;
    case AnalyticPreset::Cube2:
      d.GridVertices[0] = 101;
      d.PaperStretchMax = 25.0;
      break;
    case AnalyticPreset::Cube3:
      for (int a = 0; a < 3; ++a)
      {
        d.Lo[a] = 1.0;
        d.Hi[a] = 11.0;
      }
      d.GridVertices[0] = 101;
      d.PaperStretchMax = 20.0;
      break;
    case AnalyticPreset::SphereCylindrical:
    case AnalyticPreset::SphereCosine:
      d.IsBall = true;
      for (int a = 0; a < 3; ++a)
      {
        d.Lo[a] = -1.0;
        d.Hi[a] = 1.0;
      }
      d.BallVertices = 50000;
      d.PaperStretchMax = preset == AnalyticPreset::SphereCylindrical ? 5.0 : 10.0;
      d.PaperStretchMin = preset == AnalyticPreset::SphereCylindrical ? 1.0 : 10.0;
      break;
  }
  return d;
}

double GaussianHeight(double x, double y)
{
  return kGaussAmplitude * std::exp(-(x * x + y * y) / (2.0 * kGaussSigma * kGaussSigma));
}

Eigen::Vector2d GaussianHeightGradient(double x, double y)
{
  const double h = GaussianHeight(x, y);
  const double f = -h / (kGaussSigma * kGaussSigma);
  return Eigen::Vector2d(f * x, f * y);
}

void AnalyticStretchAt(AnalyticPreset preset, const double* p, double& s, Eigen::Vector3d& u)
{
  switch (preset)
  {
    case AnalyticPreset::Gaussian2D:
    {
      const Eigen::Vector2d g = GaussianHeightGradient(p[0], p[1]);
      const double gn = g.norm();
      s = std::sqrt(1.0 + gn * gn);
      u = gn > 1e-300 ? Eigen::Vector3d(g(0) / gn, g(1) / gn, 0.0) : Eigen::Vector3d(1.0, 0.0, 0.0);
      return;
    }
    case AnalyticPreset::Cube1:
      s = 1.0 + 9.0 * p[0];
      u = Eigen::Vector3d::UnitX();
      return;
    case AnalyticPreset::Cube2:
      s = 0.2 * std::pow(0.0025 + 0.2 * (1.0 - std::exp(-std::abs(p[0] - 0.5))), -0.8);
      u = Eigen::Vector3d::UnitX();
      return;
    case AnalyticPreset::Cube3:
    {
      double r;
      Radial(p[0], p[1], u, r);
      const double q = std::abs(p[0] * p[0] + p[1] * p[1] - 49.0);
      s = 2.0 / (0.1 + 2.0 * (1.0 - std::exp(-0.01 * q)));
      return;
    }
    case AnalyticPreset::SphereCylindrical:
    {
      double r;
      Radial(p[0], p[1], u, r);
      s = 1.0 + 4.0 * r;
      return;
    }
    case AnalyticPreset::SphereCosine:
    {
      const double c = 2.0 * std::cos(4.0 * p[0]);
      u = Eigen::Vector3d(c, 1.0, 0.0).normalized();
      s = 10.0;
      return;
    }
  }
  s = 1.0;
  u = Eigen::Vector3d::UnitX();
}

Eigen::Matrix3d AnalyticMetricAt(AnalyticPreset preset, const double* p)
{
  double s;
  Eigen::Vector3d u;
  AnalyticStretchAt(preset, p, s, u);
  Eigen::Matrix3d m = Eigen::Matrix3d::Identity() + (s * s - 1.0) * u * u.transpose();
  if (preset == AnalyticPreset::Gaussian2D)
  {
    m.row(2).setZero();
    m.col(2).setZero();
  }
  return m;
}

MetricField EvaluateAnalyticMetric(AnalyticPreset preset, const SimplexMesh& mesh)
{
  const int want = preset == AnalyticPreset::Gaussian2D ? 2 : 3;
  if (mesh.AmbientDim != want)
  {
    throw InputError("analytic metric '" + AnalyticPresetName(preset) + "' needs a mesh in " +
      std::to_string(want) + "D, got AmbientDim " + std::to_string(mesh.AmbientDim));
  }
  MetricField f;
  f.Values.resize(6 * mesh.NumPoints());
  for (std::size_t i = 0; i < mesh.NumPoints(); ++i)
  {
    PackSymmetric(AnalyticMetricAt(preset, mesh.Point(i)), f.Values.data() + 6 * i);
  }
  return f;
}

} // namespace av
