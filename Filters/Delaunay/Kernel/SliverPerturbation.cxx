// SPDX-License-Identifier: BSD-3-Clause
// Sliver perturbation of restricted Delaunay sites in the embedding.
#include "SliverPerturbation.h"

#include "RestrictedVoronoi.h"
#include "SiteWalk.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <string>

namespace av
{
namespace
{
using VecX = Eigen::VectorXd;
} // namespace

double MinDihedralAngle(const double* p0, const double* p1, const double* p2, const double* p3, int dim)
{
  const double* p[4] = { p0, p1, p2, p3 };
  double best = 180.0;
  VecX e(dim), u(dim), w(dim);
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
    {
      int k = -1, l = -1;
      for (int q = 0; q < 4; ++q)
        if (q != i && q != j)
          (k < 0 ? k : l) = q;
      for (int a = 0; a < dim; ++a)
      {
        e[a] = p[j][a] - p[i][a];
        u[a] = p[k][a] - p[i][a];
        w[a] = p[l][a] - p[i][a];
      }
      const double ee = e.squaredNorm();
      if (!(ee > 0.0))
        return 0.0;
      u -= (u.dot(e) / ee) * e;
      w -= (w.dot(e) / ee) * e;
      const double nu = u.norm(), nw = w.norm();
      if (!(nu > 0.0) || !(nw > 0.0))
        return 0.0;
      const double cosv = std::max(-1.0, std::min(1.0, u.dot(w) / (nu * nw)));
      best = std::min(best, std::acos(cosv) * 180.0 / 3.14159265358979323846);
    }
  return best;
}

SliverPerturbationResult PerturbSliverSites(const SimplexMesh& mesh, const Embedding& embedding,
  const SiteSet& sites, const RestrictedDelaunayMesh& rdt, const SliverPerturbationOptions& options)
{
  auto fail = [](const std::string& m) { throw InputError("PerturbSliverSites: " + m); };
  ValidateSiteMoveInput("PerturbSliverSites", mesh, embedding, sites, rdt);
  const std::size_t ns = sites.NumSites();
  const int dim = embedding.Dim;
  if (!(options.StepFraction >= 0.0) || !std::isfinite(options.StepFraction) ||
    !(options.MinDihedralDegrees >= 0.0) || !(options.MinDihedralDegrees <= 90.0))
    fail("StepFraction must be finite and >= 0, MinDihedralDegrees in [0, 90]");

  if (options.FixedSites && options.FixedSites->size() != ns)
    fail("FixedSites must have one entry per site");
  SliverPerturbationResult r;
  r.Sites = sites;
  if (mesh.SimplexDim != 3 || rdt.SimplexDim != 3)
    return r;
  const std::size_t ncell = rdt.Cells.size() / 4;
  r.MinDihedral.resize(ncell);
  std::vector<VecX> move(ns);
  Eigen::MatrixXd P(4, dim);
  for (std::size_t c = 0; c < ncell; ++c)
  {
    const std::int32_t* id = rdt.Cells.data() + 4 * c;
    const double ang = MinDihedralAngle(sites.At(id[0]), sites.At(id[1]), sites.At(id[2]), sites.At(id[3]), dim);
    r.MinDihedral[c] = ang;
    if (!(ang < options.MinDihedralDegrees))
      continue;
    ++r.NumSlivers;
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < dim; ++k)
        P(i, k) = sites.At(id[i])[k];
    const Eigen::RowVectorXd mean = P.colwise().mean();
    P.rowwise() -= mean;
    double h = 0.0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        h += (P.row(i) - P.row(j)).norm() / 6.0;
    // Normal of the best-fit plane: third principal direction of the centered points.
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(P.transpose() * P);
    const VecX n = eig.eigenvectors().col(dim - 3);
    for (int i = 0; i < 4; ++i)
    {
      const double side = P.row(i).dot(n) >= 0.0 ? 1.0 : -1.0;
      if (move[id[i]].size() == 0)
        move[id[i]] = VecX::Zero(dim);
      move[id[i]] += side * options.StepFraction * h * n;
    }
  }
  if (r.NumSlivers == 0 || options.StepFraction == 0.0)
    return r;
  std::vector<std::int32_t> ownAdjacency;
  if (!options.ElementAdjacency)
    ownAdjacency = ComputeElementAdjacency(mesh);
  else if (options.ElementAdjacency->size() != mesh.NumCells() * 4)
    fail("ElementAdjacency does not match the mesh (pass ComputeElementAdjacency of this mesh)");
  const std::vector<std::int32_t>& adj = options.ElementAdjacency ? *options.ElementAdjacency : ownAdjacency;
  for (std::size_t s = 0; s < ns; ++s)
    if (move[s].size() > 0 && move[s].squaredNorm() > 0.0 &&
      !(options.FixedSites && (*options.FixedSites)[s]))
    {
      WalkSiteOnMesh(mesh, embedding, adj, r.Sites, s, move[s].data());
      ++r.NumMovedSites;
    }
  return r;
}

} // namespace av
