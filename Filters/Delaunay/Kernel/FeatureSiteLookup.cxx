// SPDX-License-Identifier: BSD-3-Clause
#include "FeatureSiteLookup.h"

#include "MeshTopology.h"

#include <utility>

namespace av
{
FeatureSiteLookup::FeatureSiteLookup(const SharpFeatures& features)
  : Features(features)
{
  Index.reserve(features.NumEdges() * 2);
  for (std::size_t e = 0; e < features.NumEdges(); ++e)
    Index.emplace(
      EdgeKey(features.Edges[2 * e], features.Edges[2 * e + 1]), static_cast<std::int32_t>(e));
}

std::int32_t FeatureSiteLookup::Find(std::int32_t u, std::int32_t v) const
{
  const auto it = Index.find(EdgeKey(u, v));
  return it == Index.end() ? -1 : it->second;
}

std::int32_t FeatureSiteLookup::EdgeOfSite(
  const SimplexMesh& mesh, const SiteSet& sites, std::size_t s, double* t) const
{
  const std::int32_t cell = sites.CellIds[s];
  if (cell < 0 || static_cast<std::size_t>(cell) >= mesh.NumCells())
    return -1;
  const std::int32_t* tri = mesh.Cell(static_cast<std::size_t>(cell));
  const double* b = sites.Bary.data() + 4 * s;
  for (int i = 0; i < 3; ++i)
  {
    if (b[i] != 0.0)
      continue;
    const std::int32_t u = tri[(i + 1) % 3], v = tri[(i + 2) % 3];
    const std::int32_t e = Find(u, v);
    if (e < 0)
      continue;
    if (t)
      *t = Features.Edges[2 * static_cast<std::size_t>(e)] == u ? b[(i + 2) % 3] : b[(i + 1) % 3];
    return e;
  }
  return -1;
}

} // namespace av
