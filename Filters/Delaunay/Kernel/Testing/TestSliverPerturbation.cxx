// SPDX-License-Identifier: BSD-3-Clause
// Tests of PerturbSliverSites / MinDihedralAngle: a sliver's sites move apart along its flat
// direction (the tet gets fatter), moved sites stay on the mesh, other sites are untouched.
#include "SliverPerturbation.h"
#include "StructuredMeshes.h"
#include "AnisoTestChecks.h"

#include <cmath>

namespace
{
// Identity embedding of a 3D mesh, padded with zero columns up to dim.
av::Embedding Identity(const av::SimplexMesh& m, int dim)
{
  av::Embedding e;
  e.Dim = dim;
  e.Coords.assign(m.NumPoints() * dim, 0.0);
  for (std::size_t i = 0; i < m.NumPoints(); ++i)
    for (int d = 0; d < 3; ++d)
      e.Coords[i * dim + d] = m.Point(i)[d];
  return e;
}

// Locates x (input space) in the mesh by brute force and appends it as a site.
void AddSite(const av::SimplexMesh& m, const av::Embedding& e, av::SiteSet& s, const double x[3])
{
  for (std::size_t c = 0; c < m.NumCells(); ++c)
  {
    const std::int32_t* v = m.Cell(c);
    double a[3][3], r[3];
    for (int i = 0; i < 3; ++i)
    {
      for (int j = 0; j < 3; ++j)
        a[i][j] = m.Point(v[j + 1])[i] - m.Point(v[0])[i];
      r[i] = x[i] - m.Point(v[0])[i];
    }
    const double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
      a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    double l[3];
    for (int k = 0; k < 3; ++k)
    {
      double b[3][3];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          b[i][j] = j == k ? r[i] : a[i][j];
      l[k] = (b[0][0] * (b[1][1] * b[2][2] - b[1][2] * b[2][1]) -
               b[0][1] * (b[1][0] * b[2][2] - b[1][2] * b[2][0]) +
               b[0][2] * (b[1][0] * b[2][1] - b[1][1] * b[2][0])) / det;
    }
    const double l0 = 1.0 - l[0] - l[1] - l[2];
    if (l0 < -1e-12 || l[0] < -1e-12 || l[1] < -1e-12 || l[2] < -1e-12)
      continue;
    s.CellIds.push_back(static_cast<std::int32_t>(c));
    const double bary[4] = { l0, l[0], l[1], l[2] };
    for (int a2 = 0; a2 < 4; ++a2)
      s.Bary.push_back(bary[a2]);
    for (int d = 0; d < e.Dim; ++d)
    {
      double y = 0.0;
      for (int a2 = 0; a2 < 4; ++a2)
        y += bary[a2] * e.At(v[a2])[d];
      s.Coords.push_back(y);
    }
    return;
  }
}

// Every site lies in its cell: valid barycentrics, coordinates = their combination.
bool OnMesh(const av::SimplexMesh& m, const av::Embedding& e, const av::SiteSet& s)
{
  for (std::size_t i = 0; i < s.NumSites(); ++i)
  {
    const std::int32_t* v = m.Cell(s.CellIds[i]);
    double sum = 0.0;
    for (int a = 0; a < 4; ++a)
    {
      if (s.Bary[4 * i + a] < 0.0)
        return false;
      sum += s.Bary[4 * i + a];
    }
    if (std::abs(sum - 1.0) > 1e-12)
      return false;
    for (int d = 0; d < e.Dim; ++d)
    {
      double y = 0.0;
      for (int a = 0; a < 4; ++a)
        y += s.Bary[4 * i + a] * e.At(v[a])[d];
      if (std::abs(y - s.Coords[i * e.Dim + d]) > 1e-12)
        return false;
    }
  }
  return true;
}
// MinDihedralAngle: regular tet 70.53 deg in any dimension; a flat quad-like tet ~ 0.
void TestMinDihedralAngle()
{
  const double r[4][5] = { { 1, 1, 1, 0, 0 }, { 1, -1, -1, 0, 0 }, { -1, 1, -1, 0, 0 }, { -1, -1, 1, 0, 0 } };
  AV_CHECK_NEAR(av::MinDihedralAngle(r[0], r[1], r[2], r[3], 5), std::acos(1.0 / 3.0) * 180.0 / M_PI, 1e-9);
  const double f[4][3] = { { 0, 0, 0 }, { 1, 1, 0 }, { 1, 0, 1e-3 }, { 0, 1, 1e-3 } };
  AV_CHECK(av::MinDihedralAngle(f[0], f[1], f[2], f[3], 3) < 0.5);
}

// A sliver: two crossing diagonals 2 * 0.01 apart in z, and a fat tet elsewhere.
const double SliverPoints[8][3] = { { 0.4, 0.4, 0.49 }, { 0.6, 0.6, 0.49 }, { 0.4, 0.6, 0.51 },
  { 0.6, 0.4, 0.51 }, { 0.1, 0.1, 0.1 }, { 0.3, 0.1, 0.1 }, { 0.1, 0.3, 0.1 }, { 0.1, 0.1, 0.3 } };

// The sliver and the fat tet as sites on a unit-cube mesh with a 5D identity embedding.
struct SliverCase
{
  av::SimplexMesh Mesh;
  av::Embedding Emb;
  av::SiteSet Sites;
  av::RestrictedDelaunayMesh Rdt;
};

SliverCase MakeSliverCase()
{
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
  SliverCase c;
  c.Mesh = av::MakeKuhnTetGrid(11, 11, 11, lo, hi);
  c.Emb = Identity(c.Mesh, 5);
  c.Sites.Dim = c.Emb.Dim;
  for (const auto& p : SliverPoints)
    AddSite(c.Mesh, c.Emb, c.Sites, p);
  AV_CHECK(c.Sites.NumSites() == 8);
  c.Rdt.SimplexDim = 3;
  c.Rdt.Cells = { 0, 1, 2, 3, 4, 5, 6, 7 };
  return c;
}

// The sliver's diagonals move apart, the tet gets fatter, the fat tet's sites stay.
void TestPush(const SliverCase& sc)
{
  const av::SiteSet& sites = sc.Sites;
  const double before = av::MinDihedralAngle(sites.At(0), sites.At(1), sites.At(2), sites.At(3), 5);
  AV_CHECK(before < 15.0);
  av::SliverPerturbationOptions o;
  o.StepFraction = 0.1;
  const av::SliverPerturbationResult r = av::PerturbSliverSites(sc.Mesh, sc.Emb, sites, sc.Rdt, o);
  AV_CHECK(r.NumSlivers == 1);
  AV_CHECK(r.NumMovedSites == 4);
  AV_CHECK(r.MinDihedral.size() == 2);
  AV_CHECK_NEAR(r.MinDihedral[0], before, 1e-12);
  AV_CHECK(r.MinDihedral[1] > 15.0);
  AV_CHECK(OnMesh(sc.Mesh, sc.Emb, r.Sites));
  // The diagonals moved apart along z by StepFraction * mean edge length each (interior, so
  // the identity embedding moves them exactly), x and y unchanged.
  const auto& pts = SliverPoints;
  double h = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
    {
      double d2 = 0.0;
      for (int d = 0; d < 3; ++d)
        d2 += (pts[i][d] - pts[j][d]) * (pts[i][d] - pts[j][d]);
      h += std::sqrt(d2) / 6.0;
    }
  for (int i = 0; i < 4; ++i)
  {
    const double dz = r.Sites.At(i)[2] - pts[i][2];
    AV_CHECK_NEAR(std::abs(dz), o.StepFraction * h, 1e-9);
    AV_CHECK((dz > 0) == (pts[i][2] > 0.5));
    AV_CHECK_NEAR(r.Sites.At(i)[0], pts[i][0], 1e-9);
    AV_CHECK_NEAR(r.Sites.At(i)[1], pts[i][1], 1e-9);
  }
  const double after = av::MinDihedralAngle(r.Sites.At(0), r.Sites.At(1), r.Sites.At(2), r.Sites.At(3), 5);
  AV_CHECK(after > 3.0 * before);
  // The fat tet's sites are bit-identical.
  for (int i = 4; i < 8; ++i)
  {
    AV_CHECK(r.Sites.CellIds[i] == sites.CellIds[i]);
    for (int d = 0; d < 5; ++d)
      AV_CHECK(r.Sites.At(i)[d] == sites.At(i)[d]);
  }
}

// A long step crosses many cells and stops at the domain boundary (z = 0 / z = 1).
void TestLongStep(const SliverCase& sc)
{
  av::SliverPerturbationOptions o;
  o.StepFraction = 5.0;
  const av::SliverPerturbationResult f = av::PerturbSliverSites(sc.Mesh, sc.Emb, sc.Sites, sc.Rdt, o);
  AV_CHECK(OnMesh(sc.Mesh, sc.Emb, f.Sites));
  for (int i = 0; i < 4; ++i)
    AV_CHECK_NEAR(f.Sites.At(i)[2], SliverPoints[i][2] > 0.5 ? 1.0 : 0.0, 1e-9);
  // Deterministic.
  const av::SliverPerturbationResult g = av::PerturbSliverSites(sc.Mesh, sc.Emb, sc.Sites, sc.Rdt, o);
  AV_CHECK(g.Sites.Coords == f.Sites.Coords && g.Sites.CellIds == f.Sites.CellIds);
}

// Fixed sites (e.g. corner / feature-line sites) keep their exact values; the others move.
void TestFixedSites(const SliverCase& sc)
{
  const av::SiteSet& sites = sc.Sites;
  av::SliverPerturbationOptions fo;
  fo.StepFraction = 0.1;
  const std::vector<std::uint8_t> fixed = { 1, 0, 0, 1, 0, 0, 0, 0 };
  fo.FixedSites = &fixed;
  const av::SliverPerturbationResult k = av::PerturbSliverSites(sc.Mesh, sc.Emb, sites, sc.Rdt, fo);
  AV_CHECK(k.NumSlivers == 1 && k.NumMovedSites == 2);
  for (int i = 0; i < 4; ++i)
  {
    const bool same = k.Sites.At(i)[2] == sites.At(i)[2] && k.Sites.CellIds[i] == sites.CellIds[i];
    AV_CHECK(same == (fixed[static_cast<std::size_t>(i)] != 0));
  }
  const std::vector<std::uint8_t> shortFlags = { 1, 0 };
  fo.FixedSites = &shortFlags;
  AV_CHECK_THROWS(av::PerturbSliverSites(sc.Mesh, sc.Emb, sites, sc.Rdt, fo));
}

// Threshold 0: nothing is a sliver, nothing moves; and bad input.
void TestThresholdAndBadInput(const SliverCase& sc)
{
  const av::SimplexMesh& mesh = sc.Mesh;
  const av::Embedding& emb = sc.Emb;
  const av::SiteSet& sites = sc.Sites;
  {
    av::SliverPerturbationOptions z;
    z.MinDihedralDegrees = 0.0;
    const av::SliverPerturbationResult n = av::PerturbSliverSites(mesh, emb, sites, sc.Rdt, z);
    AV_CHECK(n.NumSlivers == 0 && n.NumMovedSites == 0 && n.Sites.Coords == sites.Coords);
  }
  av::RestrictedDelaunayMesh bad = sc.Rdt;
  bad.Cells[0] = 99;
  AV_CHECK_THROWS(av::PerturbSliverSites(mesh, emb, sites, bad));
  av::SliverPerturbationOptions neg;
  neg.StepFraction = -1.0;
  AV_CHECK_THROWS(av::PerturbSliverSites(mesh, emb, sites, sc.Rdt, neg));
  av::SiteSet wrong = sites;
  wrong.Coords.pop_back();
  AV_CHECK_THROWS(av::PerturbSliverSites(mesh, emb, wrong, sc.Rdt));
}
} // namespace

int TestSliverPerturbation(int, char*[])
{
  TestMinDihedralAngle();
  const SliverCase sc = MakeSliverCase();
  TestPush(sc);
  TestLongStep(sc);
  TestFixedSites(sc);
  TestThresholdAndBadInput(sc);
  return AV_TEST_RESULT();
}
