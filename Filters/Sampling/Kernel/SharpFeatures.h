// SPDX-License-Identifier: BSD-3-Clause
// SharpFeatures: feature lines and corners of a simplicial mesh (paper §4.1, "Boundary and
// Sharp Feature Handling"), VTK-free. The sampler keeps particles on the lines and fixes one at
// each corner, so that the dual mesh reproduces the domain's edges and corners.
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

} // namespace av

#endif
