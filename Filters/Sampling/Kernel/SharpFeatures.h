// SPDX-License-Identifier: BSD-3-Clause
// SharpFeatures: feature lines and corners of a simplicial mesh (paper §4.1, "Boundary and
// Sharp Feature Handling"), found by angle or given (patch ids, edge lists), VTK-free. The
// sampler keeps particles on the lines and fixes one at each corner, so that the dual mesh
// reproduces the domain's edges and corners.
#ifndef av_SharpFeatures_h
#define av_SharpFeatures_h

#include "SimplexMesh.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{

/// Feature lines (made of mesh edges) and corner points of a mesh.
struct SharpFeatures
{
  /// Feature edges, two point ids each (smaller id first), sorted. Particles on them stay on them.
  std::vector<std::int32_t> Edges;
  /// Per feature edge: a cell containing it and the local indices (0..k) of its two points in
  /// that cell, in the order of Edges.
  std::vector<std::int32_t> EdgeCells;
  std::vector<std::int8_t> EdgeLocal;
  /// Corner points, sorted; each with a cell containing it and its local index there.
  std::vector<std::int32_t> Corners;
  std::vector<std::int32_t> CornerCells;
  std::vector<std::int8_t> CornerLocal;
  /// CSR map point -> incident feature edges (indices into Edges / 2): entries
  /// PointEdges[PointEdgeOffsets[p] .. PointEdgeOffsets[p + 1]).
  std::vector<std::int32_t> PointEdgeOffsets;
  std::vector<std::int32_t> PointEdges;
  /// 1 for the corner points (NumPoints entries).
  std::vector<std::uint8_t> IsCorner;

  std::size_t NumEdges() const { return Edges.size() / 2; }
};

/**
 * Finds the sharp features of `mesh` with the dihedral-angle test of VTK's vtkFeatureEdges:
 * - tetrahedra: a boundary edge is a feature edge when the outward normals of its two boundary
 *   triangles differ by more than featureAngleDegrees, or when it has other than two boundary
 *   triangles (non-manifold);
 * - triangles in 3D (surfaces): an interior edge is a feature edge (a crease) when the normals
 *   of its two triangles differ by more than the angle, or when more than two triangles share
 *   it; the surface's own boundary is not a feature line (particles already slide along it);
 * - triangles in 2D: no feature lines (the boundary is already a line).
 * Corners: points where the feature lines (for triangle meshes: feature edges together with
 * boundary edges) meet other than two at a time (1 = a line's free end, 3 or more = a
 * junction), or where two of them turn by more than featureAngleDegrees.
 * A feature angle of 180 or more disables the detection (empty result).
 * Throws InputError on a bad angle (NaN, <= 0), bad point ids, an empty mesh or (tets) a
 * triangle shared by more than two tets.
 */
SharpFeatures DetectSharpFeatures(const SimplexMesh& mesh, double featureAngleDegrees = 30.0);

/**
 * Feature lines given by patch ids, one per triangle of a surface in 3D (CAD face ids, Medit
 * triangle references, region ids): the edges between triangles of different ids and the
 * non-manifold edges, whatever their dihedral angle. Corners as in DetectSharpFeatures (line
 * degree other than 2 with the surface boundary counting, or a turn sharper than
 * featureAngleDegrees; 180: no turn rule), plus the points flagged in `corners` (one flag per
 * point; null: none). Throws InputError when the mesh is not a triangle surface in 3D, or the
 * ids or flags are not one per triangle / point.
 */
SharpFeatures SharpFeaturesFromPatches(const SimplexMesh& mesh,
  const std::vector<std::int32_t>& patchIds,
  const std::vector<std::uint8_t>* corners = nullptr,
  double featureAngleDegrees = 30.0);

/**
 * The given feature edges (two point ids each, edges of `mesh`, any order, duplicates merged)
 * and corners (point ids), plus corners where the edges meet other than two at a time (a
 * line's free end, a junction): the Edges and Corners of features found on the same mesh by
 * an earlier step (passed between filters: the same features again), or a file's ridges and
 * corners (Medit `Ridges`, `Corners`). Throws InputError on a bad id, an edge that is not an
 * edge of the mesh or an odd edge list.
 */
SharpFeatures SharpFeaturesFromEdges(const SimplexMesh& mesh,
  const std::vector<std::int32_t>& edges,
  const std::vector<std::int32_t>& corners);

} // namespace av

#endif
