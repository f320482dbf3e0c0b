// SPDX-License-Identifier: BSD-3-Clause
// SurfaceGenerators: closed/open triangle surfaces built by code (spheres, boxes, cylinders),
// used as TetGen input and as test geometry. VTK-free.
#ifndef av_SurfaceGenerators_h
#define av_SurfaceGenerators_h

#include "SimplexMesh.h"

#include <cstddef>

namespace av
{

/**
 * @brief Geodesic sphere of class I: each face of an icosahedron is split into
 * frequency² triangles and the vertices are projected onto the sphere.
 * 10·frequency² + 2 vertices, 20·frequency² triangles, outward oriented (counter-clockwise
 * seen from outside). frequency >= 1.
 */
SimplexMesh MakeGeodesicSphere(double radius, int frequency);

/**
 * @brief Icosphere with `subdivisions` levels of 1-to-4 refinement (frequency 2^subdivisions):
 * 12, 42, 162, 642, 2562, 10242, 40962, ... vertices. subdivisions in [0, 9].
 */
SimplexMesh MakeIcosphere(double radius, int subdivisions);

/**
 * @brief Closed triangulated box surface [lo, hi], with n[d] >= 1 grid intervals along axis d
 * (quads split into two triangles), outward oriented.
 */
SimplexMesh MakeBoxSurface(const double lo[3], const double hi[3], const int n[3]);

/**
 * @brief Open cylinder surface (no caps) of the given radius around the z axis, z in
 * [0, height], with `around` >= 3 vertices per ring and `along` >= 1 intervals along the axis.
 * Outward oriented. Rings are rotated by half a step every other row for better triangles.
 */
SimplexMesh MakeCylinderSurface(double radius, double height, int around, int along);

} // namespace av

#endif
