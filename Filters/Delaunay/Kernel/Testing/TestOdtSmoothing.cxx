// SPDX-License-Identifier: BSD-3-Clause
// Tests of SmoothSitesOdt: one ODT step regularizes the restricted Delaunay mesh of random
// sites, moves each free site exactly to the measure-weighted mean of its star's
// circumcenters, keeps boundary sites and the caller's fixed sites and stays on the mesh; bad
// input throws.
#include "OdtSmoothing.h"
#include "RestrictedDelaunayRefinement.h"
#include "StructuredMeshes.h"
#include "AnisoTestChecks.h"
#include "VoronoiTestMeshes.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace
{
// Identity embedding of a mesh, padded with zero columns up to dim.
av::Embedding Identity(const av::SimplexMesh& m, int dim)
{
  return av_test::MakeEmbedding(m, dim, nullptr);
}

// Mean quality of a simplex mesh with site coordinates in R^dim: mean ratio for tets
// 12 (9 V^2)^(1/3) / sum l^2, 4 sqrt3 A / sum l^2 for triangles (1 = regular).
double MeanQuality(const av::RestrictedDelaunayMesh& rdt, const av::SiteSet& s)
{
  const int k = rdt.SimplexDim, nv = k + 1;
  double total = 0.0;
  const std::size_t n = rdt.NumCells();
  for (std::size_t c = 0; c < n; ++c)
  {
    const std::int32_t* id = rdt.Cells.data() + nv * c;
    Eigen::MatrixXd E(s.Dim, k);
    for (int j = 0; j < k; ++j)
      for (int d = 0; d < s.Dim; ++d)
        E(d, j) = s.At(id[j + 1])[d] - s.At(id[0])[d];
    const double g = std::sqrt(std::max(0.0, (E.transpose() * E).determinant()));
    double l2 = 0.0;
    for (int a = 0; a < nv; ++a)
      for (int b = a + 1; b < nv; ++b)
        for (int d = 0; d < s.Dim; ++d)
          l2 += std::pow(s.At(id[a])[d] - s.At(id[b])[d], 2);
    total += k == 3 ? 12.0 * std::cbrt(9.0 * std::pow(g / 6.0, 2)) / l2 : 4.0 * std::sqrt(3.0) * (g / 2.0) / l2;
  }
  return total / static_cast<double>(n);
}

// Reference targets: measure-weighted mean of circumcenters, computed independently
// (circumcenter as the point of the simplex's hull equidistant from its vertices, by a
// least-squares solve of the bisector equations): the sums acc (dim per site) and weights w.
void ReferenceOdtSums(const av::RestrictedDelaunayMesh& rdt, const av::SiteSet& sites, int dim,
  std::vector<double>& acc, std::vector<double>& w)
{
  const int k = rdt.SimplexDim, nv = k + 1;
  acc.assign(sites.NumSites() * dim, 0.0);
  w.assign(sites.NumSites(), 0.0);
  for (std::size_t c = 0; c < rdt.NumCells(); ++c)
  {
    const std::int32_t* id = rdt.Cells.data() + nv * c;
    Eigen::MatrixXd E(dim, k);
    Eigen::VectorXd rhs(k);
    for (int j = 0; j < k; ++j)
    {
      for (int d = 0; d < dim; ++d)
        E(d, j) = sites.At(id[j + 1])[d] - sites.At(id[0])[d];
      rhs[j] = 0.5 * E.col(j).squaredNorm();
    }
    // c = p0 + E l with (c - p0).e_j = |e_j|^2 / 2 for every edge e_j from p0.
    const Eigen::VectorXd l = (E.transpose() * E).colPivHouseholderQr().solve(rhs);
    const double vol = std::sqrt((E.transpose() * E).determinant());
    for (int a = 0; a < nv; ++a)
    {
      w[id[a]] += vol;
      for (int d = 0; d < dim; ++d)
        acc[id[a] * dim + d] += vol * (sites.At(id[0])[d] + (E * l)[d]);
    }
  }
}

// Checks one ODT step on `mesh` with random sites: quality up, exact ODT targets, boundary
// sites kept, sites on the mesh.
void CheckOdt(const av::SimplexMesh& mesh, int dim, std::size_t numSites)
{
  const av::Embedding emb = Identity(mesh, dim);
  const av::SiteSet sites = av_test::RandomSites(mesh, emb, static_cast<int>(numSites), 7);
  const av::RestrictedVoronoiOptions vo = av::DelaunayRepairOptions().Voronoi;
  const av::RestrictedVoronoiDiagram rvd = av::ComputeRestrictedVoronoi(mesh, emb, sites, vo);
  const av::RestrictedDelaunayMesh rdt = av::ComputeRestrictedDelaunay(mesh, emb, sites, rvd);
  const double before = MeanQuality(rdt, sites);

  av::OdtSmoothingOptions o;
  const av::OdtSmoothingResult r = av::SmoothSitesOdt(mesh, emb, sites, rvd, rdt, o);
  AV_CHECK(r.Sites.NumSites() == sites.NumSites());
  AV_CHECK(r.NumMovedSites > numSites / 4);
  AV_CHECK(r.NumFixedSites > 0);

  std::vector<double> acc, w;
  ReferenceOdtSums(rdt, sites, dim, acc, w);
  std::vector<char> bnd(sites.NumSites(), 0);
  for (std::int32_t id : rvd.BoundaryDualFaces)
    bnd[id] = 1;
  std::size_t exact = 0, kept = 0;
  bool ok = true;
  for (std::size_t s = 0; s < sites.NumSites(); ++s)
  {
    bool same = true;
    for (int d = 0; d < dim; ++d)
      same = same && r.Sites.At(s)[d] == sites.At(s)[d];
    if (bnd[s] || w[s] == 0.0)
    {
      kept += same;
      continue;
    }
    // A free site ends at its target unless the walk stopped on the domain boundary.
    bool onBoundary = false;
    for (int d = 0; d < mesh.AmbientDim; ++d)
      onBoundary = onBoundary || r.Sites.At(s)[d] <= 1e-12 || r.Sites.At(s)[d] >= 1.0 - 1e-12;
    if (onBoundary)
      continue;
    for (int d = 0; d < dim; ++d)
      ok = ok && std::abs(r.Sites.At(s)[d] - acc[s * dim + d] / w[s]) < 1e-9;
    ++exact;
  }
  AV_CHECK(ok);
  AV_CHECK(exact > numSites / 4);
  std::size_t numBnd = 0;
  for (std::size_t s = 0; s < sites.NumSites(); ++s)
    numBnd += bnd[s] || w[s] == 0.0;
  AV_CHECK(kept == numBnd);

  // Sites stay on the mesh: valid barycentrics whose combination is the coordinates.
  av::ValidateRestrictedVoronoiInput(mesh, emb, r.Sites);

  // The step regularizes the mesh of the moved sites.
  const av::RestrictedVoronoiDiagram rvd2 = av::ComputeRestrictedVoronoi(mesh, emb, r.Sites, vo);
  const av::RestrictedDelaunayMesh rdt2 = av::ComputeRestrictedDelaunay(mesh, emb, r.Sites, rvd2);
  const double after = MeanQuality(rdt2, r.Sites);
  AV_CHECK(after > before + 0.03);

  // FixedSites: every other site that moved is flagged; those keep their exact values, the
  // unflagged ones move as before (the steps do not depend on each other within one step).
  std::vector<std::uint8_t> flags(sites.NumSites(), 0);
  std::size_t flagged = 0;
  for (std::size_t s = 0; s < sites.NumSites(); s += 2)
  {
    const bool moved = r.Sites.CellIds[s] != sites.CellIds[s] ||
      !std::equal(r.Sites.At(s), r.Sites.At(s) + dim, sites.At(s));
    flags[s] = moved ? 1 : 0;
    flagged += moved;
  }
  AV_CHECK(flagged > numSites / 10);
  av::OdtSmoothingOptions keep = o;
  keep.FixedSites = &flags;
  const av::OdtSmoothingResult k = av::SmoothSitesOdt(mesh, emb, sites, rvd, rdt, keep);
  bool flaggedKept = true, same = true;
  for (std::size_t s = 0; s < sites.NumSites(); ++s)
  {
    const av::SiteSet& expect = flags[s] ? sites : r.Sites;
    flaggedKept =
      flaggedKept && (!flags[s] || std::equal(k.Sites.At(s), k.Sites.At(s) + dim, expect.At(s)));
    same = same && (flags[s] || std::equal(k.Sites.At(s), k.Sites.At(s) + dim, expect.At(s)));
  }
  AV_CHECK(flaggedKept);
  AV_CHECK(same);
  AV_CHECK(k.NumMovedSites + flagged == r.NumMovedSites);
  AV_CHECK(k.NumFixedSites == r.NumFixedSites + flagged);
  std::vector<std::uint8_t> short_(sites.NumSites() - 1, 0);
  keep.FixedSites = &short_;
  AV_CHECK_THROWS(av::SmoothSitesOdt(mesh, emb, sites, rvd, rdt, keep));

  // StepFraction 0 moves nothing.
  o.StepFraction = 0.0;
  const av::OdtSmoothingResult z = av::SmoothSitesOdt(mesh, emb, sites, rvd, rdt, o);
  AV_CHECK(z.Sites.Coords == sites.Coords && z.Sites.CellIds == sites.CellIds);
}
} // namespace

