// SPDX-License-Identifier: BSD-3-Clause
// Restricted Voronoi diagram: partition of the domain, nearest-site property of every piece,
// brute-force cells, face bookkeeping, determinism, bad input. `TestRestrictedVoronoi bench`
// times the cube2-sized case (101x21x21 Kuhn grid, 8D, 5000 sites).
#include "RestrictedVoronoi.h"
#include "Stopwatch.h"
#include "AnisoTestChecks.h"
#include "VoronoiTestMeshes.h"

#include <chrono>
#include <ctime>
#include <cstring>
#include <iostream>
#include <map>
#include <random>

using namespace av_test;

namespace
{

// The diagram with its vertices in R^Dim too (CheckNearestSite reads them; off by default).
av::RestrictedVoronoiDiagram Rvd(const av::SimplexMesh& m, const av::Embedding& e,
  const av::SiteSet& s, av::RestrictedVoronoiOptions o = av::RestrictedVoronoiOptions())
{
  o.KeepEmbeddedPoints = true;
  return av::ComputeRestrictedVoronoi(m, e, s, o);
}

double MeshMeasure(const av::SimplexMesh& m, const double* pts, int dim)
{
  // Sum of element measures through the Gram determinant, independent of the RVD code.
  double total = 0.0;
  for (std::size_t c = 0; c < m.NumCells(); ++c)
    total += GramCellMeasure(m, pts, dim, c);
  return total;
}

void CheckPartition(const av::SimplexMesh& m, const av::Embedding& e,
  const av::RestrictedVoronoiDiagram& r, const char* name)
{
  double in = 0.0, emb = 0.0;
  for (std::size_t p = 0; p < r.NumPieces(); ++p)
  {
    in += r.PieceMeasure[p];
    emb += r.PieceEmbeddedMeasure[p];
  }
  const double inRef = MeshMeasure(m, m.Points.data(), m.AmbientDim);
  const double embRef = MeshMeasure(m, e.Coords.data(), e.Dim);
  AV_CHECK_MSG(std::abs(in - inRef) <= 1e-9 * inRef, name << ": input measure " << in << " vs " << inRef);
  AV_CHECK_MSG(std::abs(emb - embRef) <= 1e-9 * embRef, name << ": embedded measure " << emb << " vs " << embRef);
}

// Random points of every piece (its vertices and convex combinations of them) are not closer
// to another site than to the piece's own site, in R^Dim, by brute force over all sites.
void CheckNearestSite(const av::RestrictedVoronoiDiagram& r, const av::SiteSet& s, const char* name)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int dim = r.Dim;
  std::vector<double> x(dim);
  std::size_t bad = 0;
  double worst = 0.0;
  for (std::size_t p = 0; p < r.NumPieces(); ++p)
  {
    const std::int64_t v0 = r.PieceVertexOffsets[p], v1 = r.PieceVertexOffsets[p + 1];
    const int nvp = static_cast<int>(v1 - v0);
    for (int sample = 0; sample < nvp + 4; ++sample)
    {
      std::vector<double> w(nvp, 0.0);
      if (sample < nvp)
        w[sample] = 1.0;
      else
      {
        double sum = 0.0;
        for (auto& wi : w)
          sum += (wi = -std::log(1.0 - u(rng)));
        for (auto& wi : w)
          wi /= sum;
      }
      std::fill(x.begin(), x.end(), 0.0);
      for (int a = 0; a < nvp; ++a)
        for (int d = 0; d < dim; ++d)
          x[d] += w[a] * r.EmbeddedPoints[(v0 + a) * dim + d];
      auto dist2 = [&](std::size_t site) {
        double t = 0.0;
        for (int d = 0; d < dim; ++d)
          t += (x[d] - s.At(site)[d]) * (x[d] - s.At(site)[d]);
        return t;
      };
      const double own = dist2(r.PieceSite[p]);
      double best = own;
      for (std::size_t q = 0; q < s.NumSites(); ++q)
        best = std::min(best, dist2(q));
      const double excess = own - best;
      if (excess > 1e-10 * (1.0 + own))
      {
        ++bad;
        worst = std::max(worst, excess);
      }
    }
  }
  AV_CHECK_MSG(bad == 0, name << ": " << bad << " sample points closer to another site (worst "
                              << worst << ")");
}

