// SPDX-License-Identifier: BSD-3-Clause
// Internal to the Voronoi kernel: ElementWorker, all pieces of one element by a flood fill over
// the sites (candidates, clipping, emission), for one thread's range of elements.
#ifndef av_RestrictedVoronoiWorker_h
#define av_RestrictedVoronoiWorker_h

#include "RestrictedVoronoi.h"
#include "RestrictedVoronoiCandidates.h"
#include "RestrictedVoronoiChunk.h"
#include "RestrictedVoronoiClipper.h"
#include "RestrictedVoronoiContext.h"
#include "RestrictedVoronoiElementFrame.h"
#include "RestrictedVoronoiEmitter.h"
#include "RestrictedVoronoiPrimitives.h"
#include "RestrictedVoronoiSiteTree.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{
namespace rvd
{

/**
 * Per element, pieces are found by a flood fill over sites: start with the site nearest to the
 * element centroid (its piece is not empty), clip the element by the bisectors of the
 * element's candidates in distance order until the security radius test passes, then visit
 * the sites across the bisector faces of the piece. Pieces of one convex element are
 * face-connected, so this finds them all.
 */
template <int K, int DIM>
class ElementWorker
{
public:
  ElementWorker(const SimplexMesh& m, const Embedding& e, const SiteSet& s,
    const RestrictedVoronoiOptions& o, const SiteTree<DIM>& t,
    const std::vector<std::int32_t>& adj, const SiteNeighbors& nbr,
    const std::int32_t* vertexSites)
    : Frame(m, e, s)
    , Finder(Frame, t, nbr, s.NumSites())
    , Clipper(Frame)
    , Emitter(Frame, adj, o)
    , VertexSites(vertexSites)
  {
  }
  ElementWorker(const ElementWorker&) = delete; // the parts refer to Frame
  ElementWorker& operator=(const ElementWorker&) = delete;

  /// Appends the pieces of element e, and its per-element record, to `out`.
  void ProcessElement(Context<K>& C, std::int32_t e, Chunk& out)
  {
    Frame.LoadVertices(e);
    const std::int32_t whole = WholeElementSite(e);
    if (whole >= 0)
    {
      EmitWholeElement(C, whole, out);
      return;
    }
    Frame.LoadClipping();
    Finder.GatherCandidates(C);
    const std::size_t p0 = out.PieceSite.size(), v0 = out.VoronoiVertexElement.size(),
                      b0 = out.BoundaryDualFaces.size();
    C.Queue.clear();
    Enqueue(C, C.Cand[0]);
    std::size_t nextStart = 1;
    bool any = false, emptyVisit = false;
    for (std::size_t q = 0; q < C.Queue.size(); ++q)
    {
      const std::int32_t site = C.Queue[q];
      if (!Clipper.ComputePiece(C, site))
      {
        emptyVisit = true;
        // Tie at the centroid: try the next nearest candidates until one has a piece.
        while (!any && q + 1 == C.Queue.size() && nextStart < C.Cand.size())
          Enqueue(C, C.Cand[nextStart++]);
        continue;
      }
      any = true;
      // Neighbors across bisector faces / edges also have pieces here.
      const std::vector<std::int32_t>& planes = (K == 2) ? C.EdgePlane : C.FacePlane;
      for (std::int32_t pl : planes)
        if (!IsFacet(pl))
          Enqueue(C, pl);
      Emitter.Emit(C, out, site);
    }
    EndElement(C, out, Finder.LastNearest, emptyVisit, p0, v0, b0);
  }

private:
  ElementFrame<K, DIM> Frame;
  CandidateFinder<K, DIM> Finder;
  PolytopeClipper<K, DIM> Clipper;
  PieceEmitter<K, DIM> Emitter;
  const std::int32_t* VertexSites; // ClearNearestSites per mesh vertex; nullptr: no fast path

  // The site whose cell holds all of element e when its vertices have the same clear nearest
  // site (ClearNearestSites), else -1.
  std::int32_t WholeElementSite(std::int32_t e) const
  {
    if (!VertexSites)
      return -1;
    const std::int32_t* cell = Frame.Mesh.Cell(e);
    const std::int32_t n = VertexSites[cell[0]];
    for (int a = 1; a <= K; ++a)
      if (VertexSites[cell[a]] != n)
        return -1;
    return n;
  }

  // Fast path: what the flood fill gives for an element inside one cell (candidates {n} up to
  // sites that cannot cut, one uncut piece, no bisector face so no other site visited), with
  // the same emitter, so measures, records and geometry have the same bits.
  void EmitWholeElement(Context<K>& C, std::int32_t site, Chunk& out)
  {
    const std::size_t p0 = out.PieceSite.size(), v0 = out.VoronoiVertexElement.size(),
                      b0 = out.BoundaryDualFaces.size();
    Clipper.WholeElement(C, site);
    Emitter.Emit(C, out, site);
    Finder.LastNearest = site; // the walk's start for the next element
    ++out.NumWholeElements;
    EndElement(C, out, site, false, p0, v0, b0);
  }

  // The per-element record of the element just processed; resets the per-site cache.
  static void EndElement(Context<K>& C, Chunk& out, std::int32_t nearest, bool emptyVisit,
    std::size_t p0, std::size_t v0, std::size_t b0)
  {
    out.ElemNearest.push_back(nearest);
    out.ElemEmptyVisit.push_back(emptyVisit);
    out.ElemPieces.push_back(static_cast<std::int32_t>(out.PieceSite.size() - p0));
    out.ElemVV.push_back(static_cast<std::int32_t>(out.VoronoiVertexElement.size() - v0));
    out.ElemBD.push_back(static_cast<std::int32_t>((out.BoundaryDualFaces.size() - b0) / K));
    C.ResetSites();
  }

  // Queues site s for the flood fill unless it was visited.
  static void Enqueue(Context<K>& C, std::int32_t s)
  {
    const int sl = C.SlotOf(s);
    if (!C.Slots[sl].Visited)
    {
      C.Slots[sl].Visited = true;
      C.Queue.push_back(s);
    }
  }
};

} // namespace rvd
} // namespace av

#endif
