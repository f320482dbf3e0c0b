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

  /// Empties every array but keeps its capacity: a thread's scratch, reused block after block
  /// (a block's chunk is then copied from it at its exact size, without growth slack).
  void Clear()
  {
    for (auto* v : { &PieceSite,
           &PieceElement,
           &FaceVertices,
           &FaceNeighbor,
           &VoronoiVertexSites,
           &VoronoiVertexElement,
           &BoundaryDualFaces,
           &VertexPlanes,
           &ElemNearest,
           &ElemPieces,
           &ElemVV,
           &ElemBD })
      v->clear();
    for (auto* v : { &PieceMeasure, &PieceEmbeddedMeasure, &Points, &EmbeddedPoints })
      v->clear();
    for (auto* v : { &PieceVertexCount, &PieceFaceCount, &FaceSize })
      v->clear();
    for (auto* v : { &PieceRadius2, &PieceLastCut })
      v->clear();
    FaceKind.clear();
    ElemEmptyVisit.clear();
    NumWholeElements = 0;
  }
};

} // namespace rvd
} // namespace av

#endif