// Area (input space) of face f; 2D: the edge's length.
double FaceMeasureOf(const av::RestrictedVoronoiDiagram& r, std::size_t f)
{
  const int ad = r.AmbientDim;
  const std::int64_t a = r.FaceOffsets[f], b = r.FaceOffsets[f + 1];
  const double* p0 = &r.Points[r.FaceVertices[a] * ad];
  if (r.SimplexDim == 2)
  {
    const double* p1 = &r.Points[r.FaceVertices[a + 1] * ad];
    double l = 0.0;
    for (int d = 0; d < ad; ++d)
      l += (p1[d] - p0[d]) * (p1[d] - p0[d]);
    return std::sqrt(l);
  }
  double n[3] = { 0, 0, 0 };
  for (std::int64_t i = a + 1; i + 1 < b; ++i)
  {
    const double* p1 = &r.Points[r.FaceVertices[i] * ad];
    const double* p2 = &r.Points[r.FaceVertices[i + 1] * ad];
    const double u[3] = { p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2] };
    const double v[3] = { p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2] };
    n[0] += u[1] * v[2] - u[2] * v[1];
    n[1] += u[2] * v[0] - u[0] * v[2];
    n[2] += u[0] * v[1] - u[1] * v[0];
  }
  return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

// Sum of the polygon areas (input space) of faces of a given kind; 2D: edge lengths.
double FaceMeasure(const av::RestrictedVoronoiDiagram& r, av::RVDFaceKind kind)
{
  double total = 0.0;
  for (std::size_t f = 0; f < r.NumFaces(); ++f)
    if (r.FaceKind[f] == kind)
      total += FaceMeasureOf(r, f);
  return total;
}

// Bisector faces of i towards j and of j towards i cover the same surface.
void CheckBisectorSymmetry(const av::RestrictedVoronoiDiagram& r, const char* name)
{
  std::map<std::pair<int, int>, double> area;
  for (std::size_t p = 0; p < r.NumPieces(); ++p)
    for (std::int64_t f = r.PieceFaceOffsets[p]; f < r.PieceFaceOffsets[p + 1]; ++f)
      if (r.FaceKind[f] == av::RVDFaceKind::Bisector)
        area[{ r.PieceSite[p], r.FaceNeighbor[f] }] += FaceMeasureOf(r, static_cast<std::size_t>(f));
  int bad = 0;
  for (const auto& kv : area)
  {
    const auto it = area.find({ kv.first.second, kv.first.first });
    const double other = it == area.end() ? 0.0 : it->second;
    if (std::abs(other - kv.second) > 1e-9 * (1.0 + kv.second))
      ++bad;
  }
  AV_CHECK_MSG(bad == 0, name << ": " << bad << " asymmetric bisector faces");
}

// Brute-force Voronoi cell of site i in the box [0,1]^2 (Sutherland-Hodgman, all bisectors).
double BruteCellArea(const av::SiteSet& s, std::size_t i)
{
  std::vector<std::array<double, 2>> poly = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
  const double* p = s.At(i);
  for (std::size_t j = 0; j < s.NumSites() && !poly.empty(); ++j)
  {
    if (j == i)
      continue;
    const double* q = s.At(j);
    auto f = [&](const std::array<double, 2>& x) {
      return (x[0] - p[0]) * (x[0] - p[0]) + (x[1] - p[1]) * (x[1] - p[1]) -
        (x[0] - q[0]) * (x[0] - q[0]) - (x[1] - q[1]) * (x[1] - q[1]);
    };
    std::vector<std::array<double, 2>> out;
    for (std::size_t t = 0; t < poly.size(); ++t)
    {
      const auto& a = poly[t];
      const auto& b = poly[(t + 1) % poly.size()];
      const double fa = f(a), fb = f(b);
      if (fa <= 0)
        out.push_back(a);
      if ((fa <= 0) != (fb <= 0))
      {
        const double w = fa / (fa - fb);
        out.push_back({ a[0] + w * (b[0] - a[0]), a[1] + w * (b[1] - a[1]) });
      }
    }
    poly = out;
  }
  double area = 0.0;
  for (std::size_t t = 0; t < poly.size(); ++t)
    area += poly[t][0] * poly[(t + 1) % poly.size()][1] - poly[t][1] * poly[(t + 1) % poly.size()][0];
  return 0.5 * area;
}

