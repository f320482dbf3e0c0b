// SPDX-License-Identifier: BSD-3-Clause
#include "DomainAngleBound.h"

#include "InputError.h"
#include "MeshTopology.h"
#include "MetricAlgebra.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace av
{
namespace
{
constexpr double Pi = 3.14159265358979323846;

void Validate(const SimplexMesh& tets, const MetricField& metric)
{
  const char* who = "ComputeDomainAngleBound";
  if (tets.SimplexDim != 3 || tets.AmbientDim != 3)
    throw InputError(std::string(who) + ": needs a tet mesh in 3D");
  if (metric.Values.size() != 6 * tets.NumPoints())
    throw InputError(std::string(who) + ": the metric must have 6 values per point");
  for (double v : tets.Points)
    if (!std::isfinite(v))
      throw InputError(std::string(who) + ": non-finite point coordinate");
  for (double v : metric.Values)
    if (!std::isfinite(v))
      throw InputError(std::string(who) + ": non-finite metric value");
  const auto n = static_cast<std::int64_t>(tets.NumPoints());
  for (std::int32_t id : tets.Cells)
    if (id < 0 || id >= n)
      throw InputError(std::string(who) + ": cell point id out of range");
}
} // namespace

DomainAngleBound ComputeDomainAngleBound(const SimplexMesh& tets, const MetricField& metric)
{
  Validate(tets, metric);
  const std::size_t nc = tets.NumCells();
  // Boundary faces: the sorted triples that occur once.
  std::vector<std::array<std::int32_t, 3>> faces;
  faces.reserve(4 * nc);
  for (std::size_t c = 0; c < nc; ++c)
  {
    const std::int32_t* t = tets.Cell(c);
    for (int m = 0; m < 4; ++m)
    {
      std::array<std::int32_t, 3> f;
      for (int i = 0, k = 0; i < 4; ++i)
        if (i != m)
          f[k++] = t[i];
      std::sort(f.begin(), f.end());
      faces.push_back(f);
    }
  }
  std::sort(faces.begin(), faces.end());
  std::vector<std::uint64_t> boundaryEdges;
  for (std::size_t i = 0; i < faces.size();)
  {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j] == faces[i])
      ++j;
    if (j - i == 1)
      for (int e = 0; e < 3; ++e)
        boundaryEdges.push_back(EdgeKey(faces[i][e], faces[i][(e + 1) % 3]));
    i = j;
  }
  std::sort(boundaryEdges.begin(), boundaryEdges.end());
  boundaryEdges.erase(std::unique(boundaryEdges.begin(), boundaryEdges.end()), boundaryEdges.end());

  // The tets on each boundary edge.
  std::vector<std::pair<std::uint64_t, std::int32_t>> onEdge;
  for (std::size_t c = 0; c < nc; ++c)
  {
    const std::int32_t* t = tets.Cell(c);
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
      {
        const std::uint64_t k = EdgeKey(t[i], t[j]);
        if (std::binary_search(boundaryEdges.begin(), boundaryEdges.end(), k))
          onEdge.emplace_back(k, static_cast<std::int32_t>(c));
      }
  }
  std::sort(onEdge.begin(), onEdge.end());

  std::vector<Eigen::Matrix3d> roots(tets.NumPoints());
  for (std::size_t i = 0; i < roots.size(); ++i)
    roots[i] = SymmetricSqrt(UnpackSymmetric(metric.At(i)));
  auto point = [&](std::int32_t v) { return Eigen::Map<const Eigen::Vector3d>(tets.Point(v)); };

  DomainAngleBound result;
  result.NumBoundaryEdges = boundaryEdges.size();
  for (std::size_t i = 0; i < onEdge.size();)
  {
    std::size_t j = i;
    const std::uint64_t k = onEdge[i].first;
    const auto a = static_cast<std::int32_t>(k >> 32);
    const auto b = static_cast<std::int32_t>(k & 0xffffffffu);
    const Eigen::Matrix3d map = 0.5 * (roots[a] + roots[b]);
    const Eigen::Vector3d pa = map * point(a);
    const Eigen::Vector3d axis = (map * point(b) - pa).normalized();
    double sum = 0.0;
    for (; j < onEdge.size() && onEdge[j].first == k; ++j)
    {
      const std::int32_t* t = tets.Cell(static_cast<std::size_t>(onEdge[j].second));
      Eigen::Vector3d side[2];
      for (int v = 0, s = 0; v < 4; ++v)
        if (t[v] != a && t[v] != b)
        {
          const Eigen::Vector3d d = map * point(t[v]) - pa;
          side[s++] = d - axis * axis.dot(d);
        }
      const double denominator = side[0].norm() * side[1].norm();
      if (denominator > 0.0)
        sum += std::acos(std::clamp(side[0].dot(side[1]) / denominator, -1.0, 1.0));
    }
    const double degrees = sum * 180.0 / Pi;
    result.MinAngle = std::min(result.MinAngle, degrees);
    result.NumBelow15 += degrees < 15.0 ? 1 : 0;
    result.NumBelow20 += degrees < 20.0 ? 1 : 0;
    i = j;
  }
  return result;
}

} // namespace av
