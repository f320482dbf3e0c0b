// SPDX-License-Identifier: BSD-3-Clause
// SampleParticles: input checks, sharp-feature sites, the initial sites and the optimization
// (ParticleOptimizer) in a thread arena of the requested size.
#include "ParticleSampler.h"

#include "FeatureSites.h"
#include "InitialSites.h"
#include "MeshTopology.h"
#include "ParticleOptimizer.h"
#include "SamplerDimensions.h"
#include "SharpFeatures.h"
#include "Stopwatch.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>
#include <string>

namespace av
{
namespace
{

void CheckInputs(const SimplexMesh& mesh, const Embedding& emb)
{
  if (mesh.SimplexDim != 2 && mesh.SimplexDim != 3)
    throw InputError("SampleParticles: only triangles (SimplexDim 2) and tetrahedra (3)");
  if (mesh.AmbientDim < 2 || mesh.AmbientDim > 3)
    throw InputError("SampleParticles: AmbientDim must be 2 or 3");
  if (mesh.Points.size() % static_cast<std::size_t>(mesh.AmbientDim) != 0 ||
    mesh.Cells.size() % static_cast<std::size_t>(mesh.SimplexDim + 1) != 0)
    throw InputError("SampleParticles: Points/Cells array sizes are not multiples of the "
                     "dimension");
  if (mesh.NumCells() == 0)
    throw InputError("SampleParticles: the mesh has no cells");
  const int lo = std::max(mesh.AmbientDim, mesh.SimplexDim);
  const int hi = sampling::kMaxDim;
  if (emb.Dim < lo || emb.Dim > hi)
    throw InputError("SampleParticles: embedding dimension " + std::to_string(emb.Dim) +
      " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  if (emb.Coords.size() != mesh.NumPoints() * static_cast<std::size_t>(emb.Dim))
    throw InputError("SampleParticles: the embedding has " + std::to_string(emb.Coords.size()) +
      " values, expected NumPoints (" + std::to_string(mesh.NumPoints()) + ") x Dim (" +
      std::to_string(emb.Dim) + ")");
  for (double x : emb.Coords)
    if (!std::isfinite(x))
      throw InputError("SampleParticles: the embedding contains NaN or Inf");
  const auto np = static_cast<std::int64_t>(mesh.NumPoints());
  for (auto id : mesh.Cells)
    if (id < 0 || id >= np)
      throw InputError("SampleParticles: cell refers to point id " + std::to_string(id) +
        " outside [0, " + std::to_string(np) + ")");
}

void CheckOptions(const SimplexMesh& mesh, const ParticleSamplerOptions& opt)
{
  if (opt.NumSites == 0)
    throw InputError("SampleParticles: NumSites must be at least 1");
  if (opt.NumSites > 8 * mesh.NumPoints())
    throw InputError("SampleParticles: NumSites (" + std::to_string(opt.NumSites) +
      ") exceeds 8 x the number of mesh points (" + std::to_string(8 * mesh.NumPoints()) +
      "); refine the input mesh or ask for fewer sites");
  if (opt.Iterations < 0 || opt.WarmupIterations < 0 || !(opt.KernelWidthFactor > 0.0) ||
    !std::isfinite(opt.KernelWidthFactor) || !(opt.WarmupKernelWidthFactor > 0.0) ||
    !std::isfinite(opt.WarmupKernelWidthFactor) || !(opt.NeighborCutoff > 0.0) ||
    !std::isfinite(opt.NeighborCutoff) || opt.History < 1 || opt.MaxThreads < 0 ||
    opt.InitialCandidates < 1 || !std::isfinite(opt.FeatureAngle) || !(opt.FeatureAngle > 0.0) ||
    !std::isfinite(opt.FeatureSpacingFactor) || opt.FeatureSpacingFactor < 0.0)
    throw InputError("SampleParticles: Iterations >= 0, WarmupIterations >= 0, History >= 1, "
                     "InitialCandidates >= 1, MaxThreads >= 0, FeatureAngle > 0, "
                     "FeatureSpacingFactor >= 0 and a positive, finite "
                     "KernelWidthFactor, "
                     "WarmupKernelWidthFactor and NeighborCutoff are required");
  if (opt.Features &&
    (opt.Features->IsCorner.size() != mesh.NumPoints() ||
      opt.Features->PointEdgeOffsets.size() != mesh.NumPoints() + 1))
    throw InputError("SampleParticles: the given Features are not of this mesh");
}

/// Removes the sites at exactly the position of a lower-id site (see NumCoincidentRemoved),
/// keeping the order of the others and their feature records.
void RemoveCoincidentSites(ParticleSamplerResult& res)
{
  SiteSet& s = res.Sites;
  const std::size_t n = s.NumSites();
  const auto dim = static_cast<std::size_t>(s.Dim);
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t(0));
  auto less = [&](std::size_t a, std::size_t b) {
    const double* pa = s.At(a);
    const double* pb = s.At(b);
    for (std::size_t d = 0; d < dim; ++d)
      if (pa[d] != pb[d])
        return pa[d] < pb[d];
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<char> drop(n, 0);
  std::size_t removed = 0;
  for (std::size_t t = 1; t < n; ++t)
    if (std::equal(s.At(order[t]), s.At(order[t]) + dim, s.At(order[t - 1])))
    {
      drop[order[t]] = 1; // the group's first in the order is its lowest id
      ++removed;
    }
  res.NumCoincidentRemoved = removed;
  if (removed == 0)
    return;
  std::size_t w = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (drop[i])
    {
      res.NumCornerSites -= res.FeatureKind[i] == 2;
      res.NumFeatureLineSites -= res.FeatureKind[i] == 1;
      continue;
    }
    std::copy_n(s.At(i), dim, s.Coords.data() + w * dim);
    std::copy_n(s.Bary.data() + 4 * i, 4, s.Bary.data() + 4 * w);
    s.CellIds[w] = s.CellIds[i];
    res.FeatureKind[w] = res.FeatureKind[i];
    res.FeatureEdge[w] = res.FeatureEdge[i];
    ++w;
  }
  s.Coords.resize(w * dim);
  s.Bary.resize(4 * w);
  s.CellIds.resize(w);
  res.FeatureKind.resize(w);
  res.FeatureEdge.resize(w);
}

/// Empty result for n sites in R^dim (zero coordinates, all sites free).
ParticleSamplerResult MakeResult(std::size_t n, int dim)
{
  ParticleSamplerResult res;
  SiteSet& s = res.Sites;
  s.Dim = dim;
  s.CellIds.resize(n);
  s.Bary.assign(4 * n, 0.0);
  s.Coords.assign(n * static_cast<std::size_t>(dim), 0.0);
  res.FeatureKind.assign(n, 0);
  res.FeatureEdge.assign(n, -1);
  return res;
}

/**
 * Sharp features (options.PreserveSharpFeatures): `features` (options.Features, else detected
 * on the input mesh) and
 * the corner and feature-line sites placed on them (one per `spacing` of embedded length),
 * cut back to what fits in half of the sites (corners only, or none) with res.FeatureWarning
 * saying so. Fills res.NumCornerSites and NumFeatureLineSites.
 */
FeatureSitePlacement PlaceSharpFeatureSites(const SimplexMesh& mesh,
  const Embedding& embedding,
  const ParticleSamplerOptions& opt,
  double spacing,
  SharpFeatures& features,
  ParticleSamplerResult& res)
{
  FeatureSitePlacement placed;
  placed.Sites.Dim = embedding.Dim;
  if (!opt.PreserveSharpFeatures || (!opt.Features && !(opt.FeatureAngle < 180.0)))
    return placed;
  features = opt.Features ? *opt.Features : DetectSharpFeatures(mesh, opt.FeatureAngle);
  if (features.Corners.empty() && features.NumEdges() == 0)
    return placed;
  const std::size_t n = opt.NumSites;
  placed = PlaceFeatureSites(mesh, embedding, features, spacing);
  // Too few sites for the features (a coarse sampling of a domain with many corners or
  // long edges): keep what fits in half of the sites, and say so.
  const std::size_t lineSites = placed.Sites.NumSites() - placed.NumCorners;
  if (2 * placed.Sites.NumSites() > n)
  {
    const bool cornersFit = 2 * placed.NumCorners <= n;
    res.FeatureWarning = std::to_string(n) + " sites are too few for the sharp features (" +
      std::to_string(placed.NumCorners) + " corners and " + std::to_string(lineSites) +
      " sites on feature lines would take more than half): " +
      (cornersFit ? "only the corners are kept" : "features ignored") +
      "; ask for more sites to keep them";
    placed.Sites.CellIds.resize(cornersFit ? placed.NumCorners : 0);
    placed.Sites.Bary.resize(4 * placed.Sites.CellIds.size());
    placed.Sites.Coords.resize(
      placed.Sites.CellIds.size() * static_cast<std::size_t>(embedding.Dim));
    placed.Edge.resize(placed.Sites.CellIds.size());
    placed.NumCorners = placed.Sites.CellIds.size();
  }
  res.NumCornerSites = placed.NumCorners;
  res.NumFeatureLineSites = placed.Sites.NumSites() - placed.NumCorners;
  return placed;
}

} // namespace

ParticleSamplerResult SampleParticles(const SimplexMesh& mesh,
  const Embedding& embedding,
  const ParticleSamplerOptions& opt)
{
  const Stopwatch clock;
  CheckInputs(mesh, embedding);
  CheckOptions(mesh, opt);

  const int k = mesh.SimplexDim;
  const std::size_t nc = mesh.NumCells(), n = opt.NumSites;
  const std::vector<double> meas = EmbeddedCellMeasures(mesh, embedding);
  double total = 0.0;
  for (std::size_t c = 0; c < nc; ++c)
    total += meas[c];
  if (!(total > 0.0) || !std::isfinite(total))
    throw InputError("SampleParticles: the embedded mesh has zero (or non-finite) measure");

  ParticleSamplerResult res = MakeResult(n, embedding.Dim);
  res.EmbeddedMeasure = total;
  res.Sigma = opt.KernelWidthFactor * std::pow(total / static_cast<double>(n), 1.0 / k);

  // Sharp features: corner and feature-line particles placed first, the rest drawn as usual.
  const double factor =
    opt.FeatureSpacingFactor > 0.0 ? opt.FeatureSpacingFactor : (k == 3 ? 1.26 : 1.075);
  SharpFeatures features;
  const FeatureSitePlacement placed = PlaceSharpFeatureSites(mesh,
    embedding,
    opt,
    factor * std::pow(total / static_cast<double>(n), 1.0 / k),
    features,
    res);
  sampling::DrawInitialSites(mesh, embedding, meas, opt, placed, res);

  const SharpFeatures* featurePtr = placed.Sites.NumSites() > 0 ? &features : nullptr;
  if (featurePtr)
    res.Features = features;
  auto run = [&]() { sampling::OptimizeParticles(mesh, embedding, featurePtr, opt, res); };
  if (opt.MaxThreads > 0)
  {
    tbb::task_arena arena(opt.MaxThreads);
    arena.execute(run);
  }
  else
    run();
  RemoveCoincidentSites(res);
  res.Seconds = clock.Seconds();
  return res;
}

} // namespace av