void TestSquareIdentity()
{
  const av::SimplexMesh m = TriGrid(13, 13, 0, 0, 1, 1);
  const av::Embedding e = MakeEmbedding(m, 2, nullptr);
  const av::SiteSet s = RandomSites(m, e, 40, 1);
  const av::RestrictedVoronoiDiagram r = Rvd(m, e, s);
  CheckPartition(m, e, r, "square");
  CheckNearestSite(r, s, "square");
  CheckBisectorSymmetry(r, "square");
  AV_CHECK_NEAR(FaceMeasure(r, av::RVDFaceKind::DomainBoundary), 4.0, 1e-9);
  int bad = 0;
  for (std::size_t i = 0; i < s.NumSites(); ++i)
    if (std::abs(r.SiteMeasure[i] - BruteCellArea(s, i)) > 1e-9)
      ++bad;
  AV_CHECK_MSG(bad == 0, bad << " cells differ from the brute-force Voronoi cells");
  for (std::size_t i = 0; i < s.NumSites(); ++i)
    AV_CHECK(r.SiteMeasure[i] > 0.0);
  // Internal element edges are labelled with the neighboring element.
  for (std::size_t f = 0; f < r.NumFaces(); ++f)
    if (r.FaceKind[f] == av::RVDFaceKind::ElementFace)
      AV_CHECK(r.FaceNeighbor[f] >= 0 && r.FaceNeighbor[f] < static_cast<int>(m.NumCells()));

  // Same sites, same cells when the embedding is padded with zeros to 8D.
  const av::Embedding e8 = MakeEmbedding(m, 8, nullptr);
  av::SiteSet s8 = s;
  s8.Dim = 8;
  s8.Coords.clear();
  for (std::size_t i = 0; i < s.NumSites(); ++i)
    for (int d = 0; d < 8; ++d)
      s8.Coords.push_back(d < 2 ? s.At(i)[d] : 0.0);
  const av::RestrictedVoronoiDiagram r8 = Rvd(m, e8, s8);
  double diff = 0.0;
  for (std::size_t i = 0; i < s.NumSites(); ++i)
    diff = std::max(diff, std::abs(r8.SiteMeasure[i] - r.SiteMeasure[i]));
  AV_CHECK_NEAR(diff, 0.0, 1e-12);
}

void TestHeightField()
{
  const av::SimplexMesh m = TriGrid(21, 21, 0, 0, 1, 1);
  // (x, y, h(x, y)) and an 8D smooth map.
  const av::Embedding e3 = MakeEmbedding(m, 3, [](const double* x, int) {
    return 0.4 * std::exp(-8.0 * ((x[0] - 0.5) * (x[0] - 0.5) + (x[1] - 0.4) * (x[1] - 0.4)));
  });
  const av::SiteSet s3 = RandomSites(m, e3, 60, 2);
  const auto r3 = Rvd(m, e3, s3);
  CheckPartition(m, e3, r3, "height field");
  CheckNearestSite(r3, s3, "height field");
  CheckBisectorSymmetry(r3, "height field");
  AV_CHECK_NEAR(FaceMeasure(r3, av::RVDFaceKind::DomainBoundary), 4.0, 1e-9);

  const av::Embedding e8 = MakeEmbedding(m, 8, SmoothExtra);
  const av::SiteSet s8 = RandomSites(m, e8, 80, 3);
  const auto r8 = Rvd(m, e8, s8);
  CheckPartition(m, e8, r8, "2D smooth 8D");
  CheckNearestSite(r8, s8, "2D smooth 8D");

  // A surface in 3D (AmbientDim 3), embedded in 5D.
  av::SimplexMesh surf = m;
  surf.AmbientDim = 3;
  surf.Points.clear();
  for (std::size_t i = 0; i < m.NumPoints(); ++i)
  {
    const double* x = m.Point(i);
    surf.Points.insert(surf.Points.end(), { x[0], x[1], 0.3 * std::sin(3 * x[0]) * x[1] });
  }
  const av::Embedding es = MakeEmbedding(surf, 5, SmoothExtra3);
  const av::SiteSet ss = RandomSites(surf, es, 50, 4);
  const auto rs = Rvd(surf, es, ss);
  CheckPartition(surf, es, rs, "surface");
  CheckNearestSite(rs, ss, "surface");
}

