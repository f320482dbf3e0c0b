// StructuredMeshes: regular simplicial grids for tests/benchmarks, plus small topology helpers
// (unique edges, boundary vertices, signed cell measures) that work on any SimplexMesh.
#ifndef av_StructuredMeshes_h
#define av_StructuredMeshes_h

#include "SimplexMesh.h"

#include <cstdint>
#include <vector>

namespace av
{

/**
 * Kuhn (Freudenthal) tetrahedral grid of the box [lo, hi]: nx x ny x nz vertices (each >= 2),
 * point id i + nx * (j + ny * k), 6 tetrahedra per cube sharing the cube diagonal, all
 * positively oriented (det[p1-p0, p2-p0, p3-p0] > 0). Conforming across cubes.
 */
SimplexMesh MakeKuhnTetGrid(int nx, int ny, int nz, const double lo[3], const double hi[3]);

/**
 * Triangle grid of the rectangle [lo, hi]: nx x ny vertices (each >= 2), point id i + nx * j,
 * 2 counter-clockwise triangles per square (AmbientDim 2, SimplexDim 2).
 */
SimplexMesh MakeTriangleGrid(int nx, int ny, const double lo[2], const double hi[2]);

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

} // namespace av

#endif
