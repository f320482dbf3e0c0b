// SPDX-License-Identifier: BSD-3-Clause
// TetMesher: quality tetrahedral meshes of closed triangle surfaces (TetGen), plus ready-made
// box and ball meshes with a target vertex count. VTK-free.
#ifndef av_TetMesher_h
#define av_TetMesher_h

#include "SimplexMesh.h"

#include <cstddef>

namespace av
{

/// Options of TetrahedralizeClosedSurface (TetGen's -q, -a, -Y switches).
struct TetMeshOptions
{
  /// Upper bound on the volume of every tetrahedron (TetGen -a); 0 = no bound.
  double MaxVolume = 0.0;
  /// Bound on circumradius / shortest edge (TetGen -q); 0 = no quality refinement.
  /// TetGen needs > 1 (values close to 1 may not terminate); 1.5 is a safe default.
  double RadiusEdgeRatio = 1.5;
  /// Lower bound on the dihedral angles in degrees (TetGen -q ratio/angle); 0 = TetGen default.
  double MinDihedral = 0.0;
  /// Keep the input surface triangles unsplit (TetGen -Y): the output boundary is exactly
  /// the input surface.
  bool PreserveSurface = false;
  /// Silence TetGen's console output (TetGen -Q).
  bool Quiet = true;
  /// Run TetGen's self-intersection check (-d) first. TetGen 1.5.0 crashes (double free)
  /// when meshing fails on a self-intersecting surface instead of reporting it, so keep this
  /// on for surfaces you did not generate yourself. Costs about as much as the meshing.
  bool DetectSelfIntersections = true;
};

/**
 * @brief Tetrahedralizes the volume enclosed by a closed, manifold triangle surface.
 *
 * Input: AmbientDim 3, SimplexDim 2, every edge shared by exactly two triangles, no
 * degenerate triangle, no repeated triangle. Output: AmbientDim 3, SimplexDim 3, every
 * tetrahedron positively oriented (det[b-a, c-a, d-a] > 0), no unused vertex. The first
 * vertices are the input vertices in their order when PreserveSurface is set (and, in
 * practice, also otherwise: TetGen keeps its input points first).
 * Throws InputError on invalid input or when TetGen fails (self-intersection, ...).
 */
SimplexMesh TetrahedralizeClosedSurface(
  const SimplexMesh& triangleSurface, const TetMeshOptions& options);

/**
 * Signed volume enclosed by a closed triangle surface (divergence theorem; positive when the
 * triangles are oriented outwards).
 */
double EnclosedVolume(const SimplexMesh& triangleSurface);

/**
 * TetGen's volume bound (-a) that gives about `targetVertices` vertices inside the closed
 * `triangleSurface`: a quality mesh has about 5 tetrahedra per vertex.
 */
double MaxVolumeForVertexCount(const SimplexMesh& triangleSurface, std::size_t targetVertices);

/**
 * @brief Quality tet mesh of the box [lo, hi] with about `targetVertices` vertices
 * (typically within 15 %). targetVertices >= 8.
 */
SimplexMesh TetrahedralizeBox(const double lo[3], const double hi[3], std::size_t targetVertices);

/**
 * @brief Quality tet mesh of the ball of the given radius centered at the origin, with about
 * `targetVertices` vertices (typically within 15 %). The boundary vertices lie on the sphere
 * (geodesic sphere surface, refined by TetGen on its flat facets only where needed).
 * targetVertices >= 20.
 */
SimplexMesh TetrahedralizeSphere(double radius, std::size_t targetVertices);

/**
 * Delaunay tetrahedralization of the convex hull of `points` (NumPoints x 3) by TetGen, without
 * Steiner points: cell ids index `points` (the returned mesh holds a copy of them), every tet
 * positively oriented. Exactly repeated points are merged by TetGen: the cells use the first
 * of them, the others are in no cell. Throws InputError when TetGen fails or all points are
 * coplanar.
 */
SimplexMesh DelaunayOfPoints(const std::vector<double>& points);

/**
 * Constrained Delaunay tetrahedralization of the convex hull of `points` whose faces include
 * the triangles `faces` (NumFaces x 3 point ids; the faces of a valid partial tet mesh, say),
 * by TetGen (-pc), without Steiner points: cell ids index `points`, every tet positive. Throws
 * InputError when TetGen fails, the faces intersect, or it needs a Steiner point to recover
 * them.
 */
SimplexMesh ConstrainedDelaunayOfPoints(const std::vector<double>& points,
  const std::vector<std::int32_t>& faces);

} // namespace av

#endif
