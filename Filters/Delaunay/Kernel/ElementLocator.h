// SPDX-License-Identifier: BSD-3-Clause
// LocateInMesh: the element of a volume (or flat 2D) mesh that holds a point, by a walk.
#ifndef av_ElementLocator_h
#define av_ElementLocator_h

#include "SimplexMesh.h"

#include <cstdint>
#include <vector>

namespace av
{

/**
 * Walks from `cell` towards x (AmbientDim values; AmbientDim == SimplexDim) across the facet of
 * the most negative barycentric coordinate (`adjacency` as from ComputeElementAdjacency). True
 * when an element holds x (to 1e-12): `cell` is then that element and `lambda` (SimplexDim + 1
 * values, clamped to >= 0 and normalized) its barycentric coordinates. False when the walk
 * leaves the domain (x outside, or behind a concave part of the boundary) or takes more than
 * 512 steps.
 */
bool LocateInMesh(const SimplexMesh& mesh, const std::vector<std::int32_t>& adjacency,
  std::int32_t& cell, const double* x, double* lambda);

} // namespace av

#endif
