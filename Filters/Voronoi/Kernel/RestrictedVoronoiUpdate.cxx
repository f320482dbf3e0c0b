// SPDX-License-Identifier: BSD-3-Clause
// UpdateRestrictedVoronoi: the diagram after sites were appended or moved, by clipping again only
// the elements whose pieces can change and splicing them into a copy of the previous diagram.
#include "RestrictedVoronoi.h"

#include "RestrictedVoronoiAssembly.h"
#include "RestrictedVoronoiBlocks.h"
#include "RestrictedVoronoiChunk.h"
#include "RestrictedVoronoiPrimitives.h"
#include "RestrictedVoronoiSiteTree.h"
#include "RestrictedVoronoiValidation.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace av
{
namespace
{

using rvd::Dist2;

// Whether `P` carries the per-element members of a whole-mesh, measures-only run on this mesh
// (what the splice needs), for options that the splice can reproduce.
bool CanSplice(const SimplexMesh& mesh, const Embedding& embedding,
  const RestrictedVoronoiOptions& options, const RestrictedVoronoiDiagram& P)
{
  const int K = mesh.SimplexDim, nv = K + 1, dim = embedding.Dim;
  const std::size_t nc = mesh.NumCells();
  return !options.ComputeGeometry && !options.MergeBySite && options.ElementBegin == 0 &&
    options.ElementEnd < 0 && P.SimplexDim == K && P.Dim == dim &&
    P.AmbientDim == mesh.AmbientDim && P.ElementPieceOffsets.size() == nc + 1 &&
    P.ElementVoronoiVertexOffsets.size() == nc + 1 &&
    P.ElementBoundaryDualFaceOffsets.size() == nc + 1 && P.ElementNearestSite.size() == nc &&
    P.ElementBoundaryFacets.size() == nc && P.ElementEmptyVisit.size() == nc &&
    P.PieceSecurityRadius2.size() == P.NumPieces() && P.PieceLastCutDistance.size() == P.NumPieces() &&
    P.ElementPieceOffsets[nc] == static_cast<std::int64_t>(P.NumPieces()) &&
    P.PieceElement.size() == P.NumPieces() && P.PieceMeasure.size() == P.NumPieces() &&
    P.PieceEmbeddedMeasure.size() == P.NumPieces() &&
    P.ElementVoronoiVertexOffsets[nc] == static_cast<std::int64_t>(P.VoronoiVertexElement.size()) &&
    P.VoronoiVertexSites.size() == P.VoronoiVertexElement.size() * nv &&
    P.ElementBoundaryDualFaceOffsets[nc] * K == static_cast<std::int64_t>(P.BoundaryDualFaces.size());
}

// Changed sites: moved ones (old and new positions both matter) and appended ones.
struct ChangedSites
{
  std::vector<char> Moved;    ///< per previous site
  std::vector<double> Points; ///< changed positions, NumPoints x Dim
  std::size_t NumPoints = 0;
};

ChangedSites FindChangedSites(const SiteSet& sites, const SiteSet& previousSites)
{
  const int dim = sites.Dim;
  const std::size_t ns = sites.NumSites(), ns0 = previousSites.NumSites();
  ChangedSites out;
  out.Moved.assign(ns0, 0);
  std::vector<double>& pts = out.Points;
  for (std::size_t s = 0; s < ns; ++s)
  {
    const double* q = sites.At(s);
    if (s < ns0)
    {
      const double* o = previousSites.At(s);
      if (std::equal(q, q + dim, o))
        continue;
      out.Moved[s] = 1;
      pts.insert(pts.end(), o, o + dim);
    }
    pts.insert(pts.end(), q, q + dim);
  }
  out.NumPoints = pts.size() / dim;
  return out;
}

/**
 * Affected elements. A site j is a candidate of element e (CandidateFinder) unless it is
 * farther than e's nearest site n from every vertex of e, with a relative margin of 1e-9 (of
 * the squared distances). An element whose candidates and nearest site are unchanged is
 * processed by exactly the same operations, hence copied. Here a changed position counts as
 * harmless only with a 100x larger margin, so that round-off cannot decide differently.
 */
class AffectedElementTest
{
public:
  AffectedElementTest(const SimplexMesh& mesh, const Embedding& embedding, const SiteSet& sites,
    const RestrictedVoronoiDiagram& previous, std::size_t numPreviousSites,
    const ChangedSites& changed, const rvd::SiteTree<-1>& tree)
    : Mesh(mesh)
    , Emb(embedding)
    , Sites(sites)
    , P(previous)
    , NumPreviousSites(numPreviousSites)
    , Changed(changed)
    , Tree(tree)
    , Dim(embedding.Dim)
    , NV(mesh.SimplexDim + 1)
  {
  }

  /// Scratch of one thread.
  struct Scratch
  {
    std::vector<std::pair<std::uint32_t, double>> Hits;
    std::vector<double> Centroid;
  };

  bool Affected(std::size_t e, Scratch& s) const
  {
    const int dim = Dim, nv = NV;
    const std::int32_t n = P.ElementNearestSite[e];
    if (n < 0 || static_cast<std::size_t>(n) >= NumPreviousSites || Changed.Moved[n])
      return true;
    const std::int32_t* cell = Mesh.Cell(e);
    const double* v[4];
    for (int a = 0; a < nv; ++a)
      v[a] = Emb.At(cell[a]);
    std::vector<double>& c = s.Centroid;
    std::fill(c.begin(), c.end(), 0.0);
    for (int a = 0; a < nv; ++a)
      for (int d = 0; d < dim; ++d)
        c[d] += v[a][d] / nv;
    double rho = 0.0;
    for (int a = 0; a < nv; ++a)
      rho = std::max(rho, Dist2<-1>(v[a], c.data(), dim));
    rho = std::sqrt(rho) * (1.0 + 1e-12);
    const double* pn = Sites.At(n);
    // A position farther than R from c is farther than n from every vertex, by far more
    // than the margin (R(1 + 1e-6) against the 1e-9 of the test).
    const double R = (std::sqrt(Dist2<-1>(c.data(), pn, dim)) + 2.0 * rho) * (1.0 + 1e-6);
    s.Hits.clear();
    Tree.radiusSearch(c.data(), R * R, s.Hits, nanoflann::SearchParams(32, 0.0, false));
    if (s.Hits.empty())
      return false;
    double dn[4];
    for (int a = 0; a < nv; ++a)
      dn[a] = Dist2<-1>(v[a], pn, dim);
    for (const auto& h : s.Hits)
    {
      const double* q = Changed.Points.data() + std::size_t(h.first) * dim;
      double scale = 0.0, gmin = std::numeric_limits<double>::infinity();
      for (int a = 0; a < nv; ++a)
      {
        const double dq = Dist2<-1>(v[a], q, dim);
        scale = std::max(scale, std::max(dq, dn[a]));
        gmin = std::min(gmin, dq - dn[a]);
      }
      if (gmin > 1e-7 * scale)
        continue; // not a candidate
      if (!Harmless(e, q, v, c.data()))
        return true;
    }
    return false;
  }

private:
  const SimplexMesh& Mesh;
  const Embedding& Emb;
  const SiteSet& Sites;
  const RestrictedVoronoiDiagram& P;
  std::size_t NumPreviousSites;
  const ChangedSites& Changed;
  const rvd::SiteTree<-1>& Tree;
  int Dim, NV;

  // A candidate q of element e (vertices v, centroid c) is harmless if every piece (all
  // visited sites have one) was final when q came (q farther from the centroid than the
  // piece's last cut) and the final piece lies, with margin, on its site's side of the
  // bisector: with D = |q - p_i| and R the piece's security radius,
  // |x - q|^2 - |x - p_i|^2 >= D (D - 2R) on the piece, against Clip's fast-path margin
  // 1e-9 (max_a |v_a - p_i| + D)^2.
  bool Harmless(std::size_t e, const double* q, const double* const* v, const double* c) const
  {
    const int dim = Dim, nv = NV;
    const std::int64_t p0 = P.ElementPieceOffsets[e], p1 = P.ElementPieceOffsets[e + 1];
    bool harmless = !P.ElementEmptyVisit[e] && p1 > p0;
    const double dqc = std::sqrt(Dist2<-1>(c, q, dim));
    for (std::int64_t p = p0; p < p1 && harmless; ++p)
    {
      const std::int32_t i = P.PieceSite[p];
      if (static_cast<std::size_t>(i) >= NumPreviousSites || Changed.Moved[i])
        return false;
      const double last = P.PieceLastCutDistance[p];
      if (!(dqc > last * (1.0 + 1e-9) + 1e-300))
        return false;
      const double* pi = Sites.At(i);
      double rho2 = 0.0;
      for (int a = 0; a < nv; ++a)
        rho2 = std::max(rho2, Dist2<-1>(v[a], pi, dim));
      const double D = std::sqrt(Dist2<-1>(q, pi, dim));
      const double R = std::sqrt(static_cast<double>(P.PieceSecurityRadius2[p])) * (1.0 + 1e-9);
      const double bound = std::sqrt(rho2) + D;
      harmless = D > 2.0 * R && D * (D - 2.0 * R) > 1e-7 * bound * bound;
    }
    return harmless;
  }
};

// The ids of the elements that a changed site can affect, in order.
std::vector<std::int32_t> AffectedElements(const SimplexMesh& mesh, const Embedding& embedding,
  const SiteSet& sites, const RestrictedVoronoiDiagram& P, std::size_t numPreviousSites,
  const ChangedSites& changed)
{
  const std::size_t nc = mesh.NumCells();
  const int dim = embedding.Dim;
  std::vector<char> affected(nc, 0);
  if (changed.NumPoints > 0)
  {
    rvd::SiteCloud<-1> cloud{ changed.Points.data(), changed.NumPoints, dim };
    rvd::SiteTree<-1> tree(dim, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
    const AffectedElementTest test(mesh, embedding, sites, P, numPreviousSites, changed, tree);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nc), [&](const tbb::blocked_range<std::size_t>& r) {
      AffectedElementTest::Scratch scratch;
      scratch.Centroid.resize(dim);
      for (std::size_t e = r.begin(); e != r.end(); ++e)
        affected[e] = test.Affected(e, scratch) ? 1 : 0;
    });
  }
  std::vector<std::int32_t> list;
  for (std::size_t e = 0; e < nc; ++e)
    if (affected[e])
      list.push_back(static_cast<std::int32_t>(e));
  return list;
}

// Clips the listed elements. Without geometry the kernel only asks whether a facet is on the
// domain boundary: the previous diagram's boundary bits stand in for the adjacency.
std::vector<rvd::Chunk> ClipElements(const SimplexMesh& mesh, const Embedding& embedding,
  const SiteSet& sites, const RestrictedVoronoiOptions& options, const RestrictedVoronoiDiagram& P,
  const std::vector<std::int32_t>& list, std::size_t blockSize)
{
  const std::size_t nc = mesh.NumCells();
  const int nv = mesh.SimplexDim + 1;
  std::vector<rvd::Chunk> chunks((list.size() + blockSize - 1) / blockSize);
  if (list.empty())
    return chunks;
  std::vector<std::int32_t> adj(nc * nv, 0);
  for (const std::int32_t e : list)
    for (int a = 0; a < nv; ++a)
      if (P.ElementBoundaryFacets[e] & (1u << a))
        adj[std::size_t(e) * nv + a] = -1;
  rvd::ClipElementBlocks(mesh, embedding, sites, options, adj, chunks, blockSize, 0, list.size(), list.data());
  return chunks;
}

// Where each element's new output comes from: Slot[e] = its index in the list of clipped
// elements (-1: copied from the previous diagram), Start[k] where element k's output starts
// in its chunk.
struct SpliceSources
{
  struct Start
  {
    std::int64_t P, V, B;
  };
  std::vector<Start> Starts;
  std::vector<std::int32_t> Slot;
  std::size_t BlockSize;

  SpliceSources(const std::vector<rvd::Chunk>& chunks, const std::vector<std::int32_t>& list,
    std::size_t numElements, std::size_t blockSize)
    : Starts(list.size())
    , Slot(numElements, -1)
    , BlockSize(blockSize)
  {
    for (std::size_t b = 0; b < chunks.size(); ++b)
    {
      Start o{ 0, 0, 0 };
      const rvd::Chunk& ch = chunks[b];
      for (std::size_t i = 0; i < ch.ElemNearest.size(); ++i)
      {
        const std::size_t k = b * blockSize + i;
        Starts[k] = o;
        Slot[list[k]] = static_cast<std::int32_t>(k);
        o.P += ch.ElemPieces[i];
        o.V += ch.ElemVV[i];
        o.B += ch.ElemBD[i];
      }
    }
  }
};

// The per-element members of the spliced diagram.
void SpliceElementRecords(const RestrictedVoronoiDiagram& P, const std::vector<rvd::Chunk>& chunks,
  const SpliceSources& src, std::size_t nc, RestrictedVoronoiDiagram& out)
{
  out.ElementPieceOffsets.resize(nc + 1);
  out.ElementVoronoiVertexOffsets.resize(nc + 1);
  out.ElementBoundaryDualFaceOffsets.resize(nc + 1);
  out.ElementNearestSite.resize(nc);
  out.ElementEmptyVisit.resize(nc);
  out.ElementBoundaryFacets = P.ElementBoundaryFacets;
  out.ElementPieceOffsets[0] = out.ElementVoronoiVertexOffsets[0] =
    out.ElementBoundaryDualFaceOffsets[0] = 0;
  for (std::size_t e = 0; e < nc; ++e)
  {
    std::int64_t np, nvv, nbd;
    const std::int32_t k = src.Slot[e];
    if (k < 0)
    {
      np = P.ElementPieceOffsets[e + 1] - P.ElementPieceOffsets[e];
      nvv = P.ElementVoronoiVertexOffsets[e + 1] - P.ElementVoronoiVertexOffsets[e];
      nbd = P.ElementBoundaryDualFaceOffsets[e + 1] - P.ElementBoundaryDualFaceOffsets[e];
      out.ElementNearestSite[e] = P.ElementNearestSite[e];
      out.ElementEmptyVisit[e] = P.ElementEmptyVisit[e];
    }
    else
    {
      const rvd::Chunk& ch = chunks[k / src.BlockSize];
      const std::size_t i = k % src.BlockSize;
      np = ch.ElemPieces[i];
      nvv = ch.ElemVV[i];
      nbd = ch.ElemBD[i];
      out.ElementNearestSite[e] = ch.ElemNearest[i];
      out.ElementEmptyVisit[e] = ch.ElemEmptyVisit[i];
    }
    out.ElementPieceOffsets[e + 1] = out.ElementPieceOffsets[e] + np;
    out.ElementVoronoiVertexOffsets[e + 1] = out.ElementVoronoiVertexOffsets[e] + nvv;
    out.ElementBoundaryDualFaceOffsets[e + 1] = out.ElementBoundaryDualFaceOffsets[e] + nbd;
  }
}

// The rows of one element's output in the previous diagram or in a chunk.
struct ElementRows
{
  const std::int32_t *PieceSite, *PieceElement, *VoronoiVertexSites, *VoronoiVertexElement,
    *BoundaryDualFaces;
  const double *PieceMeasure, *PieceEmbeddedMeasure;
  const float *PieceRadius2, *PieceLastCut;
};

ElementRows PreviousRows(const RestrictedVoronoiDiagram& P, std::size_t e, int nv, int K)
{
  const std::int64_t p0 = P.ElementPieceOffsets[e], v0 = P.ElementVoronoiVertexOffsets[e],
                     b0 = P.ElementBoundaryDualFaceOffsets[e];
  return { P.PieceSite.data() + p0, P.PieceElement.data() + p0,
    P.VoronoiVertexSites.data() + v0 * nv, P.VoronoiVertexElement.data() + v0,
    P.BoundaryDualFaces.data() + b0 * K, P.PieceMeasure.data() + p0,
    P.PieceEmbeddedMeasure.data() + p0, P.PieceSecurityRadius2.data() + p0,
    P.PieceLastCutDistance.data() + p0 };
}

ElementRows ChunkRows(const rvd::Chunk& ch, const SpliceSources::Start& o, int nv, int K)
{
  return { ch.PieceSite.data() + o.P, ch.PieceElement.data() + o.P,
    ch.VoronoiVertexSites.data() + o.V * nv, ch.VoronoiVertexElement.data() + o.V,
    ch.BoundaryDualFaces.data() + o.B * K, ch.PieceMeasure.data() + o.P,
    ch.PieceEmbeddedMeasure.data() + o.P, ch.PieceRadius2.data() + o.P,
    ch.PieceLastCut.data() + o.P };
}

// The per-piece and dual members of the spliced diagram, element by element (TBB).
void SplicePieces(const RestrictedVoronoiDiagram& P, const std::vector<rvd::Chunk>& chunks,
  const SpliceSources& src, std::size_t nc, RestrictedVoronoiDiagram& out)
{
  const int K = out.SimplexDim, nv = K + 1;
  const std::size_t np = out.ElementPieceOffsets[nc];
  rvd::ResizeRecords(out, np, out.ElementVoronoiVertexOffsets[nc],
    out.ElementBoundaryDualFaceOffsets[nc] * K);
  out.PieceSecurityRadius2.resize(np);
  out.PieceLastCutDistance.resize(np);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nc, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t e = r.begin(); e != r.end(); ++e)
    {
      const std::int64_t p1 = out.ElementPieceOffsets[e], v1 = out.ElementVoronoiVertexOffsets[e],
                         b1 = out.ElementBoundaryDualFaceOffsets[e];
      const std::int64_t pn = out.ElementPieceOffsets[e + 1] - p1,
                         vn = out.ElementVoronoiVertexOffsets[e + 1] - v1,
                         bn = out.ElementBoundaryDualFaceOffsets[e + 1] - b1;
      const std::int32_t k = src.Slot[e];
      const ElementRows in = k < 0 ? PreviousRows(P, e, nv, K)
                                   : ChunkRows(chunks[k / src.BlockSize], src.Starts[k], nv, K);
      std::copy_n(in.PieceSite, pn, out.PieceSite.begin() + p1);
      std::copy_n(in.PieceElement, pn, out.PieceElement.begin() + p1);
      std::copy_n(in.PieceMeasure, pn, out.PieceMeasure.begin() + p1);
      std::copy_n(in.PieceEmbeddedMeasure, pn, out.PieceEmbeddedMeasure.begin() + p1);
      std::copy_n(in.PieceRadius2, pn, out.PieceSecurityRadius2.begin() + p1);
      std::copy_n(in.PieceLastCut, pn, out.PieceLastCutDistance.begin() + p1);
      std::copy_n(in.VoronoiVertexSites, vn * nv, out.VoronoiVertexSites.begin() + v1 * nv);
      std::copy_n(in.VoronoiVertexElement, vn, out.VoronoiVertexElement.begin() + v1);
      std::copy_n(in.BoundaryDualFaces, bn * K, out.BoundaryDualFaces.begin() + b1 * K);
    }
  });
}

} // namespace

