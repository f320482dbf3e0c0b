// SPDX-License-Identifier: BSD-3-Clause
// SimplexSplitter: splits VTK's linear and quadratic cells into conforming, positively oriented
// simplices (the embedding and RVD kernels only know triangles and tetrahedra). VTK-free: cell
// types are VTK's numeric ids.
#ifndef av_SimplexSplitter_h
#define av_SimplexSplitter_h

#include "SimplexMesh.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace av
{

/**
 * Result of SplitIntoSimplices. Every output point i is a weighted combination of input
 * points: PointParents[PointParentOffsets[i] .. PointParentOffsets[i + 1]) with the matching
 * PointWeights (sum 1), so point data is interpolated the same way. Input points that no
 * simplex uses (mid-edge nodes of quadratic cells, orphans) are dropped; when none is dropped,
 * output point i is input point i for i < number of input points (InputPointsKept).
 */
struct SimplexSplitResult
{
  SimplexMesh Mesh;                           ///< triangles (2D cells) or tetrahedra (3D cells)
  std::vector<std::int32_t> CellParent;       ///< input cell id of each output simplex
  std::vector<std::int64_t> PointParentOffsets; ///< NumPoints + 1 entries
  std::vector<std::int64_t> PointParents;     ///< input point ids
  std::vector<double> PointWeights;           ///< interpolation weights
  std::size_t NumAddedPoints = 0;   ///< Steiner points (hexahedron centers), last in Mesh.Points
  std::size_t NumDroppedSimplices = 0; ///< zero-measure pieces of collapsed (degenerate) cells
  bool InputPointsKept = true;
};

/**
 * @brief Splits cells into simplices, conforming across shared faces.
 *
 * points: numPoints x 3 coordinates. Cells in VTK's layout: types[c] (VTK cell type id),
 * connectivity[offsets[c] .. offsets[c + 1]) (offsets has numCells + 1 entries).
 * Supported: TETRA 10, TRIANGLE 5, QUAD 9, PIXEL 8, HEXAHEDRON 12, VOXEL 11, WEDGE 13,
 * PYRAMID 14, and the quadratic QUADRATIC_TRIANGLE 22, QUADRATIC_QUAD 23, QUADRATIC_TETRA 24,
 * QUADRATIC_HEXAHEDRON 25, QUADRATIC_WEDGE 26, QUADRATIC_PYRAMID 27, BIQUADRATIC_QUAD 28,
 * TRIQUADRATIC_HEXAHEDRON 29 (reduced to their corner nodes: curved edges become straight).
 *
 * Rules (all decided from global point ids, so both sides of a shared face agree):
 * - a quadrilateral face is cut by the diagonal through its smallest point id;
 * - wedge: 3 tets, no new point (rotated so the smallest id is vertex 0; this never meets
 *   the cyclic face configuration that would need one, Dompierre et al. 1999);
 * - pyramid: 2 tets; quad, pixel: 2 triangles;
 * - hexahedron, voxel: one new point at the center (mean of the 8 corners) and 12 tets, one per
 *   face triangle: the min-id rule alone cannot split every hexahedron without new points.
 * Orientation: tetrahedra positive (det[b-a, c-a, d-a] > 0). Triangles keep the cell's
 * orientation; with outputAmbientDim 2 (z dropped) they are made counter-clockwise.
 * Pieces of zero measure (collapsed cells) are dropped and counted.
 * Throws InputError on: no cells, unsupported types (named), a mix of 2D and 3D cells, wrong
 * point count for a type, ids out of range, NaN/Inf coordinates, bad offsets.
 */
SimplexSplitResult SplitIntoSimplices(const double* points, std::size_t numPoints,
  const std::uint8_t* types, const std::int64_t* offsets, const std::int64_t* connectivity,
  std::size_t numCells, int outputAmbientDim = 3);

/// VTK's name of a cell type id ("VTK_POLYGON"), or "cell type <id>" when unknown here.
std::string VtkCellTypeName(int vtkCellType);

} // namespace av

#endif
