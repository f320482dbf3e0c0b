// SPDX-License-Identifier: BSD-3-Clause
// Internal to the Voronoi kernel: PieceEmitter, which appends a clipped piece to the output of
// its block (measures, dual records, vertices in input space / R^Dim, faces with their kinds).
#ifndef av_RestrictedVoronoiEmitter_h
#define av_RestrictedVoronoiEmitter_h

#include "RestrictedVoronoi.h"
#include "RestrictedVoronoiChunk.h"
#include "RestrictedVoronoiContext.h"
#include "RestrictedVoronoiElementFrame.h"
#include "RestrictedVoronoiPrimitives.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{
namespace rvd
{

template <int K, int DIM>
class PieceEmitter
{
public:
  static constexpr int NV = K + 1;

  PieceEmitter(const ElementFrame<K, DIM>& frame, const std::vector<std::int32_t>& adjacency,
    const RestrictedVoronoiOptions& options)
    : F(frame)
    , Adj(adjacency)
    , Opt(options)
  {
  }

  /// Appends the current piece (C's polytope) of `site` to the chunk.
  void Emit(Context<K>& C, Chunk& out, std::int32_t site) const
  {
    const double rel = std::max(0.0, RelativeMeasure(C));
    out.PieceSite.push_back(site);
    out.PieceElement.push_back(F.Elem);
    out.PieceMeasure.push_back(rel * F.ElemMeasure);
    out.PieceEmbeddedMeasure.push_back(rel * F.ElemEmbMeasure);
    out.PieceRadius2.push_back(RoundUp(C.PieceR2));
    out.PieceLastCut.push_back(RoundUp(C.PieceLastCut));

    // Collect the vertices referenced by the faces (local numbering, first use order).
    C.Remap.assign(C.V.size(), -1);
    std::vector<std::int32_t>& order = C.NLoops; // scratch
    order.clear();
    for (std::int32_t id : C.Loops)
      if (C.Remap[id] < 0)
      {
        C.Remap[id] = static_cast<std::int32_t>(order.size());
        order.push_back(id);
      }
    for (std::int32_t id : order)
      RecordDualVertex(C.V[id], site, out);
    if (!Opt.ComputeGeometry)
      return;
    const std::int32_t base = static_cast<std::int32_t>(out.Points.size() / F.Mesh.AmbientDim);
    EmitVertices(C, out, order);
    out.PieceVertexCount.push_back(static_cast<std::int64_t>(order.size()));
    out.PieceFaceCount.push_back(EmitFaces(C, out, base));
  }

private:
  const ElementFrame<K, DIM>& F;
  const std::vector<std::int32_t>& Adj;
  const RestrictedVoronoiOptions& Opt;

  // Measure of the piece in barycentric coordinates (fraction of the element).
  double RelativeMeasure(const Context<K>& C) const
  {
    double rel = 0.0;
    if constexpr (K == 2)
    {
      const int n = static_cast<int>(C.Loops.size());
      for (int t = 0; t < n; ++t)
      {
        const auto& a = C.V[C.Loops[t]].Lam;
        const auto& b = C.V[C.Loops[(t + 1) % n]].Lam;
        rel += a[1] * b[2] - a[2] * b[1];
      }
    }
    else
    {
      const auto& o = C.V[C.Loops[C.FaceStart[0]]].Lam;
      for (std::size_t f = 0; f < C.FacePlane.size(); ++f)
      {
        const int st = C.FaceStart[f], n = C.FaceCount[f];
        const auto& a = C.V[C.Loops[st]].Lam;
        for (int t = 1; t + 1 < n; ++t)
        {
          const auto& b = C.V[C.Loops[st + t]].Lam;
          const auto& c = C.V[C.Loops[st + t + 1]].Lam;
          const double ax = a[1] - o[1], ay = a[2] - o[2], az = a[3] - o[3];
          const double bx = b[1] - o[1], by = b[2] - o[2], bz = b[3] - o[3];
          const double cx = c[1] - o[1], cy = c[2] - o[2], cz = c[3] - o[3];
          rel += ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx);
        }
      }
    }
    return rel;
  }