void TestCube()
{
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
  const av::SimplexMesh m = KuhnGrid(7, 7, 7, lo, hi);
  const av::Embedding e = MakeEmbedding(m, 3, nullptr);
  const av::SiteSet s = RandomSites(m, e, 60, 5);
  const auto r = Rvd(m, e, s);
  CheckPartition(m, e, r, "cube");
  CheckNearestSite(r, s, "cube");
  CheckBisectorSymmetry(r, "cube");
  AV_CHECK_NEAR(FaceMeasure(r, av::RVDFaceKind::DomainBoundary), 6.0, 1e-9);
  for (std::size_t i = 0; i < s.NumSites(); ++i)
    AV_CHECK(r.SiteMeasure[i] > 0.0);
  // Closed pieces: face areas add to zero as vectors (each piece is a closed polyhedron).
  int open = 0;
  for (std::size_t p = 0; p < r.NumPieces(); ++p)
  {
    double n[3] = { 0, 0, 0 };
    for (std::int64_t f = r.PieceFaceOffsets[p]; f < r.PieceFaceOffsets[p + 1]; ++f)
    {
      const std::int64_t a = r.FaceOffsets[f], b = r.FaceOffsets[f + 1];
      const double* p0 = &r.Points[r.FaceVertices[a] * 3];
      for (std::int64_t i = a + 1; i + 1 < b; ++i)
      {
        const double* p1 = &r.Points[r.FaceVertices[i] * 3];
        const double* p2 = &r.Points[r.FaceVertices[i + 1] * 3];
        const double u[3] = { p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2] };
        const double v[3] = { p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2] };
        n[0] += u[1] * v[2] - u[2] * v[1];
        n[1] += u[2] * v[0] - u[0] * v[2];
        n[2] += u[0] * v[1] - u[1] * v[0];
      }
    }
    if (std::abs(n[0]) + std::abs(n[1]) + std::abs(n[2]) > 1e-12)
      ++open;
  }
  AV_CHECK_MSG(open == 0, open << " pieces are not closed polyhedra");

  // Smooth 8D embedding of a box.
  const double hi2[3] = { 1.0, 0.4, 0.4 };
  const av::SimplexMesh m2 = KuhnGrid(11, 5, 5, lo, hi2);
  const av::Embedding e8 = MakeEmbedding(m2, 8, SmoothExtra3);
  const av::SiteSet s8 = RandomSites(m2, e8, 50, 6);
  const auto r8 = Rvd(m2, e8, s8);
  CheckPartition(m2, e8, r8, "box 8D");
  CheckNearestSite(r8, s8, "box 8D");
  CheckBisectorSymmetry(r8, "box 8D");

  // Per-site cells: no internal element faces, pieces grouped by site, same measures.
  av::RestrictedVoronoiOptions opt;
  opt.MergeBySite = true;
  const auto rm = Rvd(m2, e8, s8, opt);
  bool sorted = true, noInternal = true;
  for (std::size_t p = 1; p < rm.NumPieces(); ++p)
    sorted = sorted && rm.PieceSite[p - 1] <= rm.PieceSite[p];
  for (auto k : rm.FaceKind)
    noInternal = noInternal && k != av::RVDFaceKind::ElementFace;
  AV_CHECK(sorted);
  AV_CHECK(noInternal);
  AV_CHECK(rm.NumPieces() == r8.NumPieces());
  AV_CHECK_NEAR(FaceMeasure(rm, av::RVDFaceKind::Bisector), FaceMeasure(r8, av::RVDFaceKind::Bisector), 1e-9);
  for (std::size_t i = 0; i < s8.NumSites(); ++i)
    AV_CHECK_NEAR(rm.SiteMeasure[i], r8.SiteMeasure[i], 1e-15);

  // Deterministic output.
  const auto r8b = Rvd(m2, e8, s8);
  AV_CHECK(r8b.PieceSite == r8.PieceSite && r8b.PieceMeasure == r8.PieceMeasure &&
    r8b.FaceVertices == r8.FaceVertices);

  // Measures only: same numbers, no geometry.
  av::RestrictedVoronoiOptions lean;
  lean.ComputeGeometry = false;
  const auto rl = Rvd(m2, e8, s8, lean);
  AV_CHECK(rl.PieceMeasure == r8.PieceMeasure && rl.Points.empty());

  // Default options: no copies in R^Dim, the rest unchanged.
  const auto rd = av::ComputeRestrictedVoronoi(m2, e8, s8);
  AV_CHECK(rd.EmbeddedPoints.empty() && !r8.EmbeddedPoints.empty());
  AV_CHECK(rd.Points == r8.Points && rd.VertexPlanes == r8.VertexPlanes &&
    rd.FaceVertices == r8.FaceVertices && rd.PieceMeasure == r8.PieceMeasure);
}

