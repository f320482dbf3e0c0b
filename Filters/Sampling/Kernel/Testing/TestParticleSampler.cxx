// SPDX-License-Identifier: BSD-3-Clause
// Checks the particle sampler on embeddings with known geometry: identity embeddings of the
// unit square / cube (uniform spacing, boundary covered), a linear anisotropic embedding
// (spacing follows the metric), a curved height field; determinism and bad input.
// `TestParticleSampler --bench` times 5000 sites on a 101x21x21 (44,541-vertex) 8D embedding.
#include "ParticleSampler.h"
#include "StructuredMeshes.h"
#include "AnisoTestChecks.h"
#include "VoronoiTestMeshes.h"
#include "SiteSpacing.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace
{
using av_test::CoefficientOfVariation;
using av_test::NearestDistances;

/// Input coords padded with zeros (plus optional linear extra coords a * x) to dim.
av::Embedding PaddedEmbedding(const av::SimplexMesh& mesh, int dim, double extraPerX = 0.0)
{
  av::Embedding e;
  e.Dim = dim;
  e.Coords.assign(mesh.NumPoints() * static_cast<std::size_t>(dim), 0.0);
  for (std::size_t i = 0; i < mesh.NumPoints(); ++i)
  {
    for (int d = 0; d < mesh.AmbientDim; ++d)
      e.Coords[i * dim + d] = mesh.Point(i)[d];
    if (extraPerX != 0.0)
      e.Coords[i * dim + mesh.AmbientDim] = extraPerX * mesh.Point(i)[0];
  }
  return e;
}

/// Sites are on the embedded mesh: valid cell, barycentrics in [0,1] summing to 1, coords
/// equal to the barycentric combination of the embedded vertices.
void CheckOnMesh(const av::SimplexMesh& mesh, const av::Embedding& emb, const av::SiteSet& s)
{
  int bad = 0;
  for (std::size_t i = 0; i < s.NumSites(); ++i)
  {
    const auto c = s.CellIds[i];
    if (c < 0 || static_cast<std::size_t>(c) >= mesh.NumCells())
    {
      ++bad;
      continue;
    }
    double sum = 0.0;
    for (int j = 0; j < 4; ++j)
    {
      const double b = s.Bary[4 * i + j];
      if (b < 0.0 || b > 1.0 || (j > mesh.SimplexDim && b != 0.0))
        ++bad;
      sum += b;
    }
    if (std::abs(sum - 1.0) > 1e-12)
      ++bad;
    for (int d = 0; d < emb.Dim; ++d)
    {
      double x = 0.0;
      for (int j = 0; j <= mesh.SimplexDim; ++j)
        x += s.Bary[4 * i + j] * emb.At(mesh.Cell(c)[j])[d];
      if (std::abs(x - s.At(i)[d]) > 1e-12)
        ++bad;
    }
  }
  AV_CHECK_MSG(bad == 0, bad << " site values are off the mesh");
}

/// Rises in an energy history (each accepted step must lower it).
int Rises(const std::vector<double>& e)
{
  int rises = 0;
  for (std::size_t i = 1; i < e.size(); ++i)
    if (e[i] > e[i - 1])
      ++rises;
  return rises;
}

/// Both stages' histories: sizes, no rises (the shifted, continuous energy is a function of
/// the positions), and the first stage that ran cut its energy by minReduction.
void CheckEnergy(const av::ParticleSamplerResult& r, double minReduction)
{
  AV_CHECK(r.Energy.size() == static_cast<std::size_t>(r.IterationsDone) + 1);
  AV_CHECK(r.WarmupEnergy.size() ==
    (r.WarmupIterationsDone > 0 ? static_cast<std::size_t>(r.WarmupIterationsDone) + 1 : 0));
  AV_CHECK_MSG(Rises(r.Energy) == 0, Rises(r.Energy) << " iterations increased the energy");
  AV_CHECK_MSG(Rises(r.WarmupEnergy) == 0,
    Rises(r.WarmupEnergy) << " warm-up iterations increased the energy");
  const std::vector<double>& first = r.WarmupEnergy.empty() ? r.Energy : r.WarmupEnergy;
  AV_CHECK_MSG(first.back() < (1.0 - minReduction) * first.front(),
    "energy " << first.front() << " -> " << first.back());
}

bool SameBits(const av::ParticleSamplerResult& a, const av::ParticleSamplerResult& b)
{
  return a.Sites.Coords.size() == b.Sites.Coords.size() &&
    std::memcmp(a.Sites.Coords.data(), b.Sites.Coords.data(),
      a.Sites.Coords.size() * sizeof(double)) == 0 &&
    a.Sites.CellIds == b.Sites.CellIds &&
    std::memcmp(a.Sites.Bary.data(), b.Sites.Bary.data(), a.Sites.Bary.size() * sizeof(double)) ==
    0 &&
    a.Energy.size() == b.Energy.size() &&
    std::memcmp(a.Energy.data(), b.Energy.data(), a.Energy.size() * sizeof(double)) == 0;
}

int Bench()
{
  // Cube2-like input: 101 x 21 x 21 Kuhn grid of the unit cube, 240k tets; a smooth 8D
  // embedding stretching x by s(x) = 1 + 24 exp(-((x - 0.5) / 0.05)^2): coordinate 4 is
  // F(x) with F' = sqrt(s^2 - 1) (the exact embedding of that metric), coordinates 5-8 add
  // small smooth bumps.
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
  const av::SimplexMesh mesh = av::MakeKuhnTetGrid(101, 21, 21, lo, hi);
  av::Embedding emb;
  emb.Dim = 8;
  emb.Coords.assign(mesh.NumPoints() * 8, 0.0);
  std::vector<double> big(1001, 0.0);
  for (int i = 1; i <= 1000; ++i)
  {
    const double x = (i - 0.5) / 1000.0;
    const double s = 1.0 + 24.0 * std::exp(-std::pow((x - 0.5) / 0.05, 2));
    big[i] = big[i - 1] + std::sqrt(s * s - 1.0) / 1000.0;
  }
  for (std::size_t i = 0; i < mesh.NumPoints(); ++i)
  {
    const double* p = mesh.Point(i);
    double* e = emb.Coords.data() + 8 * i;
    e[0] = p[0];
    e[1] = p[1];
    e[2] = p[2];
    e[3] = big[static_cast<int>(std::lround(p[0] * 1000.0))];
    e[4] = 0.05 * std::sin(3.0 * p[1] + 2.0 * p[2]);
    e[5] = 0.05 * std::cos(2.0 * p[1] - p[2]);
    e[6] = 0.03 * std::sin(4.0 * p[2]);
    e[7] = 0.02 * std::cos(5.0 * p[0]);
  }
  av::ParticleSamplerOptions opt;
  opt.NumSites = 5000;
  opt.Seed = 3;
  if (const char* t = std::getenv("AV_MAX_THREADS"))
    opt.MaxThreads = std::atoi(t);
  // CPU time too: on a loaded machine wall time says little.
  const std::clock_t c0 = std::clock();
  const auto res = av::SampleParticles(mesh, emb, opt);
  const double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  std::cout << "points " << mesh.NumPoints() << " cells " << mesh.NumCells() << " dim 8 sites "
            << opt.NumSites << "\nembedded volume " << res.EmbeddedMeasure << " sigma "
            << res.Sigma << " iterations " << res.IterationsDone << " mean neighbors "
            << res.MeanNeighbors << " energy evaluations " << res.EnergyEvaluations
            << " list builds " << res.NeighborRebuilds << "\nenergy " << res.Energy.front() << " -> "
            << res.Energy.back() << "\nseconds " << res.Seconds << " (cpu " << cpu
            << " s, threads " << opt.MaxThreads << ")" << std::endl;
  CheckOnMesh(mesh, emb, res.Sites);
  CheckEnergy(res, 0.3);
  return AV_TEST_RESULT();
}

/// The square's start-only options: no iterations, i.i.d. initial sites.
av::ParticleSamplerOptions StartOnly(const av::ParticleSamplerOptions& opt)
{
  av::ParticleSamplerOptions opt0 = opt;
  opt0.Iterations = 0;
  opt0.WarmupIterations = 0;
  opt0.StratifiedInitialSites = false;
  return opt0;
}

/// Square: the warm-up and the stratified start, and the spacing against a random start.
void CheckSquareSchedule(const av::SimplexMesh& mesh, const av::Embedding& emb,
  const av::ParticleSamplerOptions& opt, const av::ParticleSamplerResult& res)
{
  const auto nn = NearestDistances(res.Sites, 2);
  const double cv = CoefficientOfVariation(nn);
  const av::ParticleSamplerOptions opt0 = StartOnly(opt);
  const double cv0 =
    CoefficientOfVariation(NearestDistances(av::SampleParticles(mesh, emb, opt0).Sites, 2));

  // Without the warm-up the paper's kernel alone still halves the energy.
  av::ParticleSamplerOptions paper = opt;
  paper.WarmupIterations = 0;
  const auto rp = av::SampleParticles(mesh, emb, paper);
  AV_CHECK(rp.WarmupEnergy.empty() && rp.WarmupIterationsDone == 0);
  CheckEnergy(rp, 0.5);
  CheckOnMesh(mesh, emb, rp.Sites);
  // The warm-up uses the narrower kernel: its first energy is the initial sites' energy at
  // sigma factor 0.25 (the same initial sites as a 0.25 run without iterations).
  av::ParticleSamplerOptions narrow = opt0;
  narrow.StratifiedInitialSites = true;
  narrow.KernelWidthFactor = 0.25;
  const auto rn = av::SampleParticles(mesh, emb, narrow);
  AV_CHECK_NEAR(res.WarmupEnergy.front(), rn.Energy.front(), 1e-9 * rn.Energy.front());
  AV_CHECK(res.WarmupIterationsDone >= 10 && res.IterationsDone > 0);

  // Stratified initial sites: counts in 4 x 4 blocks stay close to the expected 300 / 16;
  // i.i.d. draws fluctuate by about sqrt(19) ~ 4.3 per block.
  av::ParticleSamplerOptions strat = opt0;
  strat.StratifiedInitialSites = true;
  auto worstBlock = [&](const av::SiteSet& sites)
  {
    int count[16] = {};
    for (std::size_t i = 0; i < sites.NumSites(); ++i)
      ++count[std::min(3, static_cast<int>(sites.At(i)[0] * 4)) * 4 +
        std::min(3, static_cast<int>(sites.At(i)[1] * 4))];
    double worst = 0.0;
    for (int c : count)
      worst = std::max(worst, std::abs(c - 300.0 / 16.0));
    return worst;
  };
  const double worstStrat = worstBlock(av::SampleParticles(mesh, emb, strat).Sites);
  const double worstRandom = worstBlock(av::SampleParticles(mesh, emb, opt0).Sites);
  std::cout << "square: worst 4x4 block count deviation stratified " << worstStrat
            << ", random " << worstRandom << std::endl;
  AV_CHECK_MSG(worstStrat <= 2.5, "stratified block deviation " << worstStrat);
  AV_CHECK(worstRandom > worstStrat);
  std::cout << "square: energy " << res.Energy.front() << " -> " << res.Energy.back()
            << " in " << res.IterationsDone << " it, NN CV " << cv0 << " -> " << cv
            << ", neighbors " << res.MeanNeighbors << ", " << res.Seconds << " s"
            << std::endl;
  AV_CHECK_MSG(cv < 0.10, "nearest-neighbor CV " << cv);
  AV_CHECK(cv0 > 0.3);
}

/// Square: the best-candidate start is far better spaced than a random (or stratified) one.
void CheckSquareBestCandidate(
  const av::SimplexMesh& mesh, const av::Embedding& emb, const av::ParticleSamplerOptions& opt)
{
  const av::ParticleSamplerOptions opt0 = StartOnly(opt);
  av::ParticleSamplerOptions strat = opt0;
  strat.StratifiedInitialSites = true;
  const double h0 = std::sqrt(1.0 / 300.0);
  // Best-candidate start: far better spaced than a random (or stratified) one; its sites
  // are on the mesh and the same for a seed. Random starts of 300 sites have a smallest
  // pair distance of a few hundredths of the spacing.
  av::ParticleSamplerOptions bc = opt0;
  bc.InitialCandidates = 20;
  const auto rb = av::SampleParticles(mesh, emb, bc);
  CheckOnMesh(mesh, emb, rb.Sites);
  const auto nnb = NearestDistances(rb.Sites, 8);
  const auto nnr = NearestDistances(av::SampleParticles(mesh, emb, strat).Sites, 8);
  const double minB = *std::min_element(nnb.begin(), nnb.end());
  const double minR = *std::min_element(nnr.begin(), nnr.end());
  std::cout << "square: best-candidate start min NN / spacing " << minB / h0
            << ", NN CV " << CoefficientOfVariation(nnb) << "; stratified start "
            << minR / h0 << ", NN CV " << CoefficientOfVariation(nnr) << std::endl;
  AV_CHECK_MSG(minB > 0.5 * h0 && minB > 4.0 * minR, "min NN " << minB << " vs " << minR);
  AV_CHECK(CoefficientOfVariation(nnb) < 0.5 * CoefficientOfVariation(nnr));
  AV_CHECK(SameBits(rb, av::SampleParticles(mesh, emb, bc)));
  bc.InitialCandidates = 0;
  AV_CHECK_THROWS(av::SampleParticles(mesh, emb, bc));
}

/// Square: the boundary is covered (every side has sites within half a spacing), no big holes.
void CheckSquareCoverage(const av::ParticleSamplerResult& res)
{
  const double h = std::sqrt(1.0 / 300.0);
  double nearSide[4] = { 1, 1, 1, 1 };
  for (std::size_t i = 0; i < res.Sites.NumSites(); ++i)
  {
    const double* x = res.Sites.At(i);
    nearSide[0] = std::min(nearSide[0], x[0]);
    nearSide[1] = std::min(nearSide[1], 1 - x[0]);
    nearSide[2] = std::min(nearSide[2], x[1]);
    nearSide[3] = std::min(nearSide[3], 1 - x[1]);
  }
  for (double d : nearSide)
    AV_CHECK_MSG(d < 0.5 * h, "side distance " << d << " spacing " << h);
  double hole = 0.0;
  for (int a = 0; a <= 50; ++a)
    for (int b = 0; b <= 50; ++b)
    {
      double best = 1e9;
      for (std::size_t i = 0; i < res.Sites.NumSites(); ++i)
        best = std::min(best, std::hypot(res.Sites.At(i)[0] - a / 50.0,
                                res.Sites.At(i)[1] - b / 50.0));
      hole = std::max(hole, best);
    }
  std::cout << "square: largest empty disc radius / spacing " << hole / h << std::endl;
  AV_CHECK_MSG(hole < 0.9 * h, "hole " << hole / h << " spacings");
}

/// Square: same seed (any thread count) -> same bits; other seed -> other sites; abort from
/// the progress callback.
void CheckSquareDeterminismAndAbort(const av::SimplexMesh& mesh, const av::Embedding& emb,
  const av::ParticleSamplerOptions& opt, const av::ParticleSamplerResult& res)
{
  av::ParticleSamplerOptions one = opt;
  one.MaxThreads = 1;
  AV_CHECK(SameBits(res, av::SampleParticles(mesh, emb, one)));
  AV_CHECK(SameBits(res, av::SampleParticles(mesh, emb, opt)));
  av::ParticleSamplerOptions other = opt;
  other.Seed = 12;
  AV_CHECK(!SameBits(res, av::SampleParticles(mesh, emb, other)));

  // Abort from the progress callback.
  av::ParticleSamplerOptions ab = opt;
  int calls = 0;
  ab.Progress = [&](double f)
  {
    ++calls;
    return f < 0.1;
  };
  const auto ra = av::SampleParticles(mesh, emb, ab);
  // Warm-up + iterations: the callback stops the warm-up after a tenth of them.
  const int tenth = (ab.WarmupIterations + ab.Iterations + 9) / 10;
  AV_CHECK(ab.WarmupIterations > tenth);
  AV_CHECK(ra.Aborted && ra.WarmupIterationsDone == tenth && ra.IterationsDone == 0 &&
    ra.Energy.size() == 1 && calls >= tenth + 1);
  CheckOnMesh(mesh, emb, ra.Sites);
}

/// Unit square, identity embedding padded to 8D.
void CheckSquare()
{
  const double lo[2] = { 0, 0 }, hi[2] = { 1, 1 };
  const av::SimplexMesh mesh = av::MakeTriangleGrid(21, 21, lo, hi);
  const av::Embedding emb = PaddedEmbedding(mesh, 8);
  av::ParticleSamplerOptions opt;
  opt.NumSites = 300;
  opt.Seed = 11;
  const auto res = av::SampleParticles(mesh, emb, opt);
  AV_CHECK_NEAR(res.EmbeddedMeasure, 1.0, 1e-12);
  AV_CHECK_NEAR(res.Sigma, 0.3 * std::sqrt(1.0 / 300.0), 1e-12);
  AV_CHECK(res.Sites.NumSites() == 300 && res.Sites.Dim == 8);
  CheckOnMesh(mesh, emb, res.Sites);
  CheckEnergy(res, 0.5);
  // Extra coordinates stay zero: particles never leave the (flat) embedded surface.
  double off = 0.0;
  for (std::size_t i = 0; i < res.Sites.NumSites(); ++i)
    for (int d = 2; d < 8; ++d)
      off = std::max(off, std::abs(res.Sites.At(i)[d]));
  AV_CHECK(off == 0.0);
  CheckSquareSchedule(mesh, emb, opt, res);
  CheckSquareBestCandidate(mesh, emb, opt);
  CheckSquareCoverage(res);
  CheckSquareDeterminismAndAbort(mesh, emb, opt, res);
}

/// Cube: sharp features (on by default): the 8 corner sites never move, the feature-line
/// sites end on the cube's edges, evenly spread (every edge has some), and the rest are free.
void CheckCubeFeatures(const av::SimplexMesh& mesh, const av::Embedding& emb,
  const av::ParticleSamplerOptions& opt, const av::ParticleSamplerResult& res)
{
  AV_CHECK(res.NumCornerSites == 8 && res.FeatureWarning.empty());
  AV_CHECK(res.NumFeatureLineSites >= 12);
  std::size_t corners = 0, lines = 0;
  std::vector<int> perEdge(12, 0);
  for (std::size_t i = 0; i < res.Sites.NumSites(); ++i)
  {
    const double* x = res.Sites.At(i);
    int atBound = 0, freeAxis = -1;
    for (int d = 0; d < 3; ++d)
    {
      const bool b = std::abs(x[d]) < 1e-12 || std::abs(x[d] - 1.0) < 1e-12;
      atBound += b ? 1 : 0;
      freeAxis = b ? freeAxis : d;
    }
    if (res.FeatureKind[i] == 2)
    {
      ++corners;
      AV_CHECK(atBound == 3);
    }
    else if (res.FeatureKind[i] == 1)
    {
      ++lines;
      AV_CHECK_MSG(atBound >= 2, "feature-line site " << i << " left its edge");
      if (atBound == 2)
      {
        const int a = (freeAxis + 1) % 3, b = (freeAxis + 2) % 3;
        ++perEdge[static_cast<std::size_t>(4 * freeAxis + 2 * (x[a] > 0.5) + (x[b] > 0.5))];
      }
      AV_CHECK(res.FeatureEdge[i] >= 0);
    }
    for (int d = 3; d < 7; ++d)
      AV_CHECK(x[d] == 0.0);
  }
  AV_CHECK(corners == 8 && lines == res.NumFeatureLineSites);
  for (int c : perEdge)
    AV_CHECK(c >= 1);
  // Features off: no corner or line sites, and the output changes.
  av::ParticleSamplerOptions plain = opt;
  plain.PreserveSharpFeatures = false;
  const auto rp = av::SampleParticles(mesh, emb, plain);
  AV_CHECK(rp.NumCornerSites == 0 && rp.NumFeatureLineSites == 0);
  AV_CHECK(std::all_of(rp.FeatureKind.begin(), rp.FeatureKind.end(), [](std::int8_t k) { return k == 0; }));
  AV_CHECK(!SameBits(res, rp));
  // Too few sites: the features are cut back to the corners (8 <= 20 / 2), then dropped.
  av::ParticleSamplerOptions few = opt;
  few.NumSites = 20;
  const auto rf = av::SampleParticles(mesh, emb, few);
  AV_CHECK(!rf.FeatureWarning.empty() && rf.NumCornerSites == 8 && rf.NumFeatureLineSites == 0);
  few.NumSites = 12;
  const auto rn = av::SampleParticles(mesh, emb, few);
  AV_CHECK(!rn.FeatureWarning.empty() && rn.NumCornerSites == 0 && rn.NumFeatureLineSites == 0);
  // Bad feature options.
  av::ParticleSamplerOptions bad = opt;
  bad.FeatureAngle = 0.0;
  AV_CHECK_THROWS(av::SampleParticles(mesh, emb, bad));
  bad.FeatureAngle = std::nan("");
  AV_CHECK_THROWS(av::SampleParticles(mesh, emb, bad));
  bad = opt;
  bad.FeatureSpacingFactor = -1.0;
  AV_CHECK_THROWS(av::SampleParticles(mesh, emb, bad));
}

/// Unit cube (Kuhn tets), identity embedding in 7D (runtime-dimension code path).
void CheckCube()
{
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
  const av::SimplexMesh mesh = av::MakeKuhnTetGrid(9, 9, 9, lo, hi);
  const av::Embedding emb = PaddedEmbedding(mesh, 7);
  av::ParticleSamplerOptions opt;
  opt.NumSites = 400;
  opt.Seed = 5;
  const auto res = av::SampleParticles(mesh, emb, opt);
  AV_CHECK_NEAR(res.EmbeddedMeasure, 1.0, 1e-12);
  CheckOnMesh(mesh, emb, res.Sites);
  CheckEnergy(res, 0.5);
  const double cv = CoefficientOfVariation(NearestDistances(res.Sites, 3));
  std::cout << "cube: energy " << res.Energy.front() << " -> " << res.Energy.back() << " in "
            << res.IterationsDone << " it, NN CV " << cv << ", neighbors "
            << res.MeanNeighbors << ", " << res.Seconds << " s" << std::endl;
  AV_CHECK_MSG(cv < 0.15, "nearest-neighbor CV " << cv);
  CheckCubeFeatures(mesh, emb, opt, res);
  const double h = std::cbrt(1.0 / 400.0);
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side)
    {
      double best = 1.0;
      for (std::size_t i = 0; i < res.Sites.NumSites(); ++i)
        best = std::min(best, std::abs(res.Sites.At(i)[axis] - side));
      AV_CHECK_MSG(best < 0.5 * h, "face " << axis << side << " distance " << best);
    }
}

