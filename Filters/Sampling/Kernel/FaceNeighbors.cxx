// SPDX-License-Identifier: BSD-3-Clause
// FaceNeighbors: vertex -> cell incidence and the face-neighbor query of the particle sampler.
#include "FaceNeighbors.h"

#include <algorithm>
#include <utility>

namespace av
{
namespace sampling
{

VertexCells BuildVertexCells(const SimplexMesh& mesh)
{
  const std::size_t nc = mesh.NumCells(), np = mesh.NumPoints();
  const int nv = mesh.VerticesPerCell();
  VertexCells vc;
  vc.Offs.assign(np + 1, 0);
  for (auto v : mesh.Cells)
    ++vc.Offs[static_cast<std::size_t>(v) + 1];
  for (std::size_t i = 0; i < np; ++i)
    vc.Offs[i + 1] += vc.Offs[i];
  vc.Inc.resize(mesh.Cells.size());
  std::vector<std::int64_t> fill(vc.Offs.begin(), vc.Offs.end() - 1);
  for (std::size_t c = 0; c < nc; ++c)
    for (int i = 0; i < nv; ++i)
      vc.Inc[static_cast<std::size_t>(fill[static_cast<std::size_t>(mesh.Cell(c)[i])]++)] =
        static_cast<std::int32_t>(c);
  return vc;
}

std::int32_t FaceNeighbor(const SimplexMesh& mesh, const VertexCells& vc, std::size_t c, int i)
{
  const int nv = mesh.VerticesPerCell();
  const std::int32_t* ids = mesh.Cell(c);
  const auto& offs = vc.Offs;
  std::int32_t face[3] = { 0, 0, 0 };
  int nfv = 0;
  for (int j = 0; j < nv; ++j)
    if (j != i)
      face[nfv++] = ids[j];
  // Scan the shortest incidence list among the face's vertices.
  for (int a = 1; a < nfv; ++a)
  {
    const auto va = static_cast<std::size_t>(face[a]);
    const auto v0 = static_cast<std::size_t>(face[0]);
    if (offs[va + 1] - offs[va] < offs[v0 + 1] - offs[v0])
      std::swap(face[0], face[a]);
  }
  std::int32_t found = -1;
  int count = 0;
  const auto v0 = static_cast<std::size_t>(face[0]);
  for (auto k = offs[v0]; k < offs[v0 + 1]; ++k)
  {
    const std::int32_t other = vc.Inc[static_cast<std::size_t>(k)];
    if (other == static_cast<std::int32_t>(c))
      continue;
    const std::int32_t* oids = mesh.Cell(static_cast<std::size_t>(other));
    bool all = true;
    for (int a = 1; a < nfv && all; ++a)
      all = std::find(oids, oids + nv, face[a]) != oids + nv;
    if (all)
    {
      found = other;
      ++count;
    }
  }
  return count == 1 ? found : -1;
}

} // namespace sampling
} // namespace av