void TestDegenerateSites()
{
  // Sites on a lattice that matches the mesh: bisectors contain element faces and edges
  // (edges lying exactly in a bisector, parallel planes), as with the sampler's corner and
  // feature-line sites. Every vertex must be finite and the cells must still partition.
  const double lo[3] = { 0.0, 0.0, 0.0 }, hi[3] = { 1.0, 1.0, 1.0 };
  const av::SimplexMesh m = KuhnGrid(5, 5, 5, lo, hi);
  const av::Embedding e = MakeEmbedding(m, 5, nullptr);
  av::SiteSet s;
  s.Dim = 5;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
      {
        const double x[3] = { 0.5 * i, 0.5 * j, 0.5 * k };
        AV_CHECK(SiteAt(s, m, e, x));
      }
  const double mid[3] = { 1.0, 0.0, 1.0 / 3.0 }; // on a cube edge, between two vertices
  AV_CHECK(SiteAt(s, m, e, mid));
  const auto r = Rvd(m, e, s);
  std::size_t nonFinite = 0;
  for (double v : r.Points)
    nonFinite += std::isfinite(v) ? 0 : 1;
  for (double v : r.EmbeddedPoints)
    nonFinite += std::isfinite(v) ? 0 : 1;
  AV_CHECK_MSG(nonFinite == 0, nonFinite << " non-finite RVD coordinates");
  CheckPartition(m, e, r, "lattice sites");
  CheckNearestSite(r, s, "lattice sites");
}

void TestFewSites()
{
  // One site, then two: the security radius must fall back to "all sites used".
  const av::SimplexMesh m = TriGrid(6, 6, 0, 0, 1, 1);
  const av::Embedding e = MakeEmbedding(m, 2, nullptr);
  av::SiteSet s = RandomSites(m, e, 1, 8);
  auto r = Rvd(m, e, s);
  AV_CHECK_NEAR(r.SiteMeasure[0], 1.0, 1e-12);
  s = RandomSites(m, e, 3, 9);
  r = Rvd(m, e, s);
  CheckPartition(m, e, r, "three sites");
  CheckNearestSite(r, s, "three sites");
  // Small prefetch: the on-demand neighbor fetch must give the same result.
  const av::SiteSet s2 = RandomSites(m, e, 30, 10);
  av::RestrictedVoronoiOptions o;
  o.NumNeighbors = 2;
  const auto ra = Rvd(m, e, s2, o);
  const auto rb = Rvd(m, e, s2);
  for (std::size_t i = 0; i < s2.NumSites(); ++i)
    AV_CHECK_NEAR(ra.SiteMeasure[i], rb.SiteMeasure[i], 1e-12);
}

void TestBadInput()
{
  const av::SimplexMesh m = TriGrid(5, 5, 0, 0, 1, 1);
  const av::Embedding e = MakeEmbedding(m, 4, SmoothExtra);
  const av::SiteSet s = RandomSites(m, e, 10, 11);
  av::SiteSet none;
  none.Dim = 4;
  AV_CHECK_THROWS(Rvd(m, e, none));
  av::SiteSet b = s;
  b.CellIds[3] = static_cast<std::int32_t>(m.NumCells());
  AV_CHECK_THROWS(Rvd(m, e, b));
  b = s;
  b.Bary[4 * 2] += 0.1;
  AV_CHECK_THROWS(Rvd(m, e, b));
  b = s;
  b.Coords[5 * 4 + 2] += 0.5; // not on the embedded mesh
  AV_CHECK_THROWS(Rvd(m, e, b));
  b = s;
  b.Coords[1] = std::nan("");
  AV_CHECK_THROWS(Rvd(m, e, b));
  b = s;
  b.Dim = 3;
  AV_CHECK_THROWS(Rvd(m, e, b));
  av::Embedding eb = e;
  eb.Coords.pop_back();
  AV_CHECK_THROWS(Rvd(m, eb, s));
  av::SimplexMesh mb = m;
  mb.Cells[7] = 1000;
  AV_CHECK_THROWS(Rvd(mb, e, s));
  // Degenerate element (two vertices at the same place).
  av::Embedding ed = e;
  for (int d = 0; d < 4; ++d)
    ed.Coords[1 * 4 + d] = ed.Coords[0 * 4 + d];
  AV_CHECK_THROWS(Rvd(m, ed, av_test::RandomSites(m, ed, 5, 3)));
}

