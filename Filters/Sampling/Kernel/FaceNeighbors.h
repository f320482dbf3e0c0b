// SPDX-License-Identifier: BSD-3-Clause
// FaceNeighbors: the particle sampler's lazy face-neighbor lookup (vertex -> incident cells,
// the cell across one face), internal to the sampler.
#ifndef av_FaceNeighbors_h
#define av_FaceNeighbors_h

#include "SimplexMesh.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{
namespace sampling
{

/**
 * Vertex -> incident cells (CSR); faces are matched by intersecting these short lists.
 *
 * Why not ComputeElementAdjacency (MeshTopology.h): it gives the same neighbors on manifold
 * meshes without repeated vertex ids (checked on cube2's 240k tets and a triangle grid), but
 * differs on other inputs the sampler accepts. (1) A face shared by three or more cells (a
 * non-manifold surface, or tets with PreserveSharpFeatures off) makes it throw, while
 * FaceNeighbor returns -1 there and the particles slide along that face as on a boundary.
 * (2) A cell that lists a vertex twice has two facets with the same vertices, which it pairs
 * with each other (the cell becomes its own neighbor), or throws when a third cell shares
 * them; FaceNeighbor skips the cell itself. Besides, the sampler asks only for the faces of
 * the cells its particles visit: a whole-mesh adjacency costs 0.15-0.25 s on cube2 (2-core
 * VM), a quarter of the sampler's run.
 */
struct VertexCells
{
  std::vector<std::int64_t> Offs;
  std::vector<std::int32_t> Inc;
};

VertexCells BuildVertexCells(const SimplexMesh& mesh);

/// The cell across the face of cell c opposite its local vertex i (-1: boundary, or more
/// than two cells share the face).
std::int32_t FaceNeighbor(const SimplexMesh& mesh, const VertexCells& vc, std::size_t c, int i);

} // namespace sampling
} // namespace av

#endif
