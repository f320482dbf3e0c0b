// SPDX-License-Identifier: BSD-3-Clause
// MeshingPipeline: the one meshing sequence of sites on an embedded mesh (RVD -> RDT -> site
// improvement rounds -> repair), shared by vtkAnisoRestrictedDelaunay, the CLI and the bench.
#ifndef av_MeshingPipeline_h
#define av_MeshingPipeline_h

#include "BoundaryNotchClosure.h"
#include "FeatureEdgeRecovery.h"
#include "MeshImprovement.h"
#include "RestrictedDelaunayRefinement.h"
#include "SharpFeatures.h"
#include "SimplexMesh.h"
#include "ValidDualMesh.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace av
{

/// The points at which RunMeshingPipeline reports progress (MeshingPipelineOptions::Progress).
enum class MeshingStep
{
  Voronoi,          ///< the first restricted Voronoi diagram is done
  Delaunay,         ///< its dual (the first restricted Delaunay mesh) is done
  ImprovementRound, ///< an improvement round that moved sites, and its new RVD + RDT, are done
  Improvement       ///< all improvement rounds are done; the repair comes next
};

/// Options of RunMeshingPipeline. The defaults are those of vtkAnisoRestrictedDelaunay.
struct MeshingPipelineOptions
{
  /// Site improvement rounds before the repair (ImproveSites: ODT steps, then sliver pushes,
  /// then RVD + RDT again); 0 = the paper's pipeline. Stops early at a round that moves no site.
  int ImproveRounds = 1;
  int OdtIterations = 3;      ///< ODT steps per round (0: sliver pushes only)
  bool PerturbSlivers = true; ///< sliver pushes in each round (tet meshes)
  /// Per site, nonzero: never pushed by the sliver perturbation, nor moved by the ODT steps
  /// with OdtKeepsFixedSites (the sampler's corner and feature-line sites). nullptr: every site
  /// may move. Must outlive the call.
  const std::vector<std::uint8_t>* FixedSites = nullptr;
  /// The ODT steps keep the FixedSites too, except those of the current dual's inverted cells
  /// and non-manifold faces (where fixed sites do not make a valid dual; the ODT relaxes them as
  /// it does the others). In volumes they are kept anyway (their cells meet the boundary); on
  /// surfaces a crease is not the boundary, and without this the ODT moves the crease sites off
  /// their lines (turbine: median 0.37 %, at most 1.2 % of the diagonal; a box: all 72). Off by
  /// default: closer to the input at the creases (box 3.77 -> 1.03 %, fandisk 0.82 -> 0.54 % of
  /// the diagonal), but worse triangles where the creases are rounded or close together
  /// (Filters/Delaunay/README.md, "Feature sites on surfaces").
  bool OdtKeepsFixedSites = false;
  /// Insert sites at the Voronoi vertices of inverted elements (paper §4.2); false: only
  /// compute and report (RepairRestrictedDelaunay with MaxRounds 0).
  bool Repair = true;
  int MaxRepairRounds = 10;       ///< insertion rounds at most
  bool RepairNonManifold = true;  ///< also repair faces shared by more than two elements
  /// Volumes: when the repaired dual still has inverted / flat cells or non-manifold faces,
  /// replace it by the Delaunay tetrahedralization of its sites carved to the domain
  /// (MakeDualValid, ValidDualMesh.h), valid by construction. false: keep the invalid dual.
  bool ValidDual = true;
  /// Surfaces: edges between sites consecutive along the feature lines found by
  /// DetectSharpFeatures(mesh, FeatureAngle) (the sampler's, which puts the sites on them) are
  /// put into the final dual by edge flips (RecoverFeatureEdges, FeatureEdgeRecovery.h), before
  /// the mesh improvement, which keeps them. 180 or more: off. Volumes: unused.
  double FeatureAngle = 30.0;
  /// Surfaces: the sampler's features (ParticleSamplerResult::Features, or rebuilt with
  /// SharpFeaturesFromEdges) for those flips and the crease slide, instead of detecting them at
  /// FeatureAngle. Must outlive the call.
  const SharpFeatures* Features = nullptr;
  /// Surfaces with an open boundary: a boundary vertex of the final dual that is not on the
  /// input's boundary (a site just inside it, whose cell reaches the boundary between two
  /// boundary sites) gets the triangle that closes the notch (CloseBoundaryNotches,
  /// BoundaryNotchClosure.h), before the mesh improvement. false: the dual's boundary as it is.
  bool CloseBoundaryNotches = true;
  /// Mesh improvement of the final dual (ImproveFinalMesh: flips and vertex smoothing in the
  /// metric); runs when ImproveMesh is true and Metric is given. false: the paper's dual.
  bool ImproveMesh = true;
  /// The metric per vertex of the input mesh (MetricField order); nullptr: no mesh improvement.
  /// Must outlive the call.
  const MetricField* Metric = nullptr;
  MeshImprovementOptions Improvement; ///< its options (AcceptMove is the pipeline's own)
  /// Called at each MeshingStep; returning false aborts the run (Aborted in the result).
  std::function<bool(MeshingStep)> Progress;
};

/// Output of RunMeshingPipeline.
struct MeshingPipelineResult
{
  /// The repaired mesh: Repaired.Sites (the improved input sites in input order, then the
  /// inserted ones), Repaired.Voronoi and Repaired.Delaunay of them, and the repair counts.
  DelaunayRepairResult Repaired;
  /// Per input site, 1 where the improvement rounds changed its cell id or barycentric
  /// coordinates (inserted sites are not in it).
  std::vector<std::uint8_t> Moved;
  std::size_t NumMovedSites = 0;    ///< count of Moved
  std::size_t NumOdtMovedSites = 0; ///< sites moved by the first round's ODT steps
  std::size_t NumSlivers = 0;       ///< slivers (embedded dihedral < 15 deg) of the first round
  int ImproveRoundsDone = 0;        ///< rounds that moved sites
  bool Aborted = false;             ///< Progress returned false; the rest is incomplete
  double VoronoiSeconds = 0.0;      ///< element adjacency and the first restricted Voronoi diagram
  double DelaunaySeconds = 0.0;     ///< the first restricted Delaunay mesh
  double ImproveSeconds = 0.0;      ///< improvement rounds, their RVD + RDT included
  double RepairSeconds = 0.0;       ///< the repair (its rounds after the last RVD + RDT)
  /// The mesh improvement's counts (Passes 0 when it did not run); Repaired.Delaunay is then
  /// the improved mesh (no longer the dual of Repaired.Voronoi) and Moved includes its moves.
  MeshImprovementResult Improvement;
  /// The valid-dual step (ValidDual): Replaced when the repaired dual was invalid.
  ValidDualResult ValidDual;
  double ValidDualSeconds = 0.0;
  FeatureEdgeRecoveryResult FeatureEdges;    ///< surfaces: the feature-edge flips (FeatureAngle)
  BoundaryNotchResult BoundaryNotches;       ///< surfaces: the open boundary's notches closed
  std::size_t InvertedBeforeImprovement = 0; ///< Repaired.Delaunay.NumInverted before it
  double MeshImprovementSeconds = 0.0;
};

/**
 * Meshes `sites` on the embedded mesh: the restricted Voronoi diagram (no geometry, the
 * DelaunayRepairOptions default) and its dual (ComputeRestrictedDelaunay); then up to
 * ImproveRounds rounds of ImproveSites, each followed by a new RVD + RDT; then
 * RepairRestrictedDelaunay starting from the last RVD + RDT; on surfaces, the feature-line
 * edges by flips (FeatureAngle) and the open boundary's notches closed; then, with ImproveMesh and Metric, ImproveFinalMesh on the
 * repaired dual. The element adjacency is computed once for all of them. Deterministic. Throws
 * InputError on bad input (inconsistent mesh, embedding or sites, FixedSites not one per site,
 * negative counts).
 */
MeshingPipelineResult RunMeshingPipeline(const SimplexMesh& mesh,
  const Embedding& embedding,
  const SiteSet& sites,
  const MeshingPipelineOptions& options = MeshingPipelineOptions());

} // namespace av

#endif
