// SPDX-License-Identifier: BSD-3-Clause
// MetricAdaptedMesh: the background mesh the embedding runs on, adapted to the metric and to the
// number of sites: long metric edges split (conforming, longest first), short ones collapsed
// (keeping the boundary, the feature lines, the orientation and the manifold), so that its size
// follows the sites and the metric's complexity instead of the user's mesh.
#ifndef av_MetricAdaptedMesh_h
#define av_MetricAdaptedMesh_h

#include "SimplexMesh.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{

/// Parameters of AdaptBackgroundMesh. Lengths are in the normalized metric (see below).
struct AdaptedMeshOptions
{
  /// Sites the output (Voronoi / mesh) will have. The metric is scaled by s so that the field
  /// holds that many unit cells: s^(k/2) C / UnitVertexMeasure(k) = NumberOfSites (C the
  /// complexity, k the simplex dimension); an output edge then has length about 1. Required > 0.
  int NumberOfSites = 2000;
  /// L_bg: the longest background edge allowed, in units of an output edge (the resolution
  /// criterion: every edge of the result has normalized metric length <= TargetLength, so an
  /// output edge spans about 1 / TargetLength background edges). In (0, 10].
  double TargetLength = 0.5;
  /// Edges shorter than CollapseRatio x TargetLength are collapsed when that is safe. In [0, 0.7];
  /// 0 disables coarsening. Collapses never create an edge longer than TargetLength.
  double CollapseRatio = 0.4;
  bool Refine = true;
  bool Coarsen = true;
  /// Dihedral angle (degrees) above which an edge is a feature line (as DetectSharpFeatures).
  double FeatureAngle = 30.0;
  /// A collapse may turn a boundary face (tets), a surface triangle or a line edge by at most this
  /// angle (degrees): 0 keeps the boundary exactly, flat patches still coarsen. In [0, 30].
  double SurfaceDeviationAngle = 1.0;
  /// Collapses keep the metric shape quality of every changed element >= min(this, the worst of
  /// the elements they replace) (1 = regular in the metric).
  double MinQuality = 0.2;
  /// Refinement stops (Result.HitPointLimit) once the mesh has this many points. >= 4.
  std::size_t MaxPoints = 4000000;
  int MaxCoarsenPasses = 30;
};

/// What AdaptBackgroundMesh returns.
struct AdaptedMeshResult
{
  SimplexMesh Mesh;
  /// The metric at every output point: input values at input points, the log-Euclidean mean of
  /// the containing input element's vertex metrics (with ParentWeights) at new points. Unscaled.
  MetricField Metric;
  /// Per output point, 4 input point ids (-1 = unused) and weights summing to 1: the point is
  /// sum_j w_j x_{id_j}, exactly (new points are barycentric combinations within one input
  /// element), so a point array f is carried as sum_j w_j f(id_j); a linear field stays linear.
  std::vector<std::int32_t> ParentIds;
  std::vector<double> ParentWeights;
  /// Per output cell, the input cell it came from (for a collapsed neighborhood, the input cell
  /// of the surviving element).
  std::vector<std::int32_t> CellParent;

  double MetricScale = 1.0; ///< s: normalized metric = s x input metric
  double Complexity = 0.0;  ///< C of the input field (integral of sqrt(det M))
  std::size_t NumSplits = 0;
  std::size_t NumCollapses = 0;
  int RefinePasses = 0;
  int CoarsenPasses = 0;
  bool HitPointLimit = false;
  /// Normalized metric edge lengths of the result: the longest and the mean.
  double MaxEdgeLength = 0.0;
  double MeanEdgeLength = 0.0;
  double Seconds = 0.0;
};

/**
 * Adapts `mesh` (tetrahedra; triangles in 2D; surface triangles in 3D) to `metric` (one 6-component
 * tensor per point, SPD, or rank 2 on a surface) for `options.NumberOfSites` sites:
 * 1. refinement: passes over the edges longer than TargetLength, longest first, splitting each at
 *    its midpoint together with every element that shares it (conforming, anisotropic: only long
 *    edges are cut); the new point lies in the element, so on the input's surface or boundary;
 * 2. coarsening: passes over edges shorter than CollapseRatio x TargetLength, shortest first,
 *    collapsing one end onto the other unless that inverts or flattens an element, folds a
 *    surface, moves the boundary or a feature line (corners never move), breaks the manifold
 *    (link condition, face multiplicity), lowers the quality, or makes an edge longer than
 *    TargetLength.
 * Parallel (TBB) where the work is per edge or per point; the topology changes are sequential.
 * Throws InputError on bad options, an empty mesh, bad ids, a metric of the wrong size, non-finite
 * values or a zero-complexity metric.
 */
AdaptedMeshResult AdaptBackgroundMesh(const SimplexMesh& mesh,
  const MetricField& metric,
  const AdaptedMeshOptions& options);

/// How finely a mesh resolves a metric for a number of output vertices, in the normalized metric
/// of AdaptBackgroundMesh (an output edge has length about 1).
struct BackgroundResolution
{
  double MeanEdgeLength = 0.0;
  double MaxEdgeLength = 0.0;
  double LongEdgeFraction = 0.0; ///< of the edges, those longer than the target length
};

/**
 * The edge statistics of `mesh` under `metric` scaled for `numberOfSites` sites, as
 * AdaptBackgroundMesh measures its result: whether the mesh is finer than the output it is to
 * carry (the resolution criterion, edges of at most `targetLength` output edges). Throws
 * InputError as AdaptBackgroundMesh does.
 */
BackgroundResolution MeasureBackgroundResolution(const SimplexMesh& mesh,
  const MetricField& metric,
  int numberOfSites,
  double targetLength);

/// The edge length (in output edges) the automatic adaptation asks for: on the CalculiX and
/// OpenFOAM volumes 1.5 gave the best final meshes per second (1.2 costs 3-5x more for no more
/// G_avg; 2.0 loses the rotor's worst tets; Filters/BackgroundMesh/README.md).
constexpr double kAutomaticBackgroundEdgeLength = 1.5;

/// Whether a mesh is too coarse to carry the output: its mean edge is longer than one output
/// edge, so the embedding could not follow the metric at the scale of the cells (the
/// automatic adaptation of tensor fields runs then).
inline bool CoarserThanOutput(const BackgroundResolution& r)
{
  return r.MeanEdgeLength > 1.0;
}

} // namespace av

#endif
