// SPDX-License-Identifier: BSD-3-Clause
#include "SurfaceCases.h"

#include "SurfaceCurvatureMetric.h"
#include "SurfaceGenerators.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace avbench
{

bool IsSurfaceCase(const std::string& name)
{
  return name == "cyclide" || name == "cyclide2" || name == "torus";
}

std::vector<std::string> SurfaceCaseNames()
{
  return { "cyclide", "cyclide2", "torus" };
}

SurfaceCase BuildSurfaceCase(const std::string& name, double maxStretch, double resolutionScale)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double scale = resolutionScale > 0.0 ? resolutionScale : 1.0;
  auto n = [&](int base) { return std::max(3, static_cast<int>(std::lround(base * scale))); };
  SurfaceCase c;
  if (name == "cyclide")
  {
    c.Mesh = av::MakeDupinCyclideSurface(2.0, 1.0, 1.5, n(120), n(90));
    c.Description = "cyclide-a2-c1-mu1.5-" + std::to_string(n(120)) + "x" + std::to_string(n(90));
    c.Sites = 2000;
    c.MaxStretch = 10.0;
    const double p[9] = { 1.83, 25.81, 9.14, 0.57, 0.92, 28.88, 54.47, 0.05, 6.22 };
    std::copy(p, p + 9, c.Paper);
  }
  else if (name == "cyclide2")
  {
    c.Mesh = av::MakeDupinCyclideSurface(2.0, 1.9, 1.95, n(180), n(144));
    c.Description =
      "cyclide-a2-c1.9-mu1.95-" + std::to_string(n(180)) + "x" + std::to_string(n(144));
    c.Sites = 8000;
    c.MaxStretch = 29.0; // Tab. 3 / Fig. 13: s2 / s1 in [2, 29]
    const double p[9] = { 2.18, 19.39, 23.63, 0.63, 0.92, 29.07, 53.70, 0.009, 42.83 };
    std::copy(p, p + 9, c.Paper);
  }
  else if (name == "torus")
  {
    c.Mesh = av::MakeTorusSurface(3.0, 1.0, n(120), n(60));
    c.Description = "torus-R3-r1-" + std::to_string(n(120)) + "x" + std::to_string(n(60));
    c.Sites = 2000;
    c.MaxStretch = 10.0;
    std::fill(c.Paper, c.Paper + 9, nan);
  }
  else
  {
    throw std::runtime_error("unknown surface case '" + name + "'");
  }
  if (maxStretch > 0.0)
    c.MaxStretch = maxStretch;
  av::SurfaceCurvatureMetricOptions o;
  o.MaxStretch = c.MaxStretch;
  c.Metric = av::SurfaceCurvatureMetric(c.Mesh, o).Metric;
  return c;
}

} // namespace avbench
