// SPDX-License-Identifier: BSD-3-Clause
// SurfaceGenerators: closed/open triangle surfaces built by code (spheres, boxes, cylinders,
// tori, Dupin cyclides),
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

/**
 * @brief Torus (or an open patch of it) as a structured triangle grid:
 * x = (R + r cos v) cos u, y = (R + r cos v) sin u, z = r sin v, R > r > 0.
 * `around` >= 3 vertex columns along u (the big circle), `tube` >= 3 rows along v.
 * uFraction, vFraction in (0, 1] are the covered parts of [0, 2 pi): 1 closes that direction
 * (periodic), less leaves an open boundary (an extra column / row of vertices is added).
 * Both 1: closed, genus 1, around * tube vertices. Outward oriented (normal along
 * (cos v cos u, cos v sin u, sin v)).
 */
SimplexMesh MakeTorusSurface(double majorRadius, double minorRadius, int around, int tube,
  double uFraction = 1.0, double vFraction = 1.0);

/// Point of the torus at parameters (u, v) (the closed form of MakeTorusSurface).
void TorusPoint(double majorRadius, double minorRadius, double u, double v, double xyz[3]);

/**
 * @brief Ring Dupin cyclide (the paper's Cyclide models, Figs. 5, 6, 13) as a closed,
 * periodic triangle grid of nu x nv vertices (genus 1), outward oriented:
 * with b^2 = a^2 - c^2 and D = a - c cos u cos v,
 *   x = (mu (c - a cos u cos v) + b^2 cos u) / D,
 *   y = b sin u (a - mu cos v) / D,
 *   z = b sin v (c cos u - mu) / D,
 * u, v in [0, 2 pi). Needs 0 <= c < mu < a (ring cyclide: no singular point). The u and v
 * parameter lines are the lines of curvature (all circles), which makes the principal
 * directions known in closed form. Cyclide1 (10,800 vertices): a = 2, c = 1, mu = 1.5,
 * nu = 120, nv = 90; Cyclide2 (25,920): a = 2, c = 1.9, mu = 1.95, nu = 180, nv = 144.
 * Each quad is split along its shorter diagonal.
 */
SimplexMesh MakeDupinCyclideSurface(double a, double c, double mu, int nu, int nv);

/// Point of the Dupin cyclide at parameters (u, v) (the closed form above).
void DupinCyclidePoint(double a, double c, double mu, double u, double v, double xyz[3]);

} // namespace av

#endif
