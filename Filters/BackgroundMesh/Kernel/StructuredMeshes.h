// SPDX-License-Identifier: BSD-3-Clause
// StructuredMeshes: regular simplicial grids of boxes and rectangles (generated domains for the
// analytic presets, the benchmark and the tests).
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
 * The same Kuhn grid on a rectilinear lattice: vertex (i, j, k) at (xs[i], ys[j], zs[k]), each list
 * strictly increasing with at least 2 values (graded backgrounds, e.g. BoundaryLayerLevels).
 */
SimplexMesh MakeKuhnTetGrid(
  const std::vector<double>& xs, const std::vector<double>& ys, const std::vector<double>& zs);

/**
 * Triangle grid of the rectangle [lo, hi]: nx x ny vertices (each >= 2), point id i + nx * j,
 * 2 counter-clockwise triangles per square (AmbientDim 2, SimplexDim 2).
 */
SimplexMesh MakeTriangleGrid(int nx, int ny, const double lo[2], const double hi[2]);

} // namespace av

#endif
