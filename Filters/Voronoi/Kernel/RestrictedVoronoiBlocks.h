// SPDX-License-Identifier: BSD-3-Clause
// Internal to the Voronoi kernel: ClipElementBlocks, the clipping of a list or range of
// elements in blocks (TBB), one Chunk per block.
#ifndef av_RestrictedVoronoiBlocks_h
#define av_RestrictedVoronoiBlocks_h

#include "RestrictedVoronoi.h"
#include "RestrictedVoronoiChunk.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{
namespace rvd
{

/**
 * Clips elements first..last-1 (or list[first..last-1] when `list` is not null), block b of
 * `blockSize` of them into chunks[b] (chunks.size() blocks). Builds the site kd-tree and the
 * neighbor lists, then dispatches once on (SimplexDim, Dim) into code compiled for that
 * dimension (Dim 2, 3, 4, 5, 6, 8; any other at run time). `adjacency`: element neighbors
 * (only their sign, on the domain boundary or not, matters without ComputeGeometry).
 */
void ClipElementBlocks(const SimplexMesh& mesh, const Embedding& embedding, const SiteSet& sites,
  const RestrictedVoronoiOptions& options, const std::vector<std::int32_t>& adjacency,
  std::vector<Chunk>& chunks, std::size_t blockSize, std::size_t first, std::size_t last,
  const std::int32_t* list);

} // namespace rvd
} // namespace av

#endif
