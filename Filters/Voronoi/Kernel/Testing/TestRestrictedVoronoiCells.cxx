// SPDX-License-Identifier: BSD-3-Clause
// RVD cells (BuildRestrictedVoronoiCells): merged cells are closed, outward surfaces whose
// vertices are glued across elements, their measures partition the domain, pieces add up to
// the merged cells, face kinds and neighbors, shrink, mirrored meshes, 2D loops, abort.
#include "RestrictedVoronoiCells.h"
#include "AnisoTestChecks.h"
#include "VoronoiTestMeshes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

using namespace av_test;

namespace
{

const double* CellPoint(const av::RestrictedVoronoiCells& c, std::int64_t id)
{
  return c.Points.data() + 3 * id;
}

/// Area vector of face f (fan from its first vertex).
void AreaVector(const av::RestrictedVoronoiCells& c, std::int64_t f, double a[3])
{
  a[0] = a[1] = a[2] = 0.0;
  const std::int64_t b = c.FaceOffsets[f], e = c.FaceOffsets[f + 1];
  const double* p0 = CellPoint(c, c.FaceVertices[b]);
  for (std::int64_t i = b + 1; i + 1 < e; ++i)
  {
    const double* p1 = CellPoint(c, c.FaceVertices[i]);
    const double* p2 = CellPoint(c, c.FaceVertices[i + 1]);
    const double u[3] = { p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2] };
    const double v[3] = { p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2] };
    a[0] += 0.5 * (u[1] * v[2] - u[2] * v[1]);
    a[1] += 0.5 * (u[2] * v[0] - u[0] * v[2]);
    a[2] += 0.5 * (u[0] * v[1] - u[1] * v[0]);
  }
}

/// Measure of the faces (3D: area, 2D: edge length) of one kind.
double FaceMeasure(const av::RestrictedVoronoiCells& c, av::RVDFaceKind kind)
{
  double total = 0.0;
  for (std::size_t f = 0; f < c.NumFaces(); ++f)
  {
    if (c.FaceKind[f] != kind)
      continue;
    if (c.SimplexDim == 2)
    {
      const double* p = CellPoint(c, c.FaceVertices[c.FaceOffsets[f]]);
      const double* q = CellPoint(c, c.FaceVertices[c.FaceOffsets[f] + 1]);
      total += std::hypot(q[0] - p[0], q[1] - p[1], q[2] - p[2]);
      continue;
    }
    double a[3];
    AreaVector(c, static_cast<std::int64_t>(f), a);
    total += std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  }
  return total;
}

struct PolyhedraCheck
{
  int Open = 0;       ///< cells whose directed edges are not matched by their reverses once
  int Coincident = 0; ///< cells with two points at the same place (vertices not glued)
  double TotalMeasure = 0.0, TotalVolume = 0.0, MaxVolumeError = 0.0;
  std::map<int, double> MeasureBySite;
};

/// Points of cell c at the same place (up to 1e-12): what a missed glue leaves behind.
int CoincidentPoints(const av::RestrictedVoronoiCells& cells, std::size_t c)
{
  std::vector<std::array<double, 3>> pts;
  for (std::int64_t i = cells.CellPointOffsets[c]; i < cells.CellPointOffsets[c + 1]; ++i)
    pts.push_back({ CellPoint(cells, i)[0], CellPoint(cells, i)[1], CellPoint(cells, i)[2] });
  std::sort(pts.begin(), pts.end());
  int n = 0;
  for (std::size_t i = 1; i < pts.size(); ++i)
    n += std::abs(pts[i][0] - pts[i - 1][0]) + std::abs(pts[i][1] - pts[i - 1][1]) +
        std::abs(pts[i][2] - pts[i - 1][2]) < 1e-12;
  return n;
}

/// Every cell closed (each directed edge of its faces matched by its reverse exactly once),
/// its divergence-theorem volume equal to its measure, its points distinct.
PolyhedraCheck CheckPolyhedra(const av::RestrictedVoronoiCells& cells)
{
  PolyhedraCheck r;
  for (std::size_t c = 0; c < cells.NumCells(); ++c)
  {
    std::map<std::pair<std::int64_t, std::int64_t>, int> edges;
    double vol = 0.0;
    for (std::int64_t f = cells.CellFaceOffsets[c]; f < cells.CellFaceOffsets[c + 1]; ++f)
    {
      const std::int64_t b = cells.FaceOffsets[f], e = cells.FaceOffsets[f + 1];
      for (std::int64_t i = b; i < e; ++i)
        ++edges[{ cells.FaceVertices[i], cells.FaceVertices[i + 1 == e ? b : i + 1] }];
      double a[3];
      AreaVector(cells, f, a);
      const double* p = CellPoint(cells, cells.FaceVertices[b]);
      vol += (a[0] * p[0] + a[1] * p[1] + a[2] * p[2]) / 3.0;
    }
    bool closed = !edges.empty();
    for (const auto& e : edges)
    {
      const auto rev = edges.find({ e.first.second, e.first.first });
      closed = closed && e.second == 1 && rev != edges.end() && rev->second == 1;
    }
    r.Open += closed ? 0 : 1;
    r.Coincident += CoincidentPoints(cells, c) > 0 ? 1 : 0;
    const double m = cells.CellMeasure[c];
    r.TotalMeasure += m;
    r.TotalVolume += vol;
    r.MaxVolumeError = std::max(r.MaxVolumeError, std::abs(vol - m) / std::max(m, 1e-300));
    r.MeasureBySite[cells.CellSite[c]] += m;
  }
  return r;
}

