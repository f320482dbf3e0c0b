// SPDX-License-Identifier: BSD-3-Clause
// MetricPreparation: what every metric-based mesher does to a metric before meshing with it
// (MMG's -hmin/-hmax/-hgrad, Alauzet 2010 "Size gradation control of anisotropic meshes"): a
// size mode, normalization to a target number of output cells, size limits and a bounded
// growth of the metric per unit of metric length. VTK-free.
#ifndef av_MetricPreparation_h
#define av_MetricPreparation_h

#include "SimplexMesh.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{

/// Where the sizes of the prepared metric come from.
enum class MetricSizeMode
{
  Tensor,  ///< sizes and shapes from the metric as given
  Uniform, ///< shape only: every metric scaled to unit determinant (equal-size cells)
  Blend    ///< det M = det(M_raw)^SizeBlend: between Uniform (0) and Tensor (1)
};

/// Parameters of PrepareMetric (defaults in brackets).
struct MetricPreparationOptions
{
  MetricSizeMode SizeMode = MetricSizeMode::Tensor;
  /// Blend: exponent alpha in [0, 1] of det(M_raw) kept by the size [0.5].
  double SizeBlend = 0.5;
  /// > 0: scale the metric so that its complexity C = integral of sqrt(det M) holds about that
  /// many unit vertices (C = TargetSites x UnitVertexMeasure), i.e. unit metric length is one
  /// output cell; the scale is re-fitted after the size limits and the gradation, which add
  /// complexity. 0: keep the metric's scale [0].
  double TargetSites = 0.0;
  /// Size limits in the input's length units, applied after the normalization: eigenvalues
  /// clamped to [1 / HMax^2, 1 / HMin^2]; 0 = no limit [0, 0].
  double HMin = 0.0;
  double HMax = 0.0;
  /// Cells across thin parts: along each of the directions of ComputeDomainChords, the domain's
  /// chord through a vertex is at least this many unit metric lengths there (the metric is
  /// raised along that direction, a rank-one update, where it is not), applied with the size
  /// limits. A domain thinner than the cells has no four Voronoi cells meeting inside it and
  /// its restricted Delaunay dual has holes (the CalculiX rotor's disc). When the thin parts
  /// alone would need more than TargetSites, fewer cells across (CellsAcross). Volumes and flat
  /// 2D domains, not in Uniform size mode (equal sizes); surfaces are left alone. 0 = off [0].
  double MinCellsAcross = 0.0;
  /// Bounded growth along every edge pq: M_q >= (1 + l_p(pq) ln beta)^-2 M_p, l_p the length of
  /// pq in M_p (Alauzet 2010, physical-space gradation), enforced by metric intersection [on].
  bool Gradation = true;
  /// beta = MMG's hgrad, > 1: sizes grow by at most a factor ~beta per unit metric length
  /// [1.3, MMG's default].
  double GradationFactor = 1.3;
  /// 3, or 2 for a flat 2D domain (only XX, YY, XY are read and written) [3].
  int Dimension = 3;
  /// Most normalization rounds (size limits + gradation, then the scale is re-fitted) [8].
  int MaxNormalizationRounds = 8;
  /// Stop re-fitting when the complexity is within this relative distance of the target [2e-3].
  double ComplexityTolerance = 2e-3;
  /// Deviation statistics: a vertex counts as changed when a length changes by more than this
  /// relative amount [0.05].
  double ChangeThreshold = 0.05;
};

/// How far a prepared metric is from the raw one, at the same complexity (the raw metric is
/// scaled to the prepared one's complexity, so both give the same number of cells). Per vertex:
/// the largest, over the raw metric's eigenvectors v, of max(rho, 1 / rho) - 1 with rho the
/// ratio of the lengths of v in the two metrics.
struct MetricDeviation
{
  double Median = 0.0;          ///< median over the vertices
  double Percentile95 = 0.0;    ///< 95th percentile
  double Maximum = 0.0;         ///< largest
  double ChangedFraction = 0.0; ///< fraction of vertices above ChangeThreshold
};

/// Output of PrepareMetric.
struct MetricPreparationResult
{
  MetricField Metric;                  ///< the prepared field, 6 components per vertex
  std::vector<double> StretchRatio;    ///< s_max / s_min per vertex
  double Scale = 1.0;                  ///< normalization factor applied to the size-mode metric
  double RawComplexity = 0.0;          ///< complexity of the input field
  double Complexity = 0.0;             ///< complexity of the prepared field
  double TargetComplexity = 0.0;       ///< TargetSites x UnitVertexMeasure (0 when not normalized)
  double ImpliedSites = 0.0;           ///< Complexity / UnitVertexMeasure: the sites it asks for
  int NormalizationRounds = 0;         ///< rounds run (0 without TargetSites)
  int GradationSweeps = 0;             ///< sweeps of the last gradation
  int GradationRuns = 0;               ///< gradations run in all (one per normalization round)
  int TotalGradationSweeps = 0;        ///< their sweeps added up
  std::size_t NumGraded = 0;           ///< vertices the last gradation changed
  std::size_t NumHMinClamped = 0;      ///< vertices with an eigenvalue lowered to 1 / HMin^2
  std::size_t NumHMaxClamped = 0;      ///< vertices with an eigenvalue raised to 1 / HMax^2
  std::size_t NumThicknessLimited = 0; ///< vertices raised by MinCellsAcross
  /// MinCellsAcross as used: lower where it asked for more than TargetSites (0: off).
  double CellsAcross = 0.0;
  MetricDeviation Deviation;           ///< against the input field
};

/**
 * @brief Prepares `metric` (one SPD tensor per vertex of `mesh`) for meshing.
 *
 * Steps: size mode; then, per normalization round, scale (TargetSites), size limits (HMin,
 * HMax), gradation; finally the deviation from the input. `edges` (flat pairs of vertex ids)
 * are the graph the gradation runs on: the input's own cell edges when the mesh is a split of
 * it, UniqueEdges(mesh) when empty. Throws InputError on: an empty or mismatched field, a
 * metric that is not positive definite in its used Dimension x Dimension block, NaN/Inf, edges
 * out of range, invalid options.
 */
MetricPreparationResult PrepareMetric(const SimplexMesh& mesh,
  const MetricField& metric,
  const MetricPreparationOptions& options,
  const std::vector<std::int32_t>& edges = {});

/**
 * Gradation alone, in place: every edge pq ends with M_q >= eta M_p and M_p >= eta' M_q
 * (Loewner order, relative tolerance 1e-6), eta = (1 + l_p(pq) ln beta)^-2. A work list of the
 * vertices whose metric changed, processed in parallel Jacobi sweeps (each vertex intersects
 * its metric with those propagated from its changed neighbors); metrics only grow and are
 * bounded by the field's largest, so it terminates. Returns the number of vertices changed;
 * `sweeps` gets the number of sweeps.
 */
std::size_t GradeMetric(const SimplexMesh& mesh,
  const std::vector<std::int32_t>& edges,
  double beta,
  int dimension,
  MetricField& metric,
  int& sweeps);

/// The deviation of `prepared` from `raw` (see MetricDeviation); both SPD in their used block.
MetricDeviation MeasureMetricDeviation(const SimplexMesh& mesh,
  const MetricField& raw,
  const MetricField& prepared,
  int dimension,
  double changeThreshold = 0.05);

} // namespace av

#endif
