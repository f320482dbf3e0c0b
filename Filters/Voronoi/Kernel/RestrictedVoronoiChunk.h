// SPDX-License-Identifier: BSD-3-Clause
// Internal to the Voronoi kernel: Chunk, the output of one block of elements, in the layout of
// RestrictedVoronoiDiagram with counts instead of offsets (concatenated in block order).
#ifndef av_RestrictedVoronoiChunk_h
#define av_RestrictedVoronoiChunk_h

#include "RestrictedVoronoi.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{
namespace rvd
{

struct Chunk
{
  std::vector<std::int32_t> PieceSite, PieceElement;
  std::vector<double> PieceMeasure, PieceEmbeddedMeasure;
  std::vector<std::int64_t> PieceVertexCount, PieceFaceCount;
  std::vector<double> Points, EmbeddedPoints;
  std::vector<std::int32_t> VertexPlanes;
  std::vector<std::int64_t> FaceSize;
  std::vector<std::int32_t> FaceVertices; // local to the chunk
  std::vector<RVDFaceKind> FaceKind;
  std::vector<std::int32_t> FaceNeighbor;
  std::vector<std::int32_t> VoronoiVertexSites, VoronoiVertexElement, BoundaryDualFaces;
  // Per processed element: nearest site, pieces / Voronoi vertex / boundary records emitted.
  std::vector<std::int32_t> ElemNearest, ElemPieces, ElemVV, ElemBD;
  std::vector<std::uint8_t> ElemEmptyVisit; // a visited site had an empty piece
  std::vector<float> PieceRadius2, PieceLastCut; // rounded up
  std::size_t NumWholeElements = 0;              // emitted by the fast path
};

} // namespace rvd
} // namespace av

#endif