/// Face kinds and neighbors: bisectors name another site, other faces -1.
void CheckFaceNeighbors(const av::RestrictedVoronoiCells& cells, std::size_t numSites)
{
  int bad = 0;
  for (std::size_t c = 0; c < cells.NumCells(); ++c)
    for (std::int64_t f = cells.CellFaceOffsets[c]; f < cells.CellFaceOffsets[c + 1]; ++f)
    {
      const std::int32_t n = cells.FaceNeighbor[f];
      if (cells.FaceKind[f] == av::RVDFaceKind::Bisector)
        bad += n < 0 || n >= static_cast<std::int32_t>(numSites) || n == cells.CellSite[c];
      else
        bad += n != -1;
    }
  AV_CHECK_MSG(bad == 0, bad << " faces with a wrong neighbor");
}

struct VolumeCase
{
  av::SimplexMesh Mesh;
  av::Embedding Emb;
  av::SiteSet Sites;
};

/// The unit cube (7^3 Kuhn grid, optionally mirrored in x) in a smooth 8D embedding, 60 sites.
VolumeCase MakeVolumeCase(bool mirrored)
{
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
  VolumeCase v;
  v.Mesh = KuhnGrid(7, 7, 7, lo, hi);
  if (mirrored)
    for (std::size_t i = 0; i < v.Mesh.NumPoints(); ++i)
      v.Mesh.Points[3 * i] = -v.Mesh.Points[3 * i];
  v.Emb = MakeEmbedding(v.Mesh, 8, SmoothExtra3);
  v.Sites = RandomSites(v.Mesh, v.Emb, 60, 5);
  return v;
}

av::RestrictedVoronoiDiagram Diagram(const VolumeCase& v, bool merge)
{
  av::RestrictedVoronoiOptions o;
  o.MergeBySite = merge;
  return av::ComputeRestrictedVoronoi(v.Mesh, v.Emb, v.Sites, o);
}

av::RestrictedVoronoiCells Cells(const av::SimplexMesh& m, const av::RestrictedVoronoiDiagram& r,
  bool merge, double shrink = 1.0)
{
  av::RestrictedVoronoiCellOptions o;
  o.MergeBySite = merge;
  o.ShrinkFactor = shrink;
  return av::BuildRestrictedVoronoiCells(m, r, o);
}

/// One closed polyhedron per site, glued, partitioning the cube.
void TestMergedPolyhedra()
{
  const VolumeCase v = MakeVolumeCase(false);
  const av::RestrictedVoronoiDiagram r = Diagram(v, true);
  const av::RestrictedVoronoiCells c = Cells(v.Mesh, r, true);
  AV_CHECK(c.NumCells() == v.Sites.NumSites());
  AV_CHECK(c.NumNonEmptySites == v.Sites.NumSites());
  AV_CHECK(!c.Aborted);
  for (std::size_t i = 0; i < c.NumCells(); ++i)
  {
    AV_CHECK(c.CellSite[i] == static_cast<std::int32_t>(i)); // by site, all non-empty
    AV_CHECK(c.CellElement[i] == -1);
  }
  const PolyhedraCheck k = CheckPolyhedra(c);
  AV_CHECK_MSG(k.Open == 0, k.Open << " open cells");
  AV_CHECK_MSG(k.Coincident == 0, k.Coincident << " cells with unglued vertices");
  AV_CHECK_MSG(k.MaxVolumeError < 1e-8, "volume vs measure " << k.MaxVolumeError);
  AV_CHECK_NEAR(k.TotalMeasure, 1.0, 1e-9);
  AV_CHECK_NEAR(k.TotalVolume, 1.0, 1e-9);
  AV_CHECK_NEAR(c.DomainMeasure, 1.0, 1e-12);
  double pieces = 0.0;
  for (double m : r.PieceMeasure)
    pieces += m;
  AV_CHECK(c.TotalMeasure == pieces);
  // Face kinds: no element faces once merged; the boundary faces tile the cube's surface.
  AV_CHECK(std::count(c.FaceKind.begin(), c.FaceKind.end(), av::RVDFaceKind::ElementFace) == 0);
  AV_CHECK_NEAR(FaceMeasure(c, av::RVDFaceKind::DomainBoundary), 6.0, 1e-9);
  AV_CHECK(FaceMeasure(c, av::RVDFaceKind::Bisector) > 0.0);
  CheckFaceNeighbors(c, v.Sites.NumSites());
  // Gluing: a cell has fewer points than its pieces' vertices.
  AV_CHECK(c.NumPoints() < r.NumVertices());
}

