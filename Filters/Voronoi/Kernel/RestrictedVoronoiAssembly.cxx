// SPDX-License-Identifier: BSD-3-Clause
// The assembly of the RVD from the blocks' Chunks: concatenation in block order (so the output
// is deterministic whatever the threads did), per-element records, site sums, order by site.
#include "RestrictedVoronoiAssembly.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>
#include <numeric>

namespace av
{
namespace rvd
{
namespace
{

// Where each chunk's items start in the concatenation (NumChunks + 1 each).
struct ChunkOffsets
{
  std::vector<std::size_t> Piece, Vertex, Face, FaceVertex, VoronoiVertex, BoundaryDual;

  ChunkOffsets(const std::vector<Chunk>& chunks, int k)
  {
    const std::size_t nchunk = chunks.size();
    for (auto* v : { &Piece, &Vertex, &Face, &FaceVertex, &VoronoiVertex, &BoundaryDual })
      v->assign(nchunk + 1, 0);
    for (std::size_t c = 0; c < nchunk; ++c)
    {
      Piece[c + 1] = Piece[c] + chunks[c].PieceSite.size();
      Vertex[c + 1] = Vertex[c] + chunks[c].VertexPlanes.size() / k;
      Face[c + 1] = Face[c] + chunks[c].FaceKind.size();
      FaceVertex[c + 1] = FaceVertex[c] + chunks[c].FaceVertices.size();
      VoronoiVertex[c + 1] = VoronoiVertex[c] + chunks[c].VoronoiVertexElement.size();
      BoundaryDual[c + 1] = BoundaryDual[c] + chunks[c].BoundaryDualFaces.size();
    }
  }
};

// Per-piece vertex / face counts and per-face sizes of the concatenation (geometry only).
struct GeometryCounts
{
  std::vector<std::int64_t> PieceVertices, PieceFaces, FaceSize;
};

// Sizes every member that ConcatenateChunks fills.
void Resize(const ChunkOffsets& o, bool geom, bool emb, RestrictedVoronoiDiagram& out,
  GeometryCounts& counts)
{
  const std::size_t nchunk = o.Piece.size() - 1;
  const std::size_t np = o.Piece[nchunk], nvx = o.Vertex[nchunk], nf = o.Face[nchunk];
  const int K = out.SimplexDim;
  ResizeRecords(out, np, o.VoronoiVertex[nchunk], o.BoundaryDual[nchunk]);
  if (!geom)
    return;
  out.Points.resize(nvx * out.AmbientDim);
  if (emb)
    out.EmbeddedPoints.resize(nvx * out.Dim);
  out.VertexPlanes.resize(nvx * K);
  out.FaceVertices.resize(o.FaceVertex[nchunk]);
  out.FaceKind.resize(nf);
  out.FaceNeighbor.resize(nf);
  counts.PieceVertices.resize(np);
  counts.PieceFaces.resize(np);
  counts.FaceSize.resize(nf);
}

// Copies chunk c to its place in `out` (vertex ids shifted by the vertices before it).
void CopyChunk(const Chunk& ch, std::size_t c, const ChunkOffsets& o, bool geom, bool emb,
  RestrictedVoronoiDiagram& out, GeometryCounts& counts)
{
  const int K = out.SimplexDim, nv = K + 1;
  const int adim = out.AmbientDim, dim = out.Dim;
  std::copy(ch.PieceSite.begin(), ch.PieceSite.end(), out.PieceSite.begin() + o.Piece[c]);
  std::copy(ch.PieceElement.begin(), ch.PieceElement.end(), out.PieceElement.begin() + o.Piece[c]);
  std::copy(ch.PieceMeasure.begin(), ch.PieceMeasure.end(), out.PieceMeasure.begin() + o.Piece[c]);
  std::copy(ch.PieceEmbeddedMeasure.begin(), ch.PieceEmbeddedMeasure.end(),
    out.PieceEmbeddedMeasure.begin() + o.Piece[c]);
  if (!out.PieceSecurityRadius2.empty())
  {
    std::copy(ch.PieceRadius2.begin(), ch.PieceRadius2.end(), out.PieceSecurityRadius2.begin() + o.Piece[c]);
    std::copy(ch.PieceLastCut.begin(), ch.PieceLastCut.end(), out.PieceLastCutDistance.begin() + o.Piece[c]);
  }
  std::copy(ch.VoronoiVertexSites.begin(), ch.VoronoiVertexSites.end(),
    out.VoronoiVertexSites.begin() + o.VoronoiVertex[c] * nv);
  std::copy(ch.VoronoiVertexElement.begin(), ch.VoronoiVertexElement.end(),
    out.VoronoiVertexElement.begin() + o.VoronoiVertex[c]);
  std::copy(ch.BoundaryDualFaces.begin(), ch.BoundaryDualFaces.end(),
    out.BoundaryDualFaces.begin() + o.BoundaryDual[c]);
  if (!geom)
    return;
  std::copy(ch.Points.begin(), ch.Points.end(), out.Points.begin() + o.Vertex[c] * adim);
  if (emb)
    std::copy(ch.EmbeddedPoints.begin(), ch.EmbeddedPoints.end(),
      out.EmbeddedPoints.begin() + o.Vertex[c] * dim);
  std::copy(ch.VertexPlanes.begin(), ch.VertexPlanes.end(), out.VertexPlanes.begin() + o.Vertex[c] * K);
  for (std::size_t i = 0; i < ch.FaceVertices.size(); ++i)
    out.FaceVertices[o.FaceVertex[c] + i] = ch.FaceVertices[i] + static_cast<std::int32_t>(o.Vertex[c]);
  std::copy(ch.FaceKind.begin(), ch.FaceKind.end(), out.FaceKind.begin() + o.Face[c]);
  std::copy(ch.FaceNeighbor.begin(), ch.FaceNeighbor.end(), out.FaceNeighbor.begin() + o.Face[c]);
  std::copy(ch.PieceVertexCount.begin(), ch.PieceVertexCount.end(), counts.PieceVertices.begin() + o.Piece[c]);
  std::copy(ch.PieceFaceCount.begin(), ch.PieceFaceCount.end(), counts.PieceFaces.begin() + o.Piece[c]);
  std::copy(ch.FaceSize.begin(), ch.FaceSize.end(), counts.FaceSize.begin() + o.Face[c]);
}

// PieceVertexOffsets, PieceFaceOffsets and FaceOffsets from the counts.
void OffsetsFromCounts(const GeometryCounts& counts, RestrictedVoronoiDiagram& out)
{
  const std::size_t np = counts.PieceVertices.size(), nf = counts.FaceSize.size();
  out.PieceVertexOffsets.resize(np + 1, 0);
  out.PieceFaceOffsets.resize(np + 1, 0);
  out.FaceOffsets.resize(nf + 1, 0);
  for (std::size_t p = 0; p < np; ++p)
  {
    out.PieceVertexOffsets[p + 1] = out.PieceVertexOffsets[p] + counts.PieceVertices[p];
    out.PieceFaceOffsets[p + 1] = out.PieceFaceOffsets[p] + counts.PieceFaces[p];
  }
  for (std::size_t f = 0; f < nf; ++f)
    out.FaceOffsets[f + 1] = out.FaceOffsets[f] + counts.FaceSize[f];
}

// Appends piece p of `in` (its vertices, renumbered, and faces) to the geometry of `m`.
void AppendPieceGeometry(const RestrictedVoronoiDiagram& in, std::size_t p, bool emb,
  RestrictedVoronoiDiagram& m)
{
  const int K = in.SimplexDim, adim = in.AmbientDim, dim = in.Dim;
  const std::int64_t v0 = in.PieceVertexOffsets[p], v1 = in.PieceVertexOffsets[p + 1];
  const std::int64_t shift = static_cast<std::int64_t>(m.VertexPlanes.size() / K) - v0;
  m.Points.insert(m.Points.end(), in.Points.begin() + v0 * adim, in.Points.begin() + v1 * adim);
  if (emb)
    m.EmbeddedPoints.insert(m.EmbeddedPoints.end(), in.EmbeddedPoints.begin() + v0 * dim,
      in.EmbeddedPoints.begin() + v1 * dim);
  m.VertexPlanes.insert(m.VertexPlanes.end(), in.VertexPlanes.begin() + v0 * K,
    in.VertexPlanes.begin() + v1 * K);
  for (std::int64_t f = in.PieceFaceOffsets[p]; f < in.PieceFaceOffsets[p + 1]; ++f)
  {
    for (std::int64_t i = in.FaceOffsets[f]; i < in.FaceOffsets[f + 1]; ++i)
      m.FaceVertices.push_back(static_cast<std::int32_t>(in.FaceVertices[i] + shift));
    m.FaceOffsets.push_back(static_cast<std::int64_t>(m.FaceVertices.size()));
    m.FaceKind.push_back(in.FaceKind[f]);
    m.FaceNeighbor.push_back(in.FaceNeighbor[f]);
  }
  m.PieceVertexOffsets.push_back(static_cast<std::int64_t>(m.VertexPlanes.size() / K));
  m.PieceFaceOffsets.push_back(static_cast<std::int64_t>(m.FaceKind.size()));
}

} // namespace

RestrictedVoronoiDiagram NewDiagram(const SimplexMesh& mesh, const Embedding& embedding, std::size_t numSites)
{
  RestrictedVoronoiDiagram out;
  out.SimplexDim = mesh.SimplexDim;
  out.AmbientDim = mesh.AmbientDim;
  out.Dim = embedding.Dim;
  out.NumSites = numSites;
  return out;
}

void ResizeRecords(RestrictedVoronoiDiagram& out, std::size_t pieces, std::size_t voronoiVertices,
  std::size_t boundaryDualEntries)
{
  const int nv = out.SimplexDim + 1;
  out.PieceSite.resize(pieces);
  out.PieceElement.resize(pieces);
  out.PieceMeasure.resize(pieces);
  out.PieceEmbeddedMeasure.resize(pieces);
  out.VoronoiVertexSites.resize(voronoiVertices * nv);
  out.VoronoiVertexElement.resize(voronoiVertices);
  out.BoundaryDualFaces.resize(boundaryDualEntries);
}

void FillElementRecords(const std::vector<Chunk>& chunks, const std::vector<std::int32_t>& adj,
  std::size_t numElements, RestrictedVoronoiDiagram& out)
{
  const std::size_t nc = numElements;
  const int nv = out.SimplexDim + 1;
  out.ElementPieceOffsets.resize(nc + 1);
  out.ElementVoronoiVertexOffsets.resize(nc + 1);
  out.ElementBoundaryDualFaceOffsets.resize(nc + 1);
  out.ElementNearestSite.resize(nc);
  out.ElementEmptyVisit.resize(nc);
  out.ElementPieceOffsets[0] = out.ElementVoronoiVertexOffsets[0] =
    out.ElementBoundaryDualFaceOffsets[0] = 0;
  std::size_t e = 0;
  for (const Chunk& ch : chunks)
    for (std::size_t i = 0; i < ch.ElemNearest.size(); ++i, ++e)
    {
      out.ElementNearestSite[e] = ch.ElemNearest[i];
      out.ElementEmptyVisit[e] = ch.ElemEmptyVisit[i];
      out.ElementPieceOffsets[e + 1] = out.ElementPieceOffsets[e] + ch.ElemPieces[i];
      out.ElementVoronoiVertexOffsets[e + 1] = out.ElementVoronoiVertexOffsets[e] + ch.ElemVV[i];
      out.ElementBoundaryDualFaceOffsets[e + 1] =
        out.ElementBoundaryDualFaceOffsets[e] + ch.ElemBD[i];
    }
  const std::size_t np = static_cast<std::size_t>(out.ElementPieceOffsets[nc]);
  out.PieceSecurityRadius2.resize(np);
  out.PieceLastCutDistance.resize(np);
  out.ElementBoundaryFacets.assign(nc, 0);
  for (std::size_t c = 0; c < nc; ++c)
    for (int a = 0; a < nv; ++a)
      if (adj[c * nv + a] < 0)
        out.ElementBoundaryFacets[c] |= static_cast<std::uint8_t>(1u << a);
}

void ConcatenateChunks(std::vector<Chunk>& chunks, const RestrictedVoronoiOptions& options,
  RestrictedVoronoiDiagram& out)
{
  const ChunkOffsets o(chunks, out.SimplexDim);
  const bool geom = options.ComputeGeometry;
  const bool emb = geom && options.KeepEmbeddedPoints;
  GeometryCounts counts;
  Resize(o, geom, emb, out, counts);
  tbb::parallel_for(std::size_t(0), chunks.size(), [&](std::size_t c) {
    CopyChunk(chunks[c], c, o, geom, emb, out, counts);
    chunks[c] = Chunk(); // release memory early
  });
  if (o.Vertex.back() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    throw InputError("RestrictedVoronoi: output too large (more than 2^31 vertices)");
  if (geom)
    OffsetsFromCounts(counts, out);
}

void SumSiteMeasures(RestrictedVoronoiDiagram& out)
{
  const std::size_t np = out.NumPieces();
  out.SiteMeasure.assign(out.NumSites, 0.0);
  out.SiteEmbeddedMeasure.assign(out.NumSites, 0.0);
  for (std::size_t p = 0; p < np; ++p)
  {
    out.SiteMeasure[out.PieceSite[p]] += out.PieceMeasure[p];
    out.SiteEmbeddedMeasure[out.PieceSite[p]] += out.PieceEmbeddedMeasure[p];
  }
}

RestrictedVoronoiDiagram SortPiecesBySite(RestrictedVoronoiDiagram&& out, const RestrictedVoronoiOptions& options)
{
  const bool geom = options.ComputeGeometry;
  const bool emb = geom && options.KeepEmbeddedPoints;
  const std::size_t np = out.NumPieces();
  std::vector<std::size_t> perm(np);
  std::iota(perm.begin(), perm.end(), 0);
  std::stable_sort(perm.begin(), perm.end(),
    [&](std::size_t a, std::size_t b) { return out.PieceSite[a] < out.PieceSite[b]; });
  RestrictedVoronoiDiagram m;
  m.SimplexDim = out.SimplexDim;
  m.AmbientDim = out.AmbientDim;
  m.Dim = out.Dim;
  m.NumSites = out.NumSites;
  m.NumRecomputedElements = out.NumRecomputedElements;
  m.SiteMeasure = std::move(out.SiteMeasure);
  m.SiteEmbeddedMeasure = std::move(out.SiteEmbeddedMeasure);
  m.VoronoiVertexSites = std::move(out.VoronoiVertexSites);
  m.VoronoiVertexElement = std::move(out.VoronoiVertexElement);
  m.BoundaryDualFaces = std::move(out.BoundaryDualFaces);
  m.PieceVertexOffsets.push_back(0);
  m.PieceFaceOffsets.push_back(0);
  m.FaceOffsets.push_back(0);
  for (std::size_t q = 0; q < np; ++q)
  {
    const std::size_t p = perm[q];
    m.PieceSite.push_back(out.PieceSite[p]);
    m.PieceElement.push_back(out.PieceElement[p]);
    m.PieceMeasure.push_back(out.PieceMeasure[p]);
    m.PieceEmbeddedMeasure.push_back(out.PieceEmbeddedMeasure[p]);
    if (geom)
      AppendPieceGeometry(out, p, emb, m);
  }
  if (!geom)
  {
    m.PieceVertexOffsets.clear();
    m.PieceFaceOffsets.clear();
    m.FaceOffsets.clear();
  }
  return m;
}

} // namespace rvd
} // namespace av