int TestOdtSmoothing(int, char*[])
{
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
  const av::SimplexMesh tets = av::MakeKuhnTetGrid(9, 9, 9, lo, hi);
  CheckOdt(tets, 3, 600);
  CheckOdt(tets, 5, 600); // padded embedding: same geometry in R^5
  const av::SimplexMesh tris = av::MakeTriangleGrid(21, 21, lo, hi);
  CheckOdt(tris, 2, 400);

  // Bad input.
  {
    const av::Embedding emb = Identity(tets, 3);
    const av::SiteSet sites = av_test::RandomSites(tets, emb, 50, 3);
    const av::RestrictedVoronoiDiagram rvd = av::ComputeRestrictedVoronoi(tets, emb, sites);
    av::RestrictedDelaunayMesh rdt = av::ComputeRestrictedDelaunay(tets, emb, sites, rvd);
    av::OdtSmoothingOptions o;
    o.StepFraction = -1.0;
    AV_CHECK_THROWS(av::SmoothSitesOdt(tets, emb, sites, rvd, rdt, o));
    o.StepFraction = std::nan("");
    AV_CHECK_THROWS(av::SmoothSitesOdt(tets, emb, sites, rvd, rdt, o));
    av::RestrictedDelaunayMesh wrong = rdt;
    wrong.Cells[0] = 1000;
    AV_CHECK_THROWS(av::SmoothSitesOdt(tets, emb, sites, rvd, wrong));
    // A shared adjacency gives the same result; one of the wrong size is refused.
    const std::vector<std::int32_t> adjacency = av::ComputeElementAdjacency(tets);
    av::OdtSmoothingOptions shared;
    shared.ElementAdjacency = &adjacency;
    const av::OdtSmoothingResult own = av::SmoothSitesOdt(tets, emb, sites, rvd, rdt);
    const av::OdtSmoothingResult withShared = av::SmoothSitesOdt(tets, emb, sites, rvd, rdt, shared);
    AV_CHECK(own.Sites.Coords == withShared.Sites.Coords && own.Sites.CellIds == withShared.Sites.CellIds);
    const std::vector<std::int32_t> tooShort(adjacency.begin(), adjacency.end() - 4);
    shared.ElementAdjacency = &tooShort;
    AV_CHECK_THROWS(av::SmoothSitesOdt(tets, emb, sites, rvd, rdt, shared));
    av::RestrictedVoronoiOptions vo;
    vo.ElementAdjacency = &tooShort;
    AV_CHECK_THROWS(av::ComputeRestrictedVoronoi(tets, emb, sites, vo));
    vo.ElementAdjacency = &adjacency;
    AV_CHECK(av::ComputeRestrictedVoronoi(tets, emb, sites, vo).PieceMeasure == rvd.PieceMeasure);
    av::SiteSet badCell = sites;
    badCell.CellIds[0] = static_cast<std::int32_t>(tets.NumCells());
    AV_CHECK_THROWS(av::SmoothSitesOdt(tets, emb, badCell, rvd, rdt));
    av::SiteSet shortSites = sites;
    shortSites.Coords.pop_back();
    AV_CHECK_THROWS(av::SmoothSitesOdt(tets, emb, shortSites, rvd, rdt));
  }
  return AV_TEST_RESULT();
}
