// SPDX-License-Identifier: BSD-3-Clause
// SurfaceFidelity: how faithful a remeshed surface is to its input (paper §6.3): sampled
// two-sided Hausdorff distance, self-intersecting triangle pairs, triangles flipped against
// the input's normals, Euler characteristic and boundary loops. VTK-free.
#ifndef av_SurfaceFidelity_h
#define av_SurfaceFidelity_h

#include "SimplexMesh.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{

/// Result of SampledHausdorffDistance; distances in input units and in % of the bounding-box
/// diagonal of the reference surface.
struct HausdorffResult
{
  double ForwardMax = 0.0;  ///< max over samples of `surface` of the distance to `reference`
  double BackwardMax = 0.0; ///< max over samples of `reference` of the distance to `surface`
  double Max = 0.0;         ///< max of both: the sampled Hausdorff distance
  double ForwardMean = 0.0; ///< mean distance of the forward samples
  double Diagonal = 0.0;    ///< bounding-box diagonal of `reference`
  double MaxPercent = 0.0;  ///< 100 Max / Diagonal
  std::size_t Samples = 0;  ///< forward + backward sample points
};

/**
 * Sampled Hausdorff distance between two triangle surfaces in 3D. Each triangle of either
 * surface is sampled at the barycentric grid points (i, j, k) / n, i + j + k = n, n =
 * `samplesPerEdge` >= 1 (so vertices and edge points are included); each sample's exact
 * distance to the other surface comes from a TriangleBvh. A lower bound of the true Hausdorff
 * distance that converges as n grows. Runs in parallel (TBB).
 * Throws InputError for meshes that are not non-empty triangle surfaces in 3D.
 */
HausdorffResult SampledHausdorffDistance(const SimplexMesh& surface,
  const SimplexMesh& reference,
  int samplesPerEdge = 3);

/**
 * Number of pairs of triangles that share no vertex and intersect (touching counts), the
 * paper's "self-intersecting faces" measure. Candidate pairs come from a TriangleBvh; the test
 * is segment against triangle on both triangles' edges with orientation predicates that are
 * evaluated in double with Shewchuk's static error bound and, when that is not conclusive,
 * again in 113-bit binary128 arithmetic (exact differences, products rounded far below double
 * precision). Coplanar pairs are tested in the projection of largest area. Runs in parallel.
 */
std::size_t CountSelfIntersections(const SimplexMesh& surface);

/**
 * One flag per triangle of `surface`: 1 where it intersects another triangle with which it
 * shares no vertex (the pairs CountSelfIntersections counts). Runs in parallel.
 */
std::vector<std::uint8_t> SelfIntersectingTriangles(const SimplexMesh& surface);

/**
 * Triangles of `surface` whose normal points against `vertexNormals` (3 per vertex of
 * `surface`, e.g. the input surface's normals interpolated at the output vertices): the dot
 * product of the triangle normal with the mean of its vertices' reference normals is <= 0.
 * `flipped`, if given, gets one flag per triangle.
 */
std::size_t CountFlippedTriangles(const SimplexMesh& surface,
  const std::vector<double>& vertexNormals,
  std::vector<std::uint8_t>* flipped = nullptr);

/**
 * Reference normals for CountFlippedTriangles when only the reference surface is known: at each
 * vertex of `surface`, the unit normal of the closest triangle of `reference` (from a
 * TriangleBvh; zero for a degenerate closest triangle). 3 values per vertex. Runs in parallel.
 */
std::vector<double> ClosestTriangleNormals(const SimplexMesh& surface,
  const SimplexMesh& reference);

/// Euler characteristic V - E + F of the used vertices, and the count of boundary loops.
struct SurfaceTopology
{
  long long Euler = 0;
  std::size_t BoundaryLoops = 0;
  std::size_t BoundaryEdges = 0;
  std::size_t NonManifoldEdges = 0; ///< edges of more than two triangles
  std::size_t Components = 0;       ///< connected components of the triangles
};

/// Topology of a triangle surface; boundary loops are the cycles of boundary edges (a vertex
/// with more than two boundary edges joins its loops into one).
SurfaceTopology ComputeSurfaceTopology(const SimplexMesh& surface);

/// All fidelity measures of a remeshed surface (EvaluateSurfaceFidelity).
struct SurfaceFidelityResult
{
  SurfaceTopology Topology;
  std::size_t SelfIntersections = 0;
  bool HasReference = false; ///< the fields below are set only with a reference
  SurfaceTopology ReferenceTopology;
  HausdorffResult Hausdorff;
  std::size_t Flipped = 0;
  std::vector<std::uint8_t> FlippedFlags; ///< one per triangle of the surface
};

/**
 * Topology and self-intersections of `surface`; with a `reference` (may be null), also the
 * reference's topology, the sampled Hausdorff distance (`samplesPerEdge`) and the triangles
 * flipped: whose normal disagrees both with the reference's closest-triangle normals at its
 * vertices (CountFlippedTriangles with ClosestTriangleNormals) and with the normal of the
 * reference triangle closest to its centroid. Each test alone flags unflipped triangles at
 * creases (at a vertex on a crease the closest triangle may be either face's; the centroid of
 * a triangle cutting across a crease may project onto the face nearly perpendicular to it).
 * Throws InputError for inputs that are not non-empty triangle surfaces in 3D.
 */
SurfaceFidelityResult EvaluateSurfaceFidelity(const SimplexMesh& surface,
  const SimplexMesh* reference,
  int samplesPerEdge = 3);

} // namespace av

#endif
