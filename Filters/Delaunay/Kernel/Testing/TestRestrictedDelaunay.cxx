// SPDX-License-Identifier: BSD-3-Clause
// Restricted Delaunay mesh: equals the brute-force Delaunay triangulation restricted to the
// domain (identity embedding, 2D and 3D), manifold and never inverted for well-spread sites,
// and rejects a Voronoi diagram computed from other inputs.
#include "RestrictedDelaunay.h"
#include "AnisoTestChecks.h"
#include "VoronoiTestMeshes.h"

#include <algorithm>
#include <array>
#include <iostream>
#include <random>
#include <set>

using namespace av_test;

namespace
{
using Key = std::array<int, 4>;

// Perturbed lattice of n^k sites in the unit square / cube.
av::SiteSet Lattice(const av::SimplexMesh& m, const av::Embedding& e, int n, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  av::SiteSet s;
  s.Dim = e.Dim;
  const int k = m.SimplexDim;
  for (int c = 0; c < (k == 2 ? n * n : n * n * n); ++c)
  {
    const int idx[3] = { c % n, (c / n) % n, c / (n * n) };
    double x[3];
    for (int d = 0; d < k; ++d)
      x[d] = (idx[d] + 0.5 + u(rng)) / n;
    AV_CHECK(SiteAt(s, m, e, x));
  }
  return s;
}

// Brute-force Delaunay simplices whose circumcenter lies strictly inside [0,1]^k.
std::set<Key> BruteRestrictedDelaunay(const av::SiteSet& s, int k)
{
  const int n = static_cast<int>(s.NumSites());
  std::set<Key> out;
  auto p = [&](int i, int d) { return s.At(i)[d]; };
  std::vector<int> idx(k + 1);
  // Enumerate (k+1)-subsets.
  std::function<void(int, int)> rec = [&](int start, int depth) {
    if (depth == k + 1)
    {
      // Circumcenter c: 2 (p_a - p_0) . c = |p_a|^2 - |p_0|^2.
      double A[3][3], b[3];
      for (int a = 0; a < k; ++a)
      {
        b[a] = 0.0;
        for (int d = 0; d < k; ++d)
        {
          A[a][d] = 2.0 * (p(idx[a + 1], d) - p(idx[0], d));
          b[a] += p(idx[a + 1], d) * p(idx[a + 1], d) - p(idx[0], d) * p(idx[0], d);
        }
      }
      double c[3];
      if (std::abs(av_test::SolveCramer(k, A, b, c)) < 1e-14)
        return;
      for (int d = 0; d < k; ++d)
        if (!(c[d] > 0.0 && c[d] < 1.0))
          return;
      double r2 = 0.0;
      for (int d = 0; d < k; ++d)
        r2 += (c[d] - p(idx[0], d)) * (c[d] - p(idx[0], d));
      for (int q = 0; q < n; ++q)
      {
        if (std::find(idx.begin(), idx.end(), q) != idx.end())
          continue;
        double d2 = 0.0;
        for (int d = 0; d < k; ++d)
          d2 += (c[d] - p(q, d)) * (c[d] - p(q, d));
        if (d2 < r2)
          return;
      }
      Key key = { -1, -1, -1, -1 };
      for (int a = 0; a <= k; ++a)
        key[a] = idx[a];
      out.insert(key);
      return;
    }
    for (int i = start; i < n; ++i)
    {
      idx[depth] = i;
      rec(i + 1, depth + 1);
    }
  };
  rec(0, 0);
  return out;
}

std::set<Key> CellSet(const av::RestrictedDelaunayMesh& d)
{
  std::set<Key> out;
  const int nv = d.SimplexDim + 1;
  for (std::size_t c = 0; c < d.NumCells(); ++c)
  {
    Key key = { -1, -1, -1, -1 };
    for (int a = 0; a < nv; ++a)
      key[a] = d.Cells[c * nv + a];
    std::sort(key.begin(), key.begin() + nv);
    out.insert(key);
  }
  return out;
}

// A mesh of well-spread sites on a mild embedding: every site used, nothing inverted, a
// manifold without open interior faces, positive in input space.
void CheckCleanMesh(const av::RestrictedDelaunayMesh& d)
{
  AV_CHECK(d.NumUnusedSites == 0);
  AV_CHECK(d.NumInverted == 0);
  AV_CHECK(d.NumNonManifoldFaces == 0);
  AV_CHECK(d.NumOpenInteriorFaces == 0);
  AV_CHECK(NegativeCells(d) == 0);
}

// The RDT of well-spread sites on an identity embedding: clean, and equal to the brute-force
// restricted Delaunay triangulation, without duplicates.
av::RestrictedDelaunayMesh CheckIdentityCase(
  const av::SimplexMesh& m, const av::Embedding& e, const av::SiteSet& s)
{
  const int k = m.SimplexDim;
  const auto rvd = av::ComputeRestrictedVoronoi(m, e, s);
  const auto d = av::ComputeRestrictedDelaunay(m, e, s, rvd);
  CheckCleanMesh(d);
  const auto brute = BruteRestrictedDelaunay(s, k);
  AV_CHECK_MSG(CellSet(d) == brute, k << "D RDT has " << d.NumCells() << " simplices, brute force "
                                      << brute.size());
  AV_CHECK(d.NumCells() == brute.size()); // no duplicates
  return d;
}

void Test2DIdentity()
{
  const av::SimplexMesh m = TriGrid(17, 17, 0, 0, 1, 1);
  for (int dim : { 2, 8 })
  {
    const av::Embedding e = MakeEmbedding(m, dim, nullptr);
    const av::SiteSet s = Lattice(m, e, 9, 21);
    const av::RestrictedDelaunayMesh d = CheckIdentityCase(m, e, s);
    for (std::size_t s0 = 0; s0 < s.NumSites(); ++s0)
      AV_CHECK(d.Points[2 * s0] == s.At(s0)[0] && d.Points[2 * s0 + 1] == s.At(s0)[1]);
  }
}

void Test3DIdentity()
{
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
  const av::SimplexMesh m = KuhnGrid(9, 9, 9, lo, hi);
  const av::Embedding e = MakeEmbedding(m, 3, nullptr);
  CheckIdentityCase(m, e, Lattice(m, e, 4, 22));
}

void TestSmoothEmbedding()
{
  // Mild 8D height-field-like embedding and well-spread sites: still a clean manifold mesh.
  const av::SimplexMesh m = TriGrid(25, 25, 0, 0, 1, 1);
  const av::Embedding e = MakeEmbedding(m, 8, [](const double* x, int col) {
    return 0.05 * std::sin(2.0 * x[0] + col) * std::cos(1.5 * x[1]);
  });
  const av::SiteSet s = Lattice(m, e, 10, 23);
  const auto rvd = av::ComputeRestrictedVoronoi(m, e, s);
  const auto d = av::ComputeRestrictedDelaunay(m, e, s, rvd);
  std::cout << "smooth 8D: " << d.NumCells() << " triangles, inverted " << d.NumInverted
            << ", non-manifold faces " << d.NumNonManifoldFaces << ", open interior faces "
            << d.NumOpenInteriorFaces << ", unused sites " << d.NumUnusedSites << std::endl;
  AV_CHECK(d.NumInverted == 0);
  AV_CHECK(d.NumNonManifoldFaces == 0);
  AV_CHECK(d.NumOpenInteriorFaces == 0);
  AV_CHECK(d.NumUnusedSites == 0);
  // Inversion detection: mirror the input coordinates (x -> -x) keeping the embedding's
  // orientation; every back-projected triangle must now be flagged.
  av::SimplexMesh mm = m;
  av::Embedding em = e;
  av::SiteSet sm = s;
  for (std::size_t i = 0; i < mm.NumPoints(); ++i)
    mm.Points[2 * i] = -mm.Points[2 * i];
  const auto dm = av::ComputeRestrictedDelaunay(mm, em, sm, rvd);
  AV_CHECK(dm.NumInverted == d.NumCells());
}

void TestBadInput()
{
  const av::SimplexMesh m = TriGrid(6, 6, 0, 0, 1, 1);
  const av::Embedding e = MakeEmbedding(m, 3, SmoothExtra);
  const av::SiteSet s = RandomSites(m, e, 12, 24);
  const auto rvd = av::ComputeRestrictedVoronoi(m, e, s);
  const av::SiteSet s2 = RandomSites(m, e, 13, 25);
  AV_CHECK_THROWS(av::ComputeRestrictedDelaunay(m, e, s2, rvd));
  av::RestrictedVoronoiDiagram bad = rvd;
  bad.VoronoiVertexSites.push_back(0);
  AV_CHECK_THROWS(av::ComputeRestrictedDelaunay(m, e, s, bad));
  av::SiteSet none;
  none.Dim = 3;
  AV_CHECK_THROWS(av::ComputeRestrictedDelaunay(m, e, none, rvd));
}

// Four sites on a square of the boundary face z = 0, one lifted by 1e-9: their circumcenter is
// 5e-10 inside the cube, so the restricted Delaunay mesh has a flat tet there. It must be
// flagged (as inverted: the repair then breaks it up), the lattice's other tets must not.
void TestFlatBoundaryTet()
{
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
  const av::SimplexMesh m = KuhnGrid(6, 6, 6, lo, hi);
  const av::Embedding e = MakeEmbedding(m, 3, nullptr);
  av::SiteSet s;
  s.Dim = 3;
  const double quad[4][3] = { { 0.4, 0.4, 0.0 }, { 0.6, 0.4, 0.0 }, { 0.6, 0.6, 0.0 }, { 0.4, 0.6, 1e-9 } };
  for (const auto& x : quad)
    AV_CHECK(SiteAt(s, m, e, x));
  const double far[4][3] = { { 0.5, 0.5, 0.5 }, { 0.1, 0.1, 0.3 }, { 0.9, 0.2, 0.4 }, { 0.3, 0.9, 0.6 } };
  for (const auto& x : far)
    AV_CHECK(SiteAt(s, m, e, x));
  const av::RestrictedVoronoiDiagram rvd = av::ComputeRestrictedVoronoi(m, e, s);
  const av::RestrictedDelaunayMesh rdt = av::ComputeRestrictedDelaunay(m, e, s, rvd);
  std::size_t flat = 0, flagged = 0;
  for (std::size_t c = 0; c < rdt.NumCells(); ++c)
  {
    std::set<int> ids(rdt.Cells.begin() + 4 * c, rdt.Cells.begin() + 4 * c + 4);
    const bool isQuad = ids == std::set<int>{ 0, 1, 2, 3 };
    flat += isQuad;
    flagged += rdt.Inverted[c];
    if (isQuad)
      AV_CHECK(rdt.Inverted[c] == 1);
  }
  std::cout << "flat boundary tet: " << flat << " of " << rdt.NumCells() << " cells, " << flagged
            << " flagged" << std::endl;
  AV_CHECK(flat == 1);
  AV_CHECK(flagged == 1 && rdt.NumInverted == 1);
}

} // namespace

int TestRestrictedDelaunay(int, char*[])
{
  TestFlatBoundaryTet();
  Test2DIdentity();
  Test3DIdentity();
  TestSmoothEmbedding();
  TestBadInput();
  return AV_TEST_RESULT();
}