/// One closed polyhedron per piece; per site they add up to the merged cells.
void TestPiecePolyhedra()
{
  const VolumeCase v = MakeVolumeCase(false);
  const av::RestrictedVoronoiDiagram r = Diagram(v, false);
  const av::RestrictedVoronoiCells c = Cells(v.Mesh, r, false);
  AV_CHECK(c.NumCells() == r.NumPieces());
  AV_CHECK(c.NumNonEmptySites == v.Sites.NumSites());
  bool same = c.NumCells() == r.NumPieces();
  for (std::size_t p = 0; same && p < r.NumPieces(); ++p)
    same = c.CellSite[p] == r.PieceSite[p] && c.CellElement[p] == r.PieceElement[p] &&
      c.CellMeasure[p] == r.PieceMeasure[p] && c.CellEmbeddedMeasure[p] == r.PieceEmbeddedMeasure[p];
  AV_CHECK(same);
  PolyhedraCheck k = CheckPolyhedra(c);
  AV_CHECK(k.Open == 0 && k.Coincident == 0);
  AV_CHECK(k.MaxVolumeError < 1e-8);
  AV_CHECK(std::count(c.FaceKind.begin(), c.FaceKind.end(), av::RVDFaceKind::ElementFace) > 0);
  CheckFaceNeighbors(c, v.Sites.NumSites());
  const PolyhedraCheck merged = CheckPolyhedra(Cells(v.Mesh, Diagram(v, true), true));
  double worst = 0.0;
  for (const auto& s : merged.MeasureBySite)
    worst = std::max(worst, std::abs(k.MeasureBySite[s.first] - s.second) / s.second);
  AV_CHECK_MSG(worst < 1e-12, "pieces vs merged cells " << worst);
}

/// Shrink: each cell scaled about its vertex centroid (measure x s^3, volume x s^3).
void TestShrink()
{
  const VolumeCase v = MakeVolumeCase(false);
  const av::RestrictedVoronoiDiagram r = Diagram(v, true);
  const av::RestrictedVoronoiCells full = Cells(v.Mesh, r, true);
  const av::RestrictedVoronoiCells half = Cells(v.Mesh, r, true, 0.5);
  AV_CHECK(half.NumCells() == full.NumCells() && half.NumPoints() == full.NumPoints());
  const PolyhedraCheck a = CheckPolyhedra(full), b = CheckPolyhedra(half);
  AV_CHECK(b.Open == 0);
  AV_CHECK_NEAR(b.TotalMeasure / a.TotalMeasure, 0.125, 1e-12);
  AV_CHECK_NEAR(b.TotalVolume / a.TotalVolume, 0.125, 1e-9);
  AV_CHECK(b.MaxVolumeError < 1e-8);
  AV_CHECK(half.TotalMeasure == full.TotalMeasure); // the true cells
  double worst = 0.0;
  for (std::size_t c = 0; c < full.NumCells(); ++c)
  {
    double ca[3] = { 0, 0, 0 }, cb[3] = { 0, 0, 0 };
    for (std::int64_t i = full.CellPointOffsets[c]; i < full.CellPointOffsets[c + 1]; ++i)
      for (int d = 0; d < 3; ++d)
      {
        ca[d] += CellPoint(full, i)[d];
        cb[d] += CellPoint(half, i)[d];
      }
    for (int d = 0; d < 3; ++d)
      worst = std::max(worst, std::abs(ca[d] - cb[d]));
  }
  AV_CHECK_MSG(worst < 1e-12, "centroids moved by " << worst);
}

/// Negatively oriented tets: the cells are still outward (positive divergence volume).
void TestMirroredVolume()
{
  const VolumeCase v = MakeVolumeCase(true);
  AV_CHECK(av::CellMeasure(v.Mesh, 0) < 0.0);
  const av::RestrictedVoronoiCells c = Cells(v.Mesh, Diagram(v, true), true);
  const PolyhedraCheck k = CheckPolyhedra(c);
  AV_CHECK(k.Open == 0);
  AV_CHECK_MSG(k.MaxVolumeError < 1e-8, "mirrored: volume vs measure " << k.MaxVolumeError);
  AV_CHECK_NEAR(k.TotalVolume, 1.0, 1e-9);
  AV_CHECK_NEAR(c.DomainMeasure, 1.0, 1e-12);
}