/// A closed box surface (the cube's boundary triangles): its 12 edges are creases. Corner
/// sites stay at the 8 corners, crease sites on the creases (the triangle walk along lines).
void CheckBoxSurface()
{
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
  const av::SimplexMesh box = av_test::BoundaryTriangles(av::MakeKuhnTetGrid(7, 7, 7, lo, hi));
  const av::Embedding emb = PaddedEmbedding(box, 5);
  av::ParticleSamplerOptions opt;
  opt.NumSites = 300;
  const auto res = av::SampleParticles(box, emb, opt);
  CheckOnMesh(box, emb, res.Sites);
  AV_CHECK(res.NumCornerSites == 8 && res.NumFeatureLineSites >= 24);
  std::size_t onCrease = 0;
  for (std::size_t i = 0; i < res.Sites.NumSites(); ++i)
  {
    int atBound = 0;
    for (int d = 0; d < 3; ++d)
    {
      const double x = res.Sites.At(i)[d];
      atBound += (std::abs(x) < 1e-12 || std::abs(x - 1.0) < 1e-12) ? 1 : 0;
    }
    if (res.FeatureKind[i] == 2)
      AV_CHECK(atBound == 3);
    if (res.FeatureKind[i] == 1)
    {
      AV_CHECK_MSG(atBound >= 2, "crease site " << i << " left its crease");
      ++onCrease;
    }
  }
  AV_CHECK(onCrease == res.NumFeatureLineSites);
  const double cv = CoefficientOfVariation(NearestDistances(res.Sites, 3));
  std::cout << "box surface: " << res.NumCornerSites << " corner + " << res.NumFeatureLineSites
            << " crease sites, NN CV " << cv << std::endl;
  AV_CHECK_MSG(cv < 0.15, "nearest-neighbor CV " << cv);
}