  // Dual records of vertex v of piece `site` (symbolic): a Voronoi vertex (all labels
  // bisectors) or a boundary dual face (one label a facet on the domain boundary).
  void RecordDualVertex(const Vert<K>& v, std::int32_t site, Chunk& out) const
  {
    int nfac = 0, fac = -1;
    std::array<std::int32_t, K + 1> s;
    int ns = 0;
    s[ns++] = site;
    for (int a = 0; a < K; ++a)
    {
      if (IsFacet(v.Pl[a]))
      {
        ++nfac;
        fac = FacetOf(v.Pl[a]);
      }
      else
        s[ns++] = v.Pl[a];
    }
    if (nfac > 1 || (nfac == 1 && Adj[std::size_t(F.Elem) * NV + fac] >= 0))
      return; // neither a Voronoi vertex nor on the domain boundary: nothing to record
    SortSmall(s.begin(), s.begin() + ns);
    if (nfac == 0)
    {
      out.VoronoiVertexSites.insert(out.VoronoiVertexSites.end(), s.begin(), s.begin() + ns);
      out.VoronoiVertexElement.push_back(F.Elem);
    }
    else if (nfac == 1 && Adj[std::size_t(F.Elem) * NV + fac] < 0)
      out.BoundaryDualFaces.insert(out.BoundaryDualFaces.end(), s.begin(), s.begin() + ns);
  }

  // What the plane of a face / edge is, and its neighbor (site, element or -1).
  void PlaneKind(std::int32_t pl, RVDFaceKind& kind, std::int32_t& nbr) const
  {
    if (!IsFacet(pl))
    {
      kind = RVDFaceKind::Bisector;
      nbr = pl;
    }
    else
    {
      nbr = Adj[std::size_t(F.Elem) * NV + FacetOf(pl)];
      kind = nbr < 0 ? RVDFaceKind::DomainBoundary : RVDFaceKind::ElementFace;
    }
  }

  // Input-space (and embedded) coordinates and plane labels of the vertices in `order`.
  void EmitVertices(const Context<K>& C, Chunk& out, const std::vector<std::int32_t>& order) const
  {
    const int adim = F.Mesh.AmbientDim;
    for (std::int32_t id : order)
    {
      const auto& v = C.V[id];
      for (int d = 0; d < adim; ++d)
      {
        double x = 0.0;
        for (int a = 0; a < NV; ++a)
          x += v.Lam[a] * F.XV[a][d];
        out.Points.push_back(x);
      }
      if (Opt.KeepEmbeddedPoints)
        for (int d = 0; d < F.Dim; ++d)
        {
          double x = 0.0;
          for (int a = 0; a < NV; ++a)
            x += v.Lam[a] * F.EV[a][d];
          out.EmbeddedPoints.push_back(x);
        }
      for (int a = 0; a < K; ++a)
        out.VertexPlanes.push_back(v.Pl[a]);
    }
  }

  // Edges (K = 2) or faces (K = 3) of the piece, vertex ids from `base` in the chunk; element
  // faces are dropped with MergeBySite. Returns how many were appended.
  std::int64_t EmitFaces(const Context<K>& C, Chunk& out, std::int32_t base) const
  {
    std::int64_t nfaces = 0;
    if constexpr (K == 2)
    {
      const int n = static_cast<int>(C.Loops.size());
      for (int t = 0; t < n; ++t)
      {
        RVDFaceKind kind;
        std::int32_t nbr;
        PlaneKind(C.EdgePlane[t], kind, nbr);
        if (Opt.MergeBySite && kind == RVDFaceKind::ElementFace)
          continue;
        out.FaceVertices.push_back(base + C.Remap[C.Loops[t]]);
        out.FaceVertices.push_back(base + C.Remap[C.Loops[(t + 1) % n]]);
        out.FaceSize.push_back(2);
        out.FaceKind.push_back(kind);
        out.FaceNeighbor.push_back(nbr);
        ++nfaces;
      }
    }
    else
    {
      for (std::size_t f = 0; f < C.FacePlane.size(); ++f)
      {
        RVDFaceKind kind;
        std::int32_t nbr;
        PlaneKind(C.FacePlane[f], kind, nbr);
        if (Opt.MergeBySite && kind == RVDFaceKind::ElementFace)
          continue;
        const int st = C.FaceStart[f], n = C.FaceCount[f];
        for (int t = 0; t < n; ++t)
          out.FaceVertices.push_back(base + C.Remap[C.Loops[st + t]]);
        out.FaceSize.push_back(n);
        out.FaceKind.push_back(kind);
        out.FaceNeighbor.push_back(nbr);
        ++nfaces;
      }
    }
    return nfaces;
  }
};

} // namespace rvd
} // namespace av

#endif
