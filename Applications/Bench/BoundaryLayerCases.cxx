// SPDX-License-Identifier: BSD-3-Clause
#include "BoundaryLayerCases.h"

#include "MetricFieldOps.h"
#include "StructuredMeshes.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace avbench
{
namespace
{
/// Parses "bl-linearS" / "bl-expS"; false when `name` is neither.
bool Parse(const std::string& name, av::BoundaryLayerMetricOptions& o)
{
  static const struct
  {
    const char* Prefix;
    av::BoundaryLayerProfile Profile;
  } kinds[] = { { "bl-linear", av::BoundaryLayerProfile::Linear },
    { "bl-exp", av::BoundaryLayerProfile::Exponential } };
  for (const auto& k : kinds)
  {
    const std::string prefix = k.Prefix;
    if (name.rfind(prefix, 0) != 0 || name.size() == prefix.size())
      continue;
    const std::string number = name.substr(prefix.size());
    char* end = nullptr;
    const double s = std::strtod(number.c_str(), &end);
    if (end != number.c_str() + number.size() || !std::isfinite(s) || s < 1.0)
      return false;
    o.Profile = k.Profile;
    o.Stretch = s;
    return true;
  }
  return false;
}
} // namespace

bool IsBoundaryLayerCase(const std::string& name)
{
  av::BoundaryLayerMetricOptions o;
  return Parse(name, o);
}

std::vector<std::string> BoundaryLayerCaseNames()
{
  return { "bl-linear100", "bl-linear1000", "bl-exp100", "bl-exp1000" };
}

BoundaryLayerCase BuildBoundaryLayerCase(const std::string& name, int resolution)
{
  BoundaryLayerCase c;
  if (!Parse(name, c.Options))
    throw std::runtime_error("unknown boundary-layer case '" + name +
      "' (bl-linearS or bl-expS with a stretch S >= 1, e.g. bl-linear100)");
  const int n = resolution > 0 ? resolution : 21;
  if (n < 2)
    throw std::runtime_error("boundary-layer case: --resolution must be at least 2");
  std::vector<double> across(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    across[i] = i == n - 1 ? 1.0 : static_cast<double>(i) / (n - 1);
  // The normal levels step by the same fraction of h_z as the lattice across does of h0.
  const double fraction = std::min(1.0, 1.0 / ((n - 1) * c.Options.TangentSize));
  const std::vector<double> levels = av::BoundaryLayerLevels(c.Options, fraction);
  c.Mesh = av::MakeKuhnTetGrid(across, across, levels);
  c.Metric = av::EvaluateBoundaryLayerMetric(c.Options, c.Mesh);
  c.Sites = static_cast<std::size_t>(
    std::lround(av::MetricComplexity(c.Mesh, c.Metric) / av::UnitVertexMeasure(3)));
  c.Description = "graded-kuhn-" + std::to_string(n) + "x" + std::to_string(n) + "x" +
    std::to_string(levels.size()) + " " + av::BoundaryLayerProfileName(c.Options.Profile) +
    " stretch " + std::to_string(static_cast<long long>(std::lround(c.Options.Stretch)));
  return c;
}

} // namespace avbench