RestrictedVoronoiDiagram UpdateRestrictedVoronoi(const SimplexMesh& mesh,
  const Embedding& embedding, const SiteSet& sites, const RestrictedVoronoiDiagram& previous,
  const SiteSet& previousSites, const RestrictedVoronoiOptions& options)
{
  ValidateRestrictedVoronoiInput(mesh, embedding, sites);
  const int dim = embedding.Dim;
  const std::size_t ns = sites.NumSites(), ns0 = previousSites.NumSites(), nc = mesh.NumCells();
  if (previous.NumSites != ns0 || previousSites.Dim != sites.Dim || ns0 > ns ||
    previousSites.Coords.size() != ns0 * static_cast<std::size_t>(dim))
    throw InputError("RestrictedVoronoi update: the previous diagram does not belong to the "
                     "previous sites, or the sites are not the previous ones followed by new ones");
  if (!CanSplice(mesh, embedding, options, previous))
    return ComputeRestrictedVoronoi(mesh, embedding, sites, options);
  const ChangedSites changed = FindChangedSites(sites, previousSites);
  if (2 * changed.NumPoints > ns + ns0)
    return ComputeRestrictedVoronoi(mesh, embedding, sites, options);
  const std::vector<std::int32_t> list =
    AffectedElements(mesh, embedding, sites, previous, ns0, changed);
  if (10 * list.size() > 7 * nc)
    return ComputeRestrictedVoronoi(mesh, embedding, sites, options);
  rvd::CheckDegenerateElements(mesh, embedding, list.data(), list.size());

  const std::size_t blockSize = 64;
  const std::vector<rvd::Chunk> chunks =
    ClipElements(mesh, embedding, sites, options, previous, list, blockSize);
  const SpliceSources src(chunks, list, nc, blockSize);
  RestrictedVoronoiDiagram out = rvd::NewDiagram(mesh, embedding, ns);
  out.NumRecomputedElements = list.size();
  for (const rvd::Chunk& ch : chunks)
    out.NumWholeElements += ch.NumWholeElements;
  SpliceElementRecords(previous, chunks, src, nc, out);
  SplicePieces(previous, chunks, src, nc, out);
  rvd::SumSiteMeasures(out); // same summation order as ComputeRestrictedVoronoi
  return out;
}

} // namespace av
