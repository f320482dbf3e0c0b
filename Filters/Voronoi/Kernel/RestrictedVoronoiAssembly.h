// SPDX-License-Identifier: BSD-3-Clause
// Internal to the Voronoi kernel: the assembly of the blocks' Chunks into one
// RestrictedVoronoiDiagram (concatenation, per-element records, site sums, order by site).
#ifndef av_RestrictedVoronoiAssembly_h
#define av_RestrictedVoronoiAssembly_h

#include "RestrictedVoronoi.h"
#include "RestrictedVoronoiChunk.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{
namespace rvd
{

/// An empty diagram with the dimensions of the inputs.
RestrictedVoronoiDiagram NewDiagram(const SimplexMesh& mesh, const Embedding& embedding, std::size_t numSites);

/// Sizes the per-piece members (site, element, measures) and the dual records (Voronoi
/// vertices in records of SimplexDim+1 sites, boundary dual faces in entries).
void ResizeRecords(RestrictedVoronoiDiagram& out, std::size_t pieces, std::size_t voronoiVertices,
  std::size_t boundaryDualEntries);

/// The per-element members (offsets, nearest sites, empty visits, boundary facets) of a
/// whole-mesh run, from the chunks of all numElements elements in order. Sizes the per-piece
/// bounds, which ConcatenateChunks fills.
void FillElementRecords(const std::vector<Chunk>& chunks, const std::vector<std::int32_t>& adjacency,
  std::size_t numElements, RestrictedVoronoiDiagram& out);

/// Appends the chunks in order (deterministic) to the empty per-piece, per-vertex, per-face
/// and dual members of `out`, turning counts into offsets; releases each chunk once copied.
/// Throws InputError past 2^31 vertices.
void ConcatenateChunks(std::vector<Chunk>& chunks, const RestrictedVoronoiOptions& options,
  RestrictedVoronoiDiagram& out);

/// SiteMeasure and SiteEmbeddedMeasure: the piece measures summed in piece order.
void SumSiteMeasures(RestrictedVoronoiDiagram& out);

/// MergeBySite: the pieces reordered by site (stable: elements stay in order), vertices
/// renumbered so that every piece's vertices stay contiguous.
RestrictedVoronoiDiagram SortPiecesBySite(RestrictedVoronoiDiagram&& out, const RestrictedVoronoiOptions& options);

} // namespace rvd
} // namespace av

#endif