int Bench()
{
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
  const av::SimplexMesh m = KuhnGrid(101, 21, 21, lo, hi);
  const av::Embedding e = MakeEmbedding(m, 8, SmoothExtra3);
  const av::SiteSet s = RandomSites(m, e, 5000, 12);
  for (int geom = 0; geom < 2; ++geom)
    for (int rep = 0; rep < 1; ++rep)
    {
      av::RestrictedVoronoiOptions o;
      o.ComputeGeometry = geom != 0;
      const av::Stopwatch wall;
      const std::clock_t c0 = std::clock();
      const auto r = Rvd(m, e, s, o);
      const std::clock_t c1 = std::clock();
      const double wallSeconds = wall.Seconds();
      std::cout << "cells " << m.NumCells() << " sites " << s.NumSites() << " geometry " << geom
                << ": " << wallSeconds << " s wall, "
                << double(c1 - c0) / CLOCKS_PER_SEC << " s CPU (all threads), pieces "
                << r.NumPieces() << ", vertices " << r.NumVertices() << ", faces " << r.NumFaces()
                << ", voronoi vertex records " << r.VoronoiVertexElement.size() << std::endl;
    }
  return 0;
}

/// Element ranges (one block per process in a distributed run): the blocks' pieces, in order,
/// are exactly those of the full run.
void TestElementRange()
{
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
  const av::SimplexMesh m = KuhnGrid(6, 6, 6, lo, hi);
  const av::Embedding e = MakeEmbedding(m, 3, nullptr);
  const av::SiteSet s = RandomSites(m, e, 40, 7);
  const auto full = Rvd(m, e, s);
  const std::int64_t nc = static_cast<std::int64_t>(m.NumCells());
  const std::int64_t cuts[4] = { 0, 300, 301, nc }; // uneven, one single-element block
  std::size_t p = 0;
  double total = 0.0;
  for (int b = 0; b < 3; ++b)
  {
    av::RestrictedVoronoiOptions o;
    o.ElementBegin = cuts[b];
    o.ElementEnd = cuts[b + 1];
    const auto r = Rvd(m, e, s, o);
    AV_CHECK(r.NumPieces() > 0);
    for (std::size_t q = 0; q < r.NumPieces(); ++q, ++p)
    {
      AV_CHECK(r.PieceElement[q] >= cuts[b] && r.PieceElement[q] < cuts[b + 1]);
      if (p < full.NumPieces())
      {
        AV_CHECK(r.PieceElement[q] == full.PieceElement[p] && r.PieceSite[q] == full.PieceSite[p]);
        AV_CHECK(r.PieceMeasure[q] == full.PieceMeasure[p]);
        AV_CHECK(r.PieceVertexOffsets[q + 1] - r.PieceVertexOffsets[q] ==
          full.PieceVertexOffsets[p + 1] - full.PieceVertexOffsets[p]);
      }
      total += r.PieceMeasure[q];
    }
  }
  AV_CHECK(p == full.NumPieces());
  AV_CHECK_NEAR(total, 1.0, 1e-9);
  av::RestrictedVoronoiOptions bad;
  bad.ElementBegin = 5;
  bad.ElementEnd = 4;
  AV_CHECK_THROWS(Rvd(m, e, s, bad));
  bad.ElementBegin = 0;
  bad.ElementEnd = nc + 1;
  AV_CHECK_THROWS(Rvd(m, e, s, bad));
  av::RestrictedVoronoiOptions none; // empty range: no pieces, no error
  none.ElementBegin = none.ElementEnd = 10;
  AV_CHECK(Rvd(m, e, s, none).NumPieces() == 0);
}

} // namespace

int TestRestrictedVoronoi(int argc, char* argv[])
{
  if (argc > 1 && std::strcmp(argv[1], "bench") == 0)
    return Bench();
  TestSquareIdentity();
  TestHeightField();
  TestCube();
  TestFewSites();
  TestDegenerateSites();
  TestElementRange();
  TestBadInput();
  return AV_TEST_RESULT();
}
