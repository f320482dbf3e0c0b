// SPDX-License-Identifier: BSD-3-Clause
// Internal to the Voronoi kernel: the input checks of ComputeRestrictedVoronoi and
// UpdateRestrictedVoronoi beyond ValidateRestrictedVoronoiInput (elements, options).
#ifndef av_RestrictedVoronoiValidation_h
#define av_RestrictedVoronoiValidation_h

#include "RestrictedVoronoi.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{
namespace rvd
{

/// Throws InputError when one of the elements (list[0..n), or [0, n) when list is null) is
/// degenerate in the embedding: it cannot be clipped in barycentric coordinates.
void CheckDegenerateElements(const SimplexMesh& mesh, const Embedding& embedding,
  const std::int32_t* list, std::size_t n);

/// options.ElementAdjacency after a size check, or ComputeElementAdjacency(mesh) stored in
/// `own` when the caller passed none.
const std::vector<std::int32_t>& ElementAdjacencyFor(const SimplexMesh& mesh,
  const RestrictedVoronoiOptions& options, std::vector<std::int32_t>& own);

/// [first, last) of options.ElementBegin / ElementEnd; throws InputError when it is not inside
/// the mesh's numElements elements.
void ElementRangeOf(
  const RestrictedVoronoiOptions& options, std::size_t numElements, std::size_t& first, std::size_t& last);

} // namespace rvd
} // namespace av

#endif
