// SPDX-License-Identifier: BSD-3-Clause
// MeshStage: the "mesh" stage of anisovoronoi-bench (sampling, then av::RunMeshingPipeline, then
// the §5.2 quality of the dual mesh), kept apart from the JSON / CLI code.
#ifndef av_bench_MeshStage_h
#define av_bench_MeshStage_h

#include "AnalyticMetrics.h"
#include "ParticleSampler.h"
#include "SimplexMesh.h"

#include <cstddef>
#include <cstdint>

namespace avbench
{

/// Paper's numbers for the meshing of a case (Tab. 5; Tab. 3 "2D Domain" for gaussian2d);
/// NaN where the paper gives none.
struct PaperMeshValues
{
  double GMin, GAvg, ThetaMin, ThetaAvg, PercentBad, MeshSeconds;
};
PaperMeshValues PaperMeshValuesFor(av::AnalyticPreset preset);

/// Number of sites of the paper's Tab. 5 row (Tab. 3 for the 2D case).
std::size_t DefaultSitesFor(av::AnalyticPreset preset);

/// Options of RunMeshStage.
struct MeshStageOptions
{
  std::size_t Sites = 1000;
  int SampleIterations = 150;
  int WarmupIterations = 100;     ///< sampler warm-up iterations (ParticleSamplerOptions)
  std::uint64_t Seed = 1;
  double KernelWidthFactor = 0.3; ///< sampler's sigma factor
  int LloydIterations = 0;        ///< Lloyd (CVT) steps after sampling (av::RelaxSitesLloyd)
  bool Repair = true;             ///< insert sites to repair inverted dual elements
  int MaxRepairRounds = 10;
  bool RepairNonManifold = true;  ///< also repair non-manifold faces
  bool ValidDual = true;          ///< replace a still invalid volume dual (ValidDualMesh.h)
  /// Site improvement rounds before the repair (av::ImproveSites: ODT steps and sliver
  /// pushes, then RVD + RDT again); 0 = the paper's pipeline.
  int ImproveRounds = 1;
  int OdtIterations = 3;      ///< ODT steps per round (0: sliver pushes only)
  bool PerturbSlivers = true; ///< sliver pushes in each round
  bool ImproveMesh = true; ///< flips and smoothing of the final dual in the metric (MeshImprovement)
  bool PlanarBoundary = true; ///< ...also on planar boundary patches (MeshImprovementOptions)
  bool StraightCreases = true; ///< ...and along straight creases (MeshImprovementOptions)
  bool VertexInsertion = true; ///< tets: vertex insertion (MeshImprovementOptions::Insertions)
  bool Collapses = true; ///< edge collapses / contractions (MeshImprovementOptions::Collapses)
  double EdgeRuleAngle = 20.0; ///< MeshImprovementOptions::EdgeLengthRuleMinAngle (degrees)
  bool BoundarySnap = true;    ///< tets: MeshImprovementOptions::SnapToBoundary
  bool InputBoundaryMoves = true; ///< tets: MeshImprovementOptions::InputBoundaryMoves
  double BoundaryFlipMaxDihedral = 10.0; ///< ...and edges of nearly coplanar boundary faces
  double BoundaryFlipVolumeBudget = 5e-3; ///< ...changing at most this share of the volume
  bool PreserveSharpFeatures = true; ///< corner / feature-line particles (ParticleSamplerOptions)
  bool OdtKeepsFeatureSites = false; ///< MeshingPipelineOptions::OdtKeepsFixedSites
  bool RecoverFeatureEdges = true;   ///< surfaces: MeshingPipelineOptions::FeatureAngle < 180
  double FeatureAngle = 30.0;        ///< degrees
  bool CloseBoundaryNotches = true;  ///< surfaces: MeshingPipelineOptions::CloseBoundaryNotches
  int MeanSmoothingSweeps = 2;       ///< MeshImprovementOptions::MeanSmoothingSweeps
};

/// Timings and quality of one meshing run.
struct MeshStageResult
{
  std::size_t Sites = 0;
  std::size_t CornerSites = 0, FeatureLineSites = 0; ///< of the sampled sites
  double DualVolumeRatio = 0.0; ///< dual mesh volume / domain volume (tets; 1 = covered)
  std::size_t CrossBodyElements = 0; ///< dual elements with sites in two bodies of the input
  std::size_t CrossBodyPieces = 0;   ///< Voronoi pieces in a body other than their site's
  std::size_t PinchedBoundaryEdges = 0; ///< tets: edges on more than two boundary faces
  /// Tets: the input domain's smallest interior angle at a boundary edge in the metric
  /// (ComputeDomainAngleBound), degrees, capped at 90; theta_min cannot beat it. -1: not a volume.
  double DomainAngleBound = -1.0;
  std::size_t DomainEdgesBelow15 = 0; ///< tets: input boundary edges whose angle is < 15 deg
  /// Tets: the same for the final mesh's own boundary (sharper than the domain's where the
  /// mesh's boundary folds or cuts corners), and its edges below 15 degrees.
  double MeshBoundaryAngle = -1.0;
  std::size_t MeshBoundaryEdgesBelow15 = 0;
  double SampleSeconds = 0.0, LloydSeconds = 0.0;
  double RvdSeconds = 0.0, RdtSeconds = 0.0; ///< the first RVD (with the adjacency) and RDT
  double ImproveSeconds = 0.0; ///< site improvement rounds (their RVD + RDT included)
  std::size_t OdtMovedSites = 0;    ///< sites moved by the first round's ODT steps
  std::size_t SliversPerturbed = 0; ///< slivers (embedded dihedral < 15 deg) of the first round
  double RepairSeconds = 0.0; ///< repair rounds after the first RVD + RDT
  double MeshImprovementSeconds = 0.0; ///< flips and smoothing of the final dual
  std::size_t ImprovementFlips = 0;    ///< 2-3 flips + edge removals (tets), 2-2 flips (triangles)
  std::size_t ImprovementSmoothed = 0; ///< accepted vertex moves
  /// Of those, on planar boundary patches: edge removals and in-plane vertex moves (tets)
  std::size_t ImprovementBoundaryOps = 0;
  std::size_t ImprovementCreaseMoves = 0; ///< of those, moves along straight creases
  std::size_t ImprovementInsertions = 0;  ///< tets: inserted vertices
  std::size_t ImprovementPeels = 0;       ///< tets: boundary tets removed
  std::size_t ImprovementCollapses = 0;   ///< edge collapses (triangles) / contractions (tets)
  std::size_t ImprovementSnaps = 0;       ///< tets: boundary vertices moved onto the boundary
  /// The improvement's own worst element angle (its metric measure), degrees, before and after
  double ImprovementWorstBefore = 0.0, ImprovementWorstAfter = 0.0;
  /// Surfaces: site pairs consecutive along the feature lines, and of those the edges missing
  /// from the dual, made by flips, and still missing (RecoverFeatureEdges).
  std::size_t FeatureEdgesRequired = 0, FeatureEdgesMissingBefore = 0, FeatureEdgesRecovered = 0,
              FeatureEdgesMissing = 0;
  /// Surfaces: dual boundary vertices off the input's open boundary, before and after the
  /// notch closure, and the triangles it added (CloseBoundaryNotches).
  std::size_t BoundaryNotches = 0, BoundaryNotchesClosed = 0, BoundaryNotchesLeft = 0;
  std::size_t ImprovementMeanSmoothed = 0; ///< moves of the mean-quality sweeps
  double ImprovementVolumeChange = 0.0; ///< fraction of the volume moved by curved-boundary flips
  std::size_t InvertedBeforeImprovement = 0; ///< dual's inverted (or flat) cells before it
  bool ValidDualReplaced = false;  ///< the repaired dual was invalid: Delaunay of the sites
  double ValidDualSeconds = 0.0;
  /// Of the replacement: the dual's valid cells offered as flip targets, those in the result,
  /// and the flips made only to create one (MakeDualValid).
  std::size_t ValidDualTargetCells = 0, ValidDualKeptCells = 0, ValidDualTargetFlips = 0;
  double MeshSeconds = 0.0;      ///< wall of sampling + RVD + RDT + repair
  std::size_t Cells = 0;         ///< restricted Delaunay cells
  std::size_t InsertedSites = 0; ///< by the repair (Sites counts the sampled ones only)
  int RepairRounds = 0;
  std::vector<std::size_t> InvertedPerRound; ///< bad dual elements before each repair round
  bool RepairStalled = false; ///< the repair kept an earlier, better state
  std::size_t RdtInvertedBeforeRepair = 0;
  std::size_t NonManifoldFacesBeforeRepair = 0;
  double GMin = 0.0, GAvg = 0.0, ThetaMin = 0.0, ThetaAvg = 0.0, PercentBad = 0.0;
  /// G_avg of the same dual cells measured with the sites' embedded coordinates (no metric):
  /// GAvgEmbedded - GAvg is what the embedding's departure from the metric costs.
  double GAvgEmbedded = 0.0;
  std::size_t Inverted = 0;          ///< by the quality evaluator (input-space signed measure)
  std::size_t RdtInverted = 0;       ///< by ComputeRestrictedDelaunay (back-projection), after repair
  std::size_t NonManifoldFaces = 0;
  std::size_t UnusedSites = 0;
  double PercentEdgesInUnitRange = 0.0;
  double RvdVolumeError = 0.0; ///< |sum piece measures - domain measure| / domain measure
  std::size_t RvdPieces = 0;
  /// Surfaces (triangles in 3D) only (paper §6.3): fidelity to the input and topology.
  bool IsSurface = false;
  double HausdorffPercent = 0.0;         ///< sampled, both ways, % of the input's diagonal
  double HausdorffForwardPercent = 0.0;  ///< output samples to the input
  double HausdorffBackwardPercent = 0.0; ///< input samples to the output
  std::size_t SelfIntersections = 0;     ///< intersecting pairs of triangles sharing no vertex
  std::size_t Flipped = 0; ///< output triangles whose normal opposes the input surface's
  long long Euler = 0, InputEuler = 0;
  std::size_t BoundaryLoops = 0, InputBoundaryLoops = 0, NonManifoldEdges = 0;
};

/**
 * Samples `options.Sites` particles on the embedded mesh, computes the restricted Voronoi
 * diagram (measures only) and its dual, repairs inverted dual elements by site insertion
 * (options.Repair), and evaluates the dual against `metric` interpolated at the final sites.
 * Throws what the kernels throw.
 */
/// The particle sampler's options of a mesh (or Voronoi) stage.
av::ParticleSamplerOptions SamplerOptionsOf(const MeshStageOptions& options);

MeshStageResult RunMeshStage(const av::SimplexMesh& mesh, const av::MetricField& metric,
  const av::Embedding& embedding, const MeshStageOptions& options);

} // namespace avbench

#endif