/// 2D: every merged cell one counter-clockwise loop along its edges, shoelace area = measure.
void CheckLoops(const av::RestrictedVoronoiCells& c, const char* name)
{
  int bad = 0;
  double total = 0.0;
  for (std::size_t i = 0; i < c.NumCells(); ++i)
  {
    const std::int64_t l0 = c.CellLoopOffsets[i], l1 = c.CellLoopOffsets[i + 1];
    const std::int64_t f0 = c.CellFaceOffsets[i], f1 = c.CellFaceOffsets[i + 1];
    double area = 0.0;
    for (std::int64_t t = l0; t < l1; ++t)
    {
      const double* p = CellPoint(c, c.LoopPoints[t]);
      const double* q = CellPoint(c, c.LoopPoints[t + 1 == l1 ? l0 : t + 1]);
      area += 0.5 * (p[0] * q[1] - p[1] * q[0]);
    }
    std::map<std::int64_t, std::int64_t> next;
    for (std::int64_t f = f0; f < f1; ++f)
      next[c.FaceVertices[c.FaceOffsets[f]]] = c.FaceVertices[c.FaceOffsets[f] + 1];
    bool chained = l1 - l0 == f1 - f0 && static_cast<std::int64_t>(next.size()) == f1 - f0;
    for (std::int64_t t = l0; chained && t < l1; ++t)
      chained = next[c.LoopPoints[t]] == c.LoopPoints[t + 1 == l1 ? l0 : t + 1];
    bad += !chained || std::abs(area - c.CellMeasure[i]) > 1e-9 * (1.0 + c.CellMeasure[i]);
    total += c.CellMeasure[i];
  }
  AV_CHECK_MSG(bad == 0, name << ": " << bad << " cells are not a loop of their edges with its area");
  AV_CHECK_NEAR(total, 1.0, 1e-9);
  AV_CHECK_NEAR(c.DomainMeasure, 1.0, 1e-12);
  AV_CHECK_NEAR(FaceMeasure(c, av::RVDFaceKind::DomainBoundary), 4.0, 1e-9);
}

void TestPolygons()
{
  for (const bool mirrored : { false, true })
  {
    av::SimplexMesh m = TriGrid(13, 13, 0, 0, 1, 1);
    if (mirrored)
      for (std::size_t i = 0; i < m.NumPoints(); ++i)
        m.Points[2 * i + 1] = 1.0 - m.Points[2 * i + 1];
    const av::Embedding e = MakeEmbedding(m, 5, SmoothExtra);
    const av::SiteSet s = RandomSites(m, e, 40, 1);
    av::RestrictedVoronoiOptions o;
    o.MergeBySite = true;
    const av::RestrictedVoronoiCells c = Cells(m, av::ComputeRestrictedVoronoi(m, e, s, o), true);
    AV_CHECK(c.NumCells() == s.NumSites() && c.NumNonEmptySites == s.NumSites());
    CheckLoops(c, mirrored ? "mirrored square" : "square");
    CheckFaceNeighbors(c, s.NumSites());
  }
}

/// Abort: polled every 1024 sites, the cells so far are kept.
void TestAbort()
{
  const av::SimplexMesh m = TriGrid(41, 41, 0, 0, 1, 1);
  const av::Embedding e = MakeEmbedding(m, 2, nullptr);
  const av::SiteSet s = RandomSites(m, e, 1100, 2);
  av::RestrictedVoronoiOptions o;
  o.MergeBySite = true;
  const av::RestrictedVoronoiDiagram r = av::ComputeRestrictedVoronoi(m, e, s, o);
  av::RestrictedVoronoiCellOptions co;
  int polls = 0;
  co.Abort = [&] { return ++polls > 0; };
  const av::RestrictedVoronoiCells c = av::BuildRestrictedVoronoiCells(m, r, co);
  AV_CHECK(c.Aborted && polls == 1);
  AV_CHECK(c.NumNonEmptySites == 1024 && c.NumCells() <= 1024);
  const av::RestrictedVoronoiCells all = av::BuildRestrictedVoronoiCells(m, r);
  AV_CHECK(!all.Aborted && all.NumNonEmptySites > 1024 && all.NumCells() > c.NumCells());
}

} // namespace

int TestRestrictedVoronoiCells(int, char*[])
{
  TestMergedPolyhedra();
  TestPiecePolyhedra();
  TestShrink();
  TestMirroredVolume();
  TestPolygons();
  TestAbort();
  return AV_TEST_RESULT();
}
