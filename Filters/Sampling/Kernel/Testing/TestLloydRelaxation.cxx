// SPDX-License-Identifier: BSD-3-Clause
// Checks the Lloyd (CVT) relaxation: exact energy / centroids on the identity-embedded unit
// square and cube, monotone energy and sites on the mesh for random starts (flat and curved
// embedding), the nearest-neighbor spread dropping, and bad input.
#include "LloydRelaxation.h"
#include "ParticleSampler.h"
#include "StructuredMeshes.h"
#include "AnisoTestChecks.h"
#include "SiteSpacing.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <vector>

namespace
{
/// Input coords padded with zeros to dim, plus height h(x, y) in the last coordinate.
av::Embedding Embed(const av::SimplexMesh& mesh, int dim, bool curved)
{
  av::Embedding e;
  e.Dim = dim;
  e.Coords.assign(mesh.NumPoints() * static_cast<std::size_t>(dim), 0.0);
  for (std::size_t i = 0; i < mesh.NumPoints(); ++i)
  {
    const double* p = mesh.Point(i);
    for (int d = 0; d < mesh.AmbientDim; ++d)
      e.Coords[i * dim + d] = p[d];
    if (curved)
      e.Coords[i * dim + dim - 1] = 0.3 * std::sin(3.0 * p[0]) * std::cos(2.0 * p[1]);
  }
  return e;
}

/// Sites at given input points of an identity-embedded grid (located by brute force).
av::SiteSet SitesAt(const av::SimplexMesh& mesh, const av::Embedding& emb,
  const std::vector<std::vector<double>>& pts)
{
  av::SiteSet s;
  s.Dim = emb.Dim;
  const int K = mesh.SimplexDim;
  for (const auto& x : pts)
  {
    for (std::size_t c = 0; c < mesh.NumCells(); ++c)
    {
      const std::int32_t* v = mesh.Cell(c);
      Eigen::Matrix3d e = Eigen::Matrix3d::Identity();
      Eigen::Vector3d r = Eigen::Vector3d::Zero();
      for (int j = 0; j < K; ++j)
        for (int d = 0; d < K; ++d)
          e(d, j) = mesh.Point(v[j + 1])[d] - mesh.Point(v[0])[d];
      for (int d = 0; d < K; ++d)
        r(d) = x[d] - mesh.Point(v[0])[d];
      const Eigen::Vector3d l = e.fullPivLu().solve(r);
      double l0 = 1.0 - l.head(K).sum();
      if (l0 < -1e-12 || (l.head(K).array() < -1e-12).any())
        continue;
      double b[4] = { l0, l(0), l(1), K == 3 ? l(2) : 0.0 };
      s.CellIds.push_back(static_cast<std::int32_t>(c));
      for (int i = 0; i < 4; ++i)
        s.Bary.push_back(b[i]);
      for (int d = 0; d < emb.Dim; ++d)
      {
        double y = 0.0;
        for (int i = 0; i <= K; ++i)
          y += b[i] * emb.At(v[i])[d];
        s.Coords.push_back(y);
      }
      break;
    }
  }
  return s;
}

double NearestNeighborCV(const av::SiteSet& s)
{
  return av_test::CoefficientOfVariation(av_test::NearestDistances(s, s.Dim));
}

/// Every site: valid cell, barycentrics >= 0 summing to 1, coords = their combination.
bool OnMesh(const av::SimplexMesh& mesh, const av::Embedding& emb, const av::SiteSet& s)
{
  const int V = mesh.SimplexDim + 1;
  for (std::size_t i = 0; i < s.NumSites(); ++i)
  {
    const std::int32_t* v = mesh.Cell(static_cast<std::size_t>(s.CellIds[i]));
    double sum = 0.0;
    for (int j = 0; j < V; ++j)
    {
      if (s.Bary[i * 4 + j] < -1e-12)
        return false;
      sum += s.Bary[i * 4 + j];
    }
    if (std::abs(sum - 1.0) > 1e-12)
      return false;
    for (int d = 0; d < s.Dim; ++d)
    {
      double y = 0.0;
      for (int j = 0; j < V; ++j)
        y += s.Bary[i * 4 + j] * emb.At(v[j])[d];
      if (std::abs(y - s.At(i)[d]) > 1e-10)
        return false;
    }
  }
  return true;
}

bool Monotone(const std::vector<double>& e, double final)
{
  std::vector<double> all = e;
  all.push_back(final);
  for (std::size_t i = 1; i < all.size(); ++i)
    if (all[i] > all[i - 1] * (1.0 + 1e-12))
      return false;
  return true;
}
} // namespace