/// Linear anisotropic embedding (x, y, a x): metric diag(1 + a^2, 1) = diag(s^2, 1).
/// Uniform in the embedding -> in input space the spacing along x is 1/s of that along y.
void CheckAnisotropic()
{
  const double s = 3.0;
  const double lo[2] = { 0, 0 }, hi[2] = { 1, 1 };
  const av::SimplexMesh mesh = av::MakeTriangleGrid(31, 11, lo, hi);
  const av::Embedding emb = PaddedEmbedding(mesh, 3, std::sqrt(s * s - 1));
  av::ParticleSamplerOptions opt;
  opt.NumSites = 300;
  const auto res = av::SampleParticles(mesh, emb, opt);
  AV_CHECK_NEAR(res.EmbeddedMeasure, s, 1e-12);
  CheckOnMesh(mesh, emb, res.Sites);
  CheckEnergy(res, 0.5);
  const double cvEmb = CoefficientOfVariation(NearestDistances(res.Sites, 3));
  AV_CHECK_MSG(cvEmb < 0.12, "embedded NN CV " << cvEmb);
  // Second moments of the input-space offsets to each site's 6 nearest neighbors in the
  // embedding: isotropic there (a hexagonal neighborhood has isotropic second moments
  // whatever its orientation), so sum dy^2 / sum dx^2 = s^2 in input space.
  double sx = 0.0, sy = 0.0;
  const std::size_t ns = res.Sites.NumSites();
  std::vector<std::pair<double, std::size_t>> byDistance(ns);
  for (std::size_t p = 0; p < ns; ++p)
  {
    for (std::size_t q = 0; q < ns; ++q)
    {
      double d2 = 0.0;
      for (int d = 0; d < 3; ++d)
        d2 += std::pow(res.Sites.At(p)[d] - res.Sites.At(q)[d], 2);
      byDistance[q] = { q == p ? 1e300 : d2, q };
    }
    std::partial_sort(byDistance.begin(), byDistance.begin() + 6, byDistance.end());
    for (int k = 0; k < 6; ++k)
    {
      const std::size_t q = byDistance[static_cast<std::size_t>(k)].second;
      sx += std::pow(res.Sites.At(p)[0] - res.Sites.At(q)[0], 2);
      sy += std::pow(res.Sites.At(p)[1] - res.Sites.At(q)[1], 2);
    }
  }
  const double ratio = std::sqrt(sy / sx);
  std::cout << "aniso: embedded NN CV " << cvEmb << ", rms |dy| / rms |dx| of 6 NN " << ratio
            << " (isotropic in embedding -> s = " << s << ")" << std::endl;
  AV_CHECK_MSG(ratio > 0.85 * s && ratio < 1.15 * s, "ratio " << ratio);
}

