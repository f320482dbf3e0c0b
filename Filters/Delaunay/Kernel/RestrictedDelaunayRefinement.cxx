// SPDX-License-Identifier: BSD-3-Clause
// Repair of the restricted Delaunay mesh by Voronoi-vertex (restricted circumcenter) insertion.
#include "RestrictedDelaunayRefinement.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace av
{

bool ComputeDualVoronoiVertex(const SimplexMesh& mesh, const Embedding& embedding,
  const SiteSet& sites, const std::int32_t* siteIds, std::int32_t element, double bary[4],
  double& radius2, double tolerance)
{
  const int k = mesh.SimplexDim, dim = embedding.Dim;
  if (element < 0 || static_cast<std::size_t>(element) >= mesh.NumCells())
    return false;
  const std::int32_t* cell = mesh.Cell(element);
  // p = v0 + B t; equidistance to s_0 and s_a: 2 (s_a - s_0) . p = |s_a|^2 - |s_0|^2.
  Eigen::Map<const Eigen::VectorXd> v0(embedding.At(cell[0]), dim);
  Eigen::Map<const Eigen::VectorXd> s0(sites.At(siteIds[0]), dim);
  Eigen::MatrixXd B(dim, k);
  for (int a = 0; a < k; ++a)
    B.col(a) = Eigen::Map<const Eigen::VectorXd>(embedding.At(cell[a + 1]), dim) - v0;
  Eigen::MatrixXd A(k, k);
  Eigen::VectorXd rhs(k);
  for (int a = 0; a < k; ++a)
  {
    Eigen::Map<const Eigen::VectorXd> sa(sites.At(siteIds[a + 1]), dim);
    const Eigen::VectorXd n = 2.0 * (sa - s0);
    A.row(a) = n.transpose() * B;
    rhs(a) = sa.squaredNorm() - s0.squaredNorm() - n.dot(v0);
  }
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
  if (!lu.isInvertible())
    return false;
  const Eigen::VectorXd t = lu.solve(rhs);
  double b[4] = { 1.0, 0.0, 0.0, 0.0 };
  for (int a = 0; a < k; ++a)
  {
    b[a + 1] = t(a);
    b[0] -= t(a);
  }
  double sum = 0.0;
  for (int a = 0; a <= k; ++a)
  {
    if (!std::isfinite(b[a]) || b[a] < -tolerance)
      return false;
    b[a] = std::max(0.0, b[a]);
    sum += b[a];
  }
  for (int a = 0; a < 4; ++a)
    bary[a] = a <= k ? b[a] / sum : 0.0;
  Eigen::VectorXd p = Eigen::VectorXd::Zero(dim);
  for (int a = 0; a <= k; ++a)
    p += bary[a] * Eigen::Map<const Eigen::VectorXd>(embedding.At(cell[a]), dim);
  radius2 = (p - s0).squaredNorm();
  return true;
}

std::vector<std::uint8_t> NonManifoldCells(const RestrictedDelaunayMesh& rdt)
{
  const int nv = rdt.SimplexDim + 1;
  const std::size_t nc = rdt.NumCells();
  using Face = std::array<std::int32_t, 4>; // 3 sorted ids, then the cell
  std::vector<Face> faces;
  faces.reserve(nc * nv);
  for (std::size_t c = 0; c < nc; ++c)
    for (int a = 0; a < nv; ++a)
    {
      Face f = { -1, -1, -1, static_cast<std::int32_t>(c) };
      int n = 0;
      for (int b = 0; b < nv; ++b)
        if (b != a)
          f[n++] = rdt.Cells[c * nv + b];
      std::sort(f.begin(), f.begin() + n);
      faces.push_back(f);
    }
  std::sort(faces.begin(), faces.end());
  std::vector<std::uint8_t> bad(nc, 0);
  for (std::size_t i = 0; i < faces.size();)
  {
    std::size_t j = i + 1;
    while (j < faces.size() && std::equal(faces[j].begin(), faces[j].begin() + 3, faces[i].begin()))
      ++j;
    if (j - i > 2)
      for (std::size_t q = i; q < j; ++q)
        bad[faces[q][3]] = 1;
    i = j;
  }
  return bad;
}

namespace
{
void ValidateRepairOptions(const DelaunayRepairOptions& options)
{
  if (options.MaxRounds < 0)
    throw InputError("RepairRestrictedDelaunay: MaxRounds must be >= 0");
  if (options.StallRounds < 1)
    throw InputError("RepairRestrictedDelaunay: StallRounds must be >= 1");
  if (!(options.MinDistanceFraction >= 0.0 && options.MinDistanceFraction < 1.0))
    throw InputError("RepairRestrictedDelaunay: MinDistanceFraction must be in [0, 1)");
  if (options.Voronoi.ElementBegin != 0 || options.Voronoi.ElementEnd >= 0)
    throw InputError("RepairRestrictedDelaunay: the repair needs the whole mesh (leave "
                     "ElementBegin / ElementEnd at their defaults)");
}

/// Throws when the caller's diagram and dual were not computed from `sites` on `mesh`.
void CheckGivenDual(const SimplexMesh& mesh, const SiteSet& sites,
  const RestrictedVoronoiDiagram& voronoi, const RestrictedDelaunayMesh& delaunay)
{
  if (voronoi.NumSites != sites.NumSites() || delaunay.SimplexDim != mesh.SimplexDim ||
    delaunay.AmbientDim != mesh.AmbientDim ||
    delaunay.Points.size() != sites.NumSites() * std::size_t(mesh.AmbientDim) ||
    delaunay.Inverted.size() != delaunay.NumCells() ||
    delaunay.CellElement.size() != delaunay.NumCells())
    throw InputError("RepairRestrictedDelaunay: the given Voronoi diagram / Delaunay mesh "
                     "were not computed from these sites");
}

/// The cells to repair: the inverted ones, and with `nonManifold` those around faces shared
/// by more than two cells.
std::vector<std::uint8_t> BadCells(const RestrictedDelaunayMesh& rdt, bool nonManifold)
{
  std::vector<std::uint8_t> bad = rdt.Inverted;
  if (nonManifold)
  {
    const std::vector<std::uint8_t> nm = NonManifoldCells(rdt);
    for (std::size_t c = 0; c < bad.size(); ++c)
      bad[c] = bad[c] | nm[c];
  }
  return bad;
}

/// The sites one round inserts: embedded positions (Dim each), elements, barycentric
/// coordinates (4 each).
struct Insertions
{
  std::vector<double> Coords;
  std::vector<std::int32_t> Elements;
  std::vector<double> Bary;
};

/// One candidate per bad cell, at its dual Voronoi vertex; candidates closer than
/// MinDistanceFraction of their circumradius to the cell's sites or to an accepted candidate,
/// and cells without a solvable vertex, are skipped (counted in `numSkipped`).
Insertions CollectInsertions(const SimplexMesh& mesh, const Embedding& embedding,
  const SiteSet& sites, const RestrictedDelaunayMesh& rdt, const std::vector<std::uint8_t>& bad,
  double minDistanceFraction, std::size_t& numSkipped)
{
  const int nv = mesh.SimplexDim + 1, dim = embedding.Dim;
  // Candidates in cell order (deterministic); the number of bad cells is small, so the
  // quadratic proximity check against this round's accepted candidates is cheap.
  Insertions accepted;
  Eigen::VectorXd p(dim);
  for (std::size_t c = 0; c < bad.size(); ++c)
  {
    if (!bad[c])
      continue;
    const std::int32_t* ids = rdt.Cells.data() + c * nv;
    const std::int32_t e = rdt.CellElement[c];
    double b[4], r2 = 0.0;
    if (!ComputeDualVoronoiVertex(mesh, embedding, sites, ids, e, b, r2) || !(r2 > 0.0))
    {
      ++numSkipped;
      continue;
    }
    const std::int32_t* cell = mesh.Cell(e);
    p.setZero();
    for (int a = 0; a < nv; ++a)
      p += b[a] * Eigen::Map<const Eigen::VectorXd>(embedding.At(cell[a]), dim);
    const double minD2 = minDistanceFraction * minDistanceFraction * r2;
    bool nearby = false;
    // Guard against round-off: the simplex's own sites are the nearest ones (at r).
    for (int a = 0; a < nv && !nearby; ++a)
      nearby = (p - Eigen::Map<const Eigen::VectorXd>(sites.At(ids[a]), dim)).squaredNorm() < minD2;
    for (std::size_t q = 0; q < accepted.Coords.size() && !nearby; q += dim)
      nearby = (p - Eigen::Map<const Eigen::VectorXd>(accepted.Coords.data() + q, dim))
                 .squaredNorm() < minD2;
    if (nearby)
    {
      ++numSkipped;
      continue;
    }
    accepted.Coords.insert(accepted.Coords.end(), p.data(), p.data() + dim);
    accepted.Elements.push_back(e);
    accepted.Bary.insert(accepted.Bary.end(), b, b + 4);
  }
  return accepted;
}

/// The state with the fewest bad elements so far, saved before each insertion that starts
/// from it (a later round can be worse).
struct BestState
{
  SiteSet Sites;
  RestrictedVoronoiDiagram Voronoi;
  RestrictedDelaunayMesh Delaunay;
  int Rounds = 0;
  std::size_t InsertedRounds = 0;

  void Save(const DelaunayRepairResult& out)
  {
    this->Sites = out.Sites;
    this->Voronoi = out.Voronoi;
    this->Delaunay = out.Delaunay;
    this->Rounds = out.Rounds;
    this->InsertedRounds = out.InsertedPerRound.size();
  }
  /// Puts the saved state back into `out` (the later rounds' sites are dropped).
  void Restore(DelaunayRepairResult& out)
  {
    out.Sites = std::move(this->Sites);
    out.Voronoi = std::move(this->Voronoi);
    out.Delaunay = std::move(this->Delaunay);
    out.Rounds = this->Rounds;
    out.InsertedPerRound.resize(this->InsertedRounds);
  }
};

DelaunayRepairResult Repair(const SimplexMesh& mesh, const Embedding& embedding,
  const SiteSet& sites, RestrictedVoronoiDiagram* voronoi, RestrictedDelaunayMesh* delaunay,
  const DelaunayRepairOptions& options)
{
  ValidateRepairOptions(options);
  DelaunayRepairResult out;
  out.Sites = sites;
  out.NumInputSites = sites.NumSites();
  SiteSet previousSites; // sites of out.Voronoi after an insertion round
  bool havePrevious = false;
  BestState best;
  std::pair<std::size_t, std::size_t> bestBad{ 0, 0 };
  int roundsSinceBest = 0;
  for (int round = 0;; ++round)
  {
    if (round == 0 && voronoi)
    {
      CheckGivenDual(mesh, sites, *voronoi, *delaunay);
      out.Voronoi = std::move(*voronoi);
      out.Delaunay = std::move(*delaunay);
    }
    else if (havePrevious)
    {
      // Only the elements near the inserted sites change: re-clip those (same result as the
      // full computation, bit for bit).
      out.Voronoi = UpdateRestrictedVoronoi(
        mesh, embedding, out.Sites, out.Voronoi, previousSites, options.Voronoi);
      out.Delaunay = ComputeRestrictedDelaunay(mesh, embedding, out.Sites, out.Voronoi);
    }
    else
    {
      out.Voronoi = ComputeRestrictedVoronoi(mesh, embedding, out.Sites, options.Voronoi);
      out.Delaunay = ComputeRestrictedDelaunay(mesh, embedding, out.Sites, out.Voronoi);
    }
    const RestrictedDelaunayMesh& rdt = out.Delaunay;
    if (round == 0)
    {
      out.InitialInverted = rdt.NumInverted;
      out.InitialNonManifoldFaces = rdt.NumNonManifoldFaces;
    }
    // Inverted cells first: non-manifold faces are repaired only once none is left, and a
    // state is better when it has fewer inverted cells, then fewer non-manifold faces. So the
    // non-manifold repair never ends with more inverted cells than the inverted repair alone
    // (on a folded embedding its insertions can invert cells that were fine).
    const std::size_t numNonManifold = options.RepairNonManifold ? rdt.NumNonManifoldFaces : 0;
    const bool nonManifold = rdt.NumInverted == 0 && numNonManifold > 0;
    const std::pair<std::size_t, std::size_t> numBad{ rdt.NumInverted, numNonManifold };
    out.InvertedPerRound.push_back(rdt.NumInverted);
    out.Converged = rdt.NumInverted == 0 && numNonManifold == 0;
    const bool currentIsBest = round == 0 || numBad < bestBad;
    if (currentIsBest)
    {
      bestBad = numBad;
      roundsSinceBest = 0;
    }
    else
    {
      ++roundsSinceBest;
    }
    if (out.Converged || round >= options.MaxRounds || roundsSinceBest >= options.StallRounds)
    {
      if (!currentIsBest)
      {
        best.Restore(out);
        out.Stalled = true;
      }
      break;
    }
    if (currentIsBest)
      best.Save(out);

    const Insertions accepted = CollectInsertions(mesh, embedding, out.Sites, rdt,
      BadCells(rdt, nonManifold), options.MinDistanceFraction, out.NumSkipped);
    if (accepted.Elements.empty())
      break; // every candidate was skipped: no progress possible
    // Appended after the scan: all candidates of a round come from the same site set.
    previousSites = out.Sites;
    havePrevious = true;
    out.Sites.Coords.insert(out.Sites.Coords.end(), accepted.Coords.begin(), accepted.Coords.end());
    out.Sites.CellIds.insert(
      out.Sites.CellIds.end(), accepted.Elements.begin(), accepted.Elements.end());
    out.Sites.Bary.insert(out.Sites.Bary.end(), accepted.Bary.begin(), accepted.Bary.end());
    out.InsertedPerRound.push_back(accepted.Elements.size());
    out.Rounds = round + 1;
  }
  out.NumInserted = out.Sites.NumSites() - out.NumInputSites;
  return out;
}
} // namespace

DelaunayRepairResult RepairRestrictedDelaunay(const SimplexMesh& mesh, const Embedding& embedding,
  const SiteSet& sites, const DelaunayRepairOptions& options)
{
  return Repair(mesh, embedding, sites, nullptr, nullptr, options);
}

DelaunayRepairResult RepairRestrictedDelaunay(const SimplexMesh& mesh, const Embedding& embedding,
  const SiteSet& sites, RestrictedVoronoiDiagram voronoi, RestrictedDelaunayMesh delaunay,
  const DelaunayRepairOptions& options)
{
  return Repair(mesh, embedding, sites, &voronoi, &delaunay, options);
}

} // namespace av
