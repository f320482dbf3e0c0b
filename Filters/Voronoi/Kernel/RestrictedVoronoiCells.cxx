// SPDX-License-Identifier: BSD-3-Clause
// The RVD as cells in input space: pieces glued into one cell per site by the symbolic identity
// of their vertices, 2D edges chained into loops, orientation, shrink about the centroid.
#include "RestrictedVoronoiCells.h"

#include "MeshTopology.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace av
{
namespace
{

using VertexKey = std::array<std::int32_t, 8>;

/// Symbolic identity of an RVD vertex across the elements of one site's cell: the bisector
/// sites and the global mesh vertices of the sub-simplex (intersection of its facet planes).
VertexKey MakeKey(const std::int32_t* planes, int k, const std::int32_t* cell)
{
  VertexKey key;
  key.fill(-1);
  std::array<std::int32_t, 4> bis{};
  int nb = 0;
  bool onFacet[4] = { false, false, false, false };
  for (int a = 0; a < k; ++a)
  {
    if (planes[a] >= 0)
      bis[nb++] = planes[a];
    else
      onFacet[-planes[a] - 1] = true;
  }
  std::sort(bis.begin(), bis.begin() + nb);
  std::array<std::int32_t, 4> verts{};
  int nvtx = 0;
  for (int a = 0; a <= k; ++a)
    if (!onFacet[a])
      verts[nvtx++] = cell[a];
  std::sort(verts.begin(), verts.begin() + nvtx);
  int n = 0;
  key[n++] = nb;
  for (int i = 0; i < nb; ++i)
    key[n++] = bis[i];
  for (int i = 0; i < nvtx; ++i)
    key[n++] = verts[i];
  return key;
}

/// Accumulates one cell at a time (local points, faces, 2D loop) and appends it to the output.
class CellBuilder
{
public:
  CellBuilder(RestrictedVoronoiCells& out, double shrink)
    : Out(out)
    , K(out.SimplexDim)
    , Shrink(shrink)
  {
    Out.CellPointOffsets.assign(1, 0);
    Out.CellFaceOffsets.assign(1, 0);
    Out.FaceOffsets.assign(1, 0);
    if (K == 2)
      Out.CellLoopOffsets.assign(1, 0);
  }

  // Scratch of the current cell: local points and faces (local ids).
  std::vector<std::array<double, 3>> P;
  std::vector<std::int64_t> FaceIds; // concatenated
  std::vector<int> FaceSizes;
  std::vector<std::int64_t> Loop; // 2D polygon loop (local ids)

  void Begin()
  {
    this->P.clear();
    this->FaceIds.clear();
    this->FaceSizes.clear();
    this->Kinds.clear();
    this->Neighbors.clear();
    this->Loop.clear();
  }

  void AddFace(const std::int64_t* ids, int n, RVDFaceKind kind, std::int32_t nbr)
  {
    this->FaceIds.insert(this->FaceIds.end(), ids, ids + n);
    this->FaceSizes.push_back(n);
    this->Kinds.push_back(kind);
    this->Neighbors.push_back(kind == RVDFaceKind::Bisector ? nbr : -1);
  }

  /// Emits the scratch cell: shrinks it about its vertex centroid, appends points and faces.
  void End(int site, int element, double measure, double embMeasure)
  {
    this->Compact();
    const std::size_t np = this->P.size();
    if (np == 0 || this->FaceSizes.empty())
      return;
    double c[3] = { 0, 0, 0 };
    for (const auto& p : this->P)
      for (int d = 0; d < 3; ++d)
        c[d] += p[d];
    for (double& v : c)
      v /= static_cast<double>(np);
    const std::int64_t base = static_cast<std::int64_t>(Out.NumPoints());
    for (const auto& p : this->P)
      for (int d = 0; d < 3; ++d)
        Out.Points.push_back(c[d] + this->Shrink * (p[d] - c[d]));
    Out.CellPointOffsets.push_back(static_cast<std::int64_t>(Out.NumPoints()));
    if (K == 2)
    {
      for (const std::int64_t id : this->Loop)
        Out.LoopPoints.push_back(base + id);
      Out.CellLoopOffsets.push_back(static_cast<std::int64_t>(Out.LoopPoints.size()));
    }
    const double scale = std::pow(this->Shrink, K);
    Out.CellSite.push_back(site);
    Out.CellElement.push_back(element);
    Out.CellMeasure.push_back(measure * scale);
    Out.CellEmbeddedMeasure.push_back(embMeasure * scale);
    for (const std::int64_t id : this->FaceIds)
      Out.FaceVertices.push_back(base + id);
    std::int64_t off = Out.FaceOffsets.back();
    for (std::size_t f = 0; f < this->FaceSizes.size(); ++f)
    {
      off += this->FaceSizes[f];
      Out.FaceOffsets.push_back(off);
      Out.FaceKind.push_back(this->Kinds[f]);
      Out.FaceNeighbor.push_back(this->Neighbors[f]);
    }
    Out.CellFaceOffsets.push_back(static_cast<std::int64_t>(Out.NumFaces()));
  }

private:
  RestrictedVoronoiCells& Out;
  int K;
  double Shrink;
  std::vector<RVDFaceKind> Kinds;
  std::vector<std::int32_t> Neighbors;
  std::vector<std::array<double, 3>> Q;
  std::vector<std::int64_t> Remap;

  // Drops the points no kept face uses (mesh vertices inside a merged cell, or points only on
  // dropped element faces) and renumbers faces and loop.
  void Compact()
  {
    std::vector<std::int64_t>& remap = this->Remap;
    remap.assign(this->P.size(), -1);
    this->Q.clear();
    for (std::int64_t& id : this->FaceIds)
    {
      if (remap[id] < 0)
      {
        remap[id] = static_cast<std::int64_t>(this->Q.size());
        this->Q.push_back(this->P[id]);
      }
      id = remap[id];
    }
    for (std::int64_t& id : this->Loop)
      id = remap[id];
    this->P.swap(this->Q);
  }
};

/// Builds the cells of one diagram: per piece, or per site with the pieces glued.
class CellAssembler
{
public:
  CellAssembler(const SimplexMesh& mesh, const RestrictedVoronoiDiagram& rvd,
    const std::vector<unsigned char>& flip, RestrictedVoronoiCells& out, double shrink)
    : Mesh(mesh)
    , Rvd(rvd)
    , Flip(flip)
    , K(mesh.SimplexDim)
    , Builder(out, shrink)
  {
  }

  /// Emits piece p on its own (MergeBySite off, or a 2D cell that is not one simple loop).
  void EmitPiece(std::size_t p)
  {
    Builder.Begin();
    const std::int64_t v0 = Rvd.PieceVertexOffsets[p], v1 = Rvd.PieceVertexOffsets[p + 1];
    const bool f = Flip[Rvd.PieceElement[p]];
    for (std::int64_t v = v0; v < v1; ++v)
      Builder.P.push_back(Point(v));
    if (K == 2)
    {
      for (std::int64_t v = v0; v < v1; ++v)
        Builder.Loop.push_back(f ? v1 - 1 - v : v - v0);
    }
    std::vector<std::int64_t>& ids = this->Ids;
    for (std::int64_t fc = Rvd.PieceFaceOffsets[p]; fc < Rvd.PieceFaceOffsets[p + 1]; ++fc)
    {
      ids.clear();
      for (std::int64_t i = Rvd.FaceOffsets[fc]; i < Rvd.FaceOffsets[fc + 1]; ++i)
        ids.push_back(Rvd.FaceVertices[i] - v0);
      if (f)
        std::reverse(ids.begin(), ids.end());
      Builder.AddFace(ids.data(), static_cast<int>(ids.size()), Rvd.FaceKind[fc], Rvd.FaceNeighbor[fc]);
    }
    Builder.End(Rvd.PieceSite[p], Rvd.PieceElement[p], Rvd.PieceMeasure[p], Rvd.PieceEmbeddedMeasure[p]);
  }

  /// Emits the pieces p0..p1-1 of one site as one cell (or, in 2D when they do not form one
  /// simple loop, one cell per piece).
  void EmitSite(std::size_t p0, std::size_t p1)
  {
    const std::int32_t site = Rvd.PieceSite[p0];
    double measure = 0.0, embMeasure = 0.0;
    for (std::size_t p = p0; p < p1; ++p)
    {
      measure += Rvd.PieceMeasure[p];
      embMeasure += Rvd.PieceEmbeddedMeasure[p];
    }
    Builder.Begin();
    GlueVertices(p0, p1);
    GlueFaces(p0, p1);
    if (K != 2 || ChainLoop())
      Builder.End(site, -1, measure, embMeasure);
    else
      for (std::size_t p = p0; p < p1; ++p)
        EmitPiece(p);
  }

private:
  const SimplexMesh& Mesh;
  const RestrictedVoronoiDiagram& Rvd;
  const std::vector<unsigned char>& Flip;
  int K;
  CellBuilder Builder;
  std::vector<std::pair<VertexKey, std::int64_t>> Keys;
  std::vector<std::int64_t> LocalOf, Ids, NextOf;

  std::array<double, 3> Point(std::int64_t v) const
  {
    const int adim = Mesh.AmbientDim;
    const double* x = Rvd.Points.data() + v * adim;
    return std::array<double, 3>{ x[0], x[1], adim == 3 ? x[2] : 0.0 };
  }

  // The site's vertices are contiguous: deduplicate them by their symbolic key (LocalOf: the
  // cell's point of every diagram vertex of the site).
  void GlueVertices(std::size_t p0, std::size_t p1)
  {
    const std::int64_t vb = Rvd.PieceVertexOffsets[p0], ve = Rvd.PieceVertexOffsets[p1];
    Keys.clear();
    for (std::size_t p = p0; p < p1; ++p)
    {
      const std::int32_t* cell = Mesh.Cell(Rvd.PieceElement[p]);
      for (std::int64_t v = Rvd.PieceVertexOffsets[p]; v < Rvd.PieceVertexOffsets[p + 1]; ++v)
        Keys.emplace_back(MakeKey(Rvd.VertexPlanes.data() + v * K, K, cell), v);
    }
    std::sort(Keys.begin(), Keys.end());
    LocalOf.assign(static_cast<std::size_t>(ve - vb), -1);
    for (std::size_t i = 0; i < Keys.size(); ++i)
    {
      if (i == 0 || Keys[i].first != Keys[i - 1].first)
        Builder.P.push_back(Point(Keys[i].second));
      LocalOf[Keys[i].second - vb] = static_cast<std::int64_t>(Builder.P.size() - 1);
    }
  }

  // The pieces' faces on the glued points; faces that collapse (degenerate) are dropped.
  void GlueFaces(std::size_t p0, std::size_t p1)
  {
    const std::int64_t vb = Rvd.PieceVertexOffsets[p0];
    std::vector<std::int64_t>& ids = this->Ids;
    for (std::size_t p = p0; p < p1; ++p)
    {
      const bool f = Flip[Rvd.PieceElement[p]];
      for (std::int64_t fc = Rvd.PieceFaceOffsets[p]; fc < Rvd.PieceFaceOffsets[p + 1]; ++fc)
      {
        ids.clear();
        for (std::int64_t i = Rvd.FaceOffsets[fc]; i < Rvd.FaceOffsets[fc + 1]; ++i)
        {
          const std::int64_t l = LocalOf[Rvd.FaceVertices[i] - vb];
          if (ids.empty() || ids.back() != l)
            ids.push_back(l);
        }
        while (ids.size() > 1 && ids.front() == ids.back())
          ids.pop_back();
        if (ids.size() < static_cast<std::size_t>(K))
          continue; // collapsed (degenerate) face
        if (f)
          std::reverse(ids.begin(), ids.end());
        Builder.AddFace(ids.data(), static_cast<int>(ids.size()), Rvd.FaceKind[fc], Rvd.FaceNeighbor[fc]);
      }
    }
  }

  // 2D: chains the kept edges into one loop (Builder.Loop); false for anything else (holes,
  // several components, inconsistent orientation).
  bool ChainLoop()
  {
    bool ok = true;
    const std::size_t nl = Builder.P.size(), ne = Builder.FaceSizes.size();
    const std::vector<std::int64_t>& edges = Builder.FaceIds;
    NextOf.assign(nl, -1);
    for (std::size_t e = 0; e < ne && ok; ++e)
    {
      const std::int64_t a = edges[2 * e], b = edges[2 * e + 1];
      if (NextOf[a] >= 0)
        ok = false;
      NextOf[a] = b;
    }
    std::vector<std::int64_t>& loop = Builder.Loop;
    loop.clear();
    if (ok && ne > 0)
    {
      std::int64_t v = edges[0];
      do
      {
        loop.push_back(v);
        v = NextOf[v];
      } while (v >= 0 && v != edges[0] && loop.size() <= ne);
      ok = v == edges[0] && loop.size() == ne;
    }
    return ok;
  }
};

// Per element: whether its pieces must be reversed (negative orientation of a tet or a flat
// triangle), and the domain measure.
std::vector<unsigned char> ElementFlips(const SimplexMesh& mesh, double& domain)
{
  const int K = mesh.SimplexDim, adim = mesh.AmbientDim;
  const bool orientable = K == 3 || adim == 2;
  std::vector<unsigned char> flip(mesh.NumCells(), 0);
  domain = 0.0;
  for (std::size_t c = 0; c < mesh.NumCells(); ++c)
  {
    const double s = CellMeasure(mesh, c); // signed for tets and flat triangles
    flip[c] = orientable && s < 0;
    domain += std::abs(s);
  }
  return flip;
}

} // namespace

RestrictedVoronoiCells BuildRestrictedVoronoiCells(const SimplexMesh& mesh,
  const RestrictedVoronoiDiagram& rvd, const RestrictedVoronoiCellOptions& options)
{
  RestrictedVoronoiCells out;
  out.SimplexDim = mesh.SimplexDim;
  const std::vector<unsigned char> flip = ElementFlips(mesh, out.DomainMeasure);
  for (double m : rvd.PieceMeasure)
    out.TotalMeasure += m;
  CellAssembler cells(mesh, rvd, flip, out, options.ShrinkFactor);
  const std::size_t np = rvd.NumPieces();
  if (!options.MergeBySite)
  {
    for (std::size_t p = 0; p < np; ++p)
      cells.EmitPiece(p);
    std::vector<unsigned char> seen(rvd.NumSites, 0);
    for (std::size_t p = 0; p < np; ++p)
      seen[rvd.PieceSite[p]] = 1;
    out.NumNonEmptySites = static_cast<std::size_t>(std::count(seen.begin(), seen.end(), 1));
    return out;
  }
  for (std::size_t p0 = 0; p0 < np;)
  {
    std::size_t p1 = p0;
    while (p1 < np && rvd.PieceSite[p1] == rvd.PieceSite[p0])
      ++p1;
    ++out.NumNonEmptySites;
    cells.EmitSite(p0, p1);
    p0 = p1;
    if ((out.NumNonEmptySites & 1023) == 0 && options.Abort && options.Abort())
    {
      out.Aborted = true;
      break;
    }
  }
  return out;
}

} // namespace av
