// SPDX-License-Identifier: BSD-3-Clause
// ParticleSampler: isotropic Gaussian-repulsion particle sampling on the embedded
// surface / volume (paper §4.1), VTK-free.
#ifndef av_ParticleSampler_h
#define av_ParticleSampler_h

#include "SharpFeatures.h"
#include "SimplexMesh.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace av
{

/// Parameters of SampleParticles (defaults from the paper).
struct ParticleSamplerOptions
{
  std::size_t NumSites = 1000;   ///< number of particles n, 1 .. 8 * NumPoints
  /// L-BFGS iterations at KernelWidthFactor, >= 0 (the paper: 50; 150 after the warm-up is
  /// a better mesh within cube2's 2 s meshing budget, see Filters/Sampling/README.md).
  int Iterations = 150;
  std::uint64_t Seed = 1;        ///< seeds the initial sampling; same seed -> same output
  double KernelWidthFactor = 0.3; ///< sigma = factor * (|embedded mesh| / n)^{1/k}
  double NeighborCutoff = 5.0;  ///< pairs farther than this many sigma are ignored
  int History = 7;               ///< L-BFGS memory (pairs of vectors)
  int MaxThreads = 0;            ///< 0: all cores; the result does not depend on it
  /// Iterations at WarmupKernelWidthFactor before the Iterations at KernelWidthFactor (not
  /// in the paper: the narrower kernel evens out the spacing faster, and these iterations
  /// improve the mesh more than the paper-kernel ones; see Filters/Sampling/README.md), >= 0.
  int WarmupIterations = 100;
  double WarmupKernelWidthFactor = 0.25; ///< sigma factor of the warm-up iterations
  /// Initial sites drawn by jittered stratification along a Morton order of the cells
  /// (false: i.i.d. draws, the paper's random start).
  bool StratifiedInitialSites = true;
  /// Candidates per initial site of a best-candidate (well-spaced) start, >= 1: each site
  /// is the one of this many measure-proportional draws farthest (in R^Dim) from the sites
  /// placed before (1: the draws above; StratifiedInitialSites is then ignored). Off by
  /// default: 20 makes a much better start (dual of the unmoved cube1 sites G_avg 0.64 ->
  /// 0.78, slivers 12 % -> 3 %; +0.03 s for 5000 sites on cube2), but after the default
  /// 100 + 50 iterations the mesh is the same within seed noise (cube1 / cube2 G_avg 0.906 /
  /// 0.911 either way); with no warm-up it gains ~0.002 G_avg.
  int InitialCandidates = 1;
  /// Sharp features (paper §4.1): a fixed particle at every corner and particles that move
  /// only along the feature lines, found by DetectSharpFeatures(mesh, FeatureAngle) on the
  /// input-space mesh; the dual mesh then keeps the domain's corners and edges. Smooth
  /// domains (no dihedral angle above FeatureAngle) are unaffected.
  bool PreserveSharpFeatures = true;
  double FeatureAngle = 30.0; ///< degrees, in (0, 180]; 180 = no features
  /// Given features (SharpFeaturesFromPatches / SharpFeaturesFromEdges of this mesh) instead of
  /// DetectSharpFeatures; used with PreserveSharpFeatures. Must outlive the call.
  const SharpFeatures* Features = nullptr;
  /// The feature lines get one particle per FeatureSpacingFactor * (|embedded mesh| / n)^{1/k}
  /// of embedded length (1.26 = 2^{1/3}: the edge of the body-centered cubic cell holding two
  /// sites of volume |mesh| / n each; 1.075 for triangles: the hexagonal spacing).
  double FeatureSpacingFactor = 0.0; ///< 0: 1.26 for tets, 1.075 for triangles
  /// Called once per iteration with the fraction done in [0,1]; return false to abort.
  std::function<bool(double)> Progress; ///< fraction of WarmupIterations + Iterations
};

/// Output of SampleParticles.
struct ParticleSamplerResult
{
  SiteSet Sites;               ///< embedded coords (Dim each), containing cell, barycentrics
  /// Per site: 0 free (interior or boundary), 1 on a feature line, 2 at a corner (fixed).
  std::vector<std::int8_t> FeatureKind;
  /// Per site: its feature edge (SharpFeatures::Edges index) for kind 1, else -1.
  std::vector<std::int32_t> FeatureEdge;
  /// The features the sites were placed on (empty when there were none, or none fit).
  SharpFeatures Features;
  std::size_t NumCornerSites = 0;
  std::size_t NumFeatureLineSites = 0;
  /// Non-empty when the sharp features would take more than half of the sites and were cut
  /// back (corners only, or none): the reason, for the caller to show.
  std::string FeatureWarning;
  /// Energy at KernelWidthFactor: Energy[0] at the start of those iterations (after the
  /// warm-up), Energy[i] after iteration i.
  std::vector<double> Energy;
  std::vector<double> WarmupEnergy; ///< the same for the warm-up (its own, narrower kernel)
  int WarmupIterationsDone = 0;
  double Sigma = 0.0;          ///< the kernel width of the (final) Iterations
  double EmbeddedMeasure = 0.0; ///< |embedded mesh|: area (triangles) or volume (tets)
  double MeanNeighbors = 0.0; ///< average neighbor count within the cutoff at the end
  int EnergyEvaluations = 0;   ///< energy evaluations (line-search trials included)
  int NeighborRebuilds = 0;   ///< builds of the outer neighbor lists (grid)
  int IterationsDone = 0;
  /// Particles removed at the end because another one (of lower id) ended on exactly the same
  /// point: two particles that reach one mesh vertex (a feature-line particle walked onto a
  /// corner, free ones pushed into a corner of the embedded boundary) no longer repel, since
  /// the Gaussian's gradient vanishes at distance 0, and a copy would get an empty cell.
  std::size_t NumCoincidentRemoved = 0;
  bool Aborted = false;        ///< the progress callback asked to stop
  double Seconds = 0.0;        ///< wall time of the whole call
};

/**
 * Samples NumSites particles on the embedded mesh (the cells of `mesh` with the vertex
 * positions of `embedding`, triangles or tets in R^Dim, Dim 2..20) and spreads them
 * isotropically by minimizing E = sum_{p<q} [exp(-|x_p - x_q|^2 / (4 sigma^2)) - exp(-c^2/4)]
 * over pairs closer than the cutoff c * sigma (c = NeighborCutoff). The constant shift
 * makes E continuous, so it is a function of the positions alone; neighbors come from
 * two-level Verlet lists: outer lists of radius c sigma + 2.5 sigma built on a grid over the
 * particles' three principal coordinates (a projection only shortens distances, so no pair
 * is missed), inner lists of radius c sigma + sigma / 2 re-filtered from them; each level is
 * rebuilt when the particles' moves could let a pair closer than c sigma escape it.
 *
 * Initial particles are drawn with probability proportional to the embedded cell measure
 * and uniformly inside the cell. The minimizer is a projected L-BFGS: the gradient of every
 * particle is projected onto the tangent space of its cell (and onto the boundary face when
 * it pushes outward), a step is walked in barycentric coordinates across cell faces, and a
 * particle that reaches the mesh boundary slides along it; a backtracking (Armijo) line
 * search keeps the energy decreasing. Particles are therefore always on / in the embedded
 * mesh. Deterministic for a given seed, whatever the number of threads.
 *
 * With PreserveSharpFeatures, the corners of the input mesh get one particle each that never
 * moves, and particles placed evenly along the feature lines (FeatureSites) move only along
 * them (their gradient projected on the line, their steps walked from edge to edge up to the
 * next corner); the other particles are drawn as above for the remaining count.
 *
 * Particles that end on exactly the point of a lower-id particle are removed (the result then
 * has fewer than NumSites sites; NumCoincidentRemoved says how many): a corner is listed
 * before the feature-line particles, and these before the free ones, so the corner stays.
 *
 * When the feature sites would be more than half of NumSites, only the corners are kept (or
 * none, if they alone are more than half) and FeatureWarning says so.
 *
 * Throws InputError on: NumSites 0 or > 8 * NumPoints, wrong array sizes, Dim outside
 * [max(AmbientDim, SimplexDim), 20], NaN/Inf, cell ids out of range, zero embedded measure,
 * non-positive options.
 */
ParticleSamplerResult SampleParticles(
  const SimplexMesh& mesh, const Embedding& embedding, const ParticleSamplerOptions& options);

} // namespace av

#endif