int TestLloydRelaxation(int, char*[])
{
  const double lo2[2] = { 0, 0 }, hi2[2] = { 1, 1 };
  const double lo3[3] = { 0, 0, 0 }, hi3[3] = { 1, 1, 1 };
  const av::SimplexMesh square = av::MakeTriangleGrid(9, 9, lo2, hi2);
  const av::SimplexMesh cube = av::MakeKuhnTetGrid(5, 5, 5, lo3, hi3);

  // Exact values: one site, int |x - s|^2 over the unit square / cube.
  {
    const av::Embedding e = Embed(square, 3, false);
    AV_CHECK_NEAR(av::ComputeCVTEnergy(square, e, SitesAt(square, e, { { 0.5, 0.5 } })),
      1.0 / 6.0, 1e-12);
    AV_CHECK_NEAR(av::ComputeCVTEnergy(square, e, SitesAt(square, e, { { 0.0, 0.0 } })),
      2.0 / 3.0, 1e-12);
    const av::Embedding e3 = Embed(cube, 5, false);
    AV_CHECK_NEAR(av::ComputeCVTEnergy(cube, e3, SitesAt(cube, e3, { { 0.5, 0.5, 0.5 } })),
      0.25, 1e-12);
    AV_CHECK_NEAR(av::ComputeCVTEnergy(cube, e3, SitesAt(cube, e3, { { 0.1, 0.2, 0.3 } })),
      0.25 + 0.16 + 0.09 + 0.04, 1e-12);
  }
  // Exact centroids: two sites split the domain at x = 0.4, one step moves them to the
  // centroids of [0, 0.4] and [0.4, 1].
  {
    const av::Embedding e = Embed(square, 4, false);
    const av::LloydResult r =
      av::RelaxSitesLloyd(square, e, SitesAt(square, e, { { 0.3, 0.5 }, { 0.5, 0.5 } }), 1);
    AV_CHECK_NEAR(r.Sites.At(0)[0], 0.2, 1e-12);
    AV_CHECK_NEAR(r.Sites.At(1)[0], 0.7, 1e-12);
    AV_CHECK_NEAR(r.Sites.At(0)[1], 0.5, 1e-12);
    const av::Embedding e3 = Embed(cube, 3, false);
    const av::LloydResult r3 = av::RelaxSitesLloyd(
      cube, e3, SitesAt(cube, e3, { { 0.5, 0.45, 0.5 }, { 0.5, 0.75, 0.5 } }), 1);
    AV_CHECK_NEAR(r3.Sites.At(0)[1], 0.3, 1e-12);
    AV_CHECK_NEAR(r3.Sites.At(1)[1], 0.8, 1e-12);
    AV_CHECK_NEAR(r3.Sites.At(1)[0], 0.5, 1e-12);
    AV_CHECK_NEAR(r3.Sites.At(1)[2], 0.5, 1e-12);
  }
  // Boundary sites: held with keepBoundarySites, pulled inwards without.
  {
    const av::Embedding e = Embed(square, 3, false);
    const av::SiteSet s0 = SitesAt(square, e, { { 0.0, 0.5 }, { 0.6, 0.5 } });
    const av::LloydResult kept = av::RelaxSitesLloyd(square, e, s0, 2, true);
    AV_CHECK(kept.FixedBoundarySites == 1);
    AV_CHECK_NEAR(kept.Sites.At(0)[0], 0.0, 1e-15);
    AV_CHECK_NEAR(kept.Sites.At(1)[0], 0.6625, 1e-12); // [0.3, 1] -> 0.65, [0.325, 1]
    const av::LloydResult freed = av::RelaxSitesLloyd(square, e, s0, 1, false);
    AV_CHECK(freed.FixedBoundarySites == 0);
    AV_CHECK_NEAR(freed.Sites.At(0)[0], 0.15, 1e-12);
  }
  // Random starts: energy decreases monotonically, sites stay on the mesh, NN CV drops.
  for (int curved = 0; curved < 2; ++curved)
  {
    for (int vol = 0; vol < 2; ++vol)
    {
      const av::SimplexMesh& mesh = vol ? cube : square;
      const av::Embedding e = Embed(mesh, vol ? 5 : 4, curved != 0);
      av::ParticleSamplerOptions so;
      so.NumSites = vol ? 60 : 50;
      so.Iterations = 0; // random sites
      so.WarmupIterations = 0;
      so.StratifiedInitialSites = false;
      so.Seed = 7;
      const av::SiteSet start = av::SampleParticles(mesh, e, so).Sites;
      const av::LloydResult r = av::RelaxSitesLloyd(mesh, e, start, 15);
      const double final = av::ComputeCVTEnergy(mesh, e, r.Sites);
      const double cv0 = NearestNeighborCV(start), cv = NearestNeighborCV(r.Sites);
      std::cout << (vol ? "cube" : "square") << (curved ? " curved" : " flat") << ": energy "
                << r.Energy.front() << " -> " << final << ", NN CV " << cv0 << " -> " << cv
                << ", mean move " << r.MeanMove.front() << " -> " << r.MeanMove.back()
                << std::endl;
      AV_CHECK_MSG(Monotone(r.Energy, final), "CVT energy increased");
      AV_CHECK(final < 0.7 * r.Energy.front());
      AV_CHECK(OnMesh(mesh, e, r.Sites));
      AV_CHECK_MSG(cv < 0.6 * cv0, "NN CV " << cv0 << " -> " << cv);
      AV_CHECK(r.MeanMove.back() < r.MeanMove.front());
    }
  }
  // Bad input.
  {
    const av::Embedding e = Embed(square, 3, false);
    av::SiteSet s = SitesAt(square, e, { { 0.5, 0.5 } });
    AV_CHECK_THROWS(av::RelaxSitesLloyd(square, e, s, -1));
    s.Coords[0] += 0.1; // off its cell
    AV_CHECK_THROWS(av::RelaxSitesLloyd(square, e, s, 1));
    AV_CHECK(av::RelaxSitesLloyd(square, e, SitesAt(square, e, { { 0.5, 0.5 } }), 0)
               .Sites.Coords == SitesAt(square, e, { { 0.5, 0.5 } }).Coords);
  }
  return AV_TEST_RESULT();
}