/// Curved height field z = 0.3 sin(2 pi x) sin(pi y): sites stay on the surface.
void CheckHeightField()
{
  const double lo[2] = { 0, 0 }, hi[2] = { 1, 1 };
  const av::SimplexMesh mesh = av::MakeTriangleGrid(31, 31, lo, hi);
  av::Embedding emb = PaddedEmbedding(mesh, 3);
  for (std::size_t i = 0; i < mesh.NumPoints(); ++i)
    emb.Coords[3 * i + 2] = 0.3 * std::sin(2 * M_PI * mesh.Point(i)[0]) *
      std::sin(M_PI * mesh.Point(i)[1]);
  av::ParticleSamplerOptions opt;
  opt.NumSites = 400;
  const auto res = av::SampleParticles(mesh, emb, opt);
  AV_CHECK(res.EmbeddedMeasure > 1.1);
  CheckOnMesh(mesh, emb, res.Sites);
  CheckEnergy(res, 0.5);
  const double cv = CoefficientOfVariation(NearestDistances(res.Sites, 3));
  std::cout << "height field: area " << res.EmbeddedMeasure << ", NN CV " << cv << std::endl;
  AV_CHECK_MSG(cv < 0.12, "embedded NN CV " << cv);
}

void CheckBadInput()
{
  const double lo[2] = { 0, 0 }, hi[2] = { 1, 1 };
  const av::SimplexMesh mesh = av::MakeTriangleGrid(5, 5, lo, hi);
  const av::Embedding emb = PaddedEmbedding(mesh, 4);
  av::ParticleSamplerOptions opt;
  opt.NumSites = 0;
  AV_CHECK_THROWS(av::SampleParticles(mesh, emb, opt));
  opt.NumSites = 8 * 25 + 1;
  AV_CHECK_THROWS(av::SampleParticles(mesh, emb, opt));
  opt.NumSites = 10;
  av::Embedding e2 = emb;
  e2.Coords.pop_back();
  AV_CHECK_THROWS(av::SampleParticles(mesh, e2, opt));
  e2 = emb;
  e2.Coords[7] = std::numeric_limits<double>::quiet_NaN();
  AV_CHECK_THROWS(av::SampleParticles(mesh, e2, opt));
  AV_CHECK_THROWS(av::SampleParticles(mesh, PaddedEmbedding(mesh, 21), opt));
  av::SimplexMesh m2 = mesh;
  m2.Cells[4] = 99;
  AV_CHECK_THROWS(av::SampleParticles(m2, emb, opt));
  e2 = emb;
  std::fill(e2.Coords.begin(), e2.Coords.end(), 0.0);
  AV_CHECK_THROWS(av::SampleParticles(mesh, e2, opt));
  opt.KernelWidthFactor = -1;
  AV_CHECK_THROWS(av::SampleParticles(mesh, emb, opt));
  opt.KernelWidthFactor = 0.3;
  opt.NumSites = 1; // one site: nothing to repel, still valid
  const auto r1 = av::SampleParticles(mesh, emb, opt);
  AV_CHECK(r1.Sites.NumSites() == 1 && r1.Energy.front() == 0.0);
}
} // namespace

int TestParticleSampler(int argc, char* argv[])
{
  if (argc > 1 && std::string(argv[1]) == "--bench")
    return Bench();
  CheckSquare();
  CheckCube();
  CheckBoxSurface();
  CheckAnisotropic();
  CheckHeightField();
  CheckBadInput();
  return AV_TEST_RESULT();
}
