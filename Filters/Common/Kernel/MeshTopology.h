// SPDX-License-Identifier: BSD-3-Clause
// MeshTopology: connectivity and measures of any SimplexMesh (element adjacency, unique edges,
// boundary vertices, cell measures), shared by every stage.
#ifndef av_MeshTopology_h
#define av_MeshTopology_h

#include "SimplexMesh.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace av
{

/// Key of the undirected edge a-b (smaller id in the high half), for hashing and sorting edges.
inline std::uint64_t EdgeKey(std::int32_t a, std::int32_t b)
{
  const std::uint32_t lo = static_cast<std::uint32_t>(a < b ? a : b);
  const std::uint32_t hi = static_cast<std::uint32_t>(a < b ? b : a);
  return (static_cast<std::uint64_t>(lo) << 32) | hi;
}

/// Neighbor element across each facet: NumCells x (SimplexDim+1), -1 on the domain boundary.
/// Facet a of a cell is the one opposite its local vertex a. Throws InputError when a facet is
/// shared by more than two cells (non-manifold mesh).
std::vector<std::int32_t> ComputeElementAdjacency(const SimplexMesh& mesh);

/// Bodies: classes of cells connected through shared points. Two parts that touch with separate
/// points (an FE assembly in contact, a mesh whose coincident nodes were never merged) are two
/// bodies. Writes each point's body (0 .. count-1, in order of first cell; -1 for points of no
/// cell) and returns the count.
std::size_t LabelBodies(const SimplexMesh& mesh, std::vector<std::int32_t>& pointBody);

/// Tets: edges on more than two boundary faces, where the domain touches itself along an edge
/// (two parts joined by an edge only, or a notch closed down to an edge). A tet mesh of a
/// manifold domain has none.
std::size_t CountPinchedBoundaryEdges(const SimplexMesh& tets);

/// Throws InputError("<who><kind> c references point p, outside [0, n)") for the first cell id
/// out of range; `kind` names the cells in the message ("triangle", "cell").
void CheckCellIds(const SimplexMesh& mesh, const std::string& who, const char* kind);

/// A facet of a cell: its SimplexDim vertex ids sorted (-1 in the unused last entry of a
/// triangle's edge) and the cell.
struct CellFacet
{
  std::array<std::int32_t, 3> Vertices;
  std::int32_t Cell;
  bool operator<(const CellFacet& o) const
  {
    return Vertices != o.Vertices ? Vertices < o.Vertices : Cell < o.Cell;
  }
};

/// Every facet of every cell, sorted by vertices then cell: the cells that share a facet are
/// neighbors in the list (a run of one: boundary; of more than two: non-manifold).
std::vector<CellFacet> SortedCellFacets(const SimplexMesh& mesh);

/// Unique edges of the mesh as a flat list (a0, b0, a1, b1, ...) with a < b, sorted.
std::vector<std::int32_t> UniqueEdges(const SimplexMesh& mesh);

/**
 * Per-vertex flag (1 = on the boundary): vertices of the faces used by exactly one tetrahedron
 * (volumes) or of the edges used by exactly one triangle (2D domains and surfaces).
 */
std::vector<char> BoundaryVertexMask(const SimplexMesh& mesh);

/**
 * Signed measure of a cell: the volume of a tet (positive for positive orientation), the signed
 * area of a triangle in 2D, or the (unsigned) area of a triangle in 3D.
 */
double CellMeasure(const SimplexMesh& mesh, std::size_t cell);

/// Area (triangles) / volume (tets) of every cell with its vertices at the embedded coords.
std::vector<double> EmbeddedCellMeasures(const SimplexMesh& mesh, const Embedding& embedding);

} // namespace av

#endif
