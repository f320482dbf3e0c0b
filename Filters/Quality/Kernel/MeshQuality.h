// SPDX-License-Identifier: BSD-3-Clause
// MeshQuality: the anisotropic mesh quality measures of paper §5.2 (plus the UGAWG
// unit-edge-length ratio), VTK-free.
#ifndef av_MeshQuality_h
#define av_MeshQuality_h

#include "SimplexMesh.h"

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{

/// Summary numbers of paper §5.2 (the columns of Tab. 3 / Tab. 5) and the UGAWG edge ratio.
struct MeshQualitySummary
{
  std::size_t NumCells = 0;
  double GMin = 0.0;     ///< smallest cell quality G (0 = degenerate, 1 = regular)
  double GAvg = 0.0;     ///< mean of G over all cells
  double ThetaMin = 0.0; ///< smallest min-angle (triangles) / min-dihedral (tets), degrees
  double ThetaAvg = 0.0; ///< mean of the per-cell min angles, degrees
  double BadAngleThreshold = 0.0; ///< 30 deg for triangles, 15 deg for tets
  std::size_t NumBad = 0;         ///< cells whose min angle < BadAngleThreshold
  double PercentBad = 0.0;        ///< 100 * NumBad / NumCells
  std::size_t NumInverted = 0;    ///< cells with signed measure <= 0 in input space
  std::size_t NumEdges = 0;       ///< unique edges
  /// Median of the metric edge lengths before normalization (the global scale removed).
  double MedianEdgeLength = 0.0;
  /// % of unique edges with normalized metric length in [1/sqrt2, sqrt2] (UGAWG range).
  double PercentEdgesInUnitRange = 0.0;
  double HistogramBinWidth = 5.0;           ///< degrees
  std::vector<std::size_t> AngleHistogram;  ///< counts of per-cell min angles, bins [0,90)
};

/// Per-cell measures (arrays of NumCells) and the summary.
struct MeshQualityResult
{
  MeshQualitySummary Summary;
  std::vector<double> G;                ///< quality G per cell after the metric mapping
  std::vector<double> MinAngle;         ///< min angle / min dihedral angle per cell, degrees
  std::vector<std::uint8_t> Inverted;   ///< 1 where the signed measure in input space <= 0
  std::vector<double> EdgeLengths;      ///< normalized metric length per unique edge
  std::vector<std::int32_t> Edges;      ///< unique edges, 2 point ids each (sorted pairs)
};

/**
 * Evaluates an output mesh (triangles or tets, in input space) against the metric given at
 * its vertices (paper §5.2). Each cell is mapped by A = (sum_i M_i^{1/2}) / (k+1): the
 * average of the per-vertex symmetric square roots of the metric (not the square root of the
 * averaged metric), then
 *   triangles: G = 2 sqrt3 S / (p h), theta = smallest angle, bad if theta < 30 deg;
 *   tets:      G = 12 (9 V^2)^{1/3} / sum l^2, theta = smallest dihedral, bad if < 15 deg.
 * Inverted: signed area (2D input) / signed volume (tets) <= 0 with the stored vertex order;
 * for triangles on a 3D surface there is no reference orientation and only zero-area
 * triangles are counted. Edge lengths use Q_ab = (A_a + A_b)/2 as in §5.1 and are divided by
 * their median (the metric's absolute scale is arbitrary after the global scaling c) before
 * the [1/sqrt2, sqrt2] test. Metric entries follow the MetricField 6-component order; for a
 * 2D mesh only XX, YY, XY are used. Negative eigenvalues are clamped to 0.
 * Throws InputError on wrong sizes, bad ids, NaN or an empty mesh.
 */
MeshQualityResult EvaluateMeshQuality(const SimplexMesh& mesh, const MetricField& metric);

/**
 * Quality G of simplices whose vertices are given in R^dim, e.g. the dual mesh's cells with the
 * sites' embedded coordinates: triangles 2 sqrt3 S / (p h), tets 12 (9 V^2)^{1/3} / sum l^2, as
 * in EvaluateMeshQuality but with no metric (area / volume from the Gram matrix of the edge
 * vectors, any dim >= simplexDim). The gap to EvaluateMeshQuality's G is what the embedding's
 * departure from the metric costs at the scale of the output cells.
 * `cells` holds (simplexDim + 1) point ids per cell, `coords` numPoints x dim values.
 * Throws InputError on a bad simplexDim (2 or 3), dim < simplexDim, wrong sizes, bad ids or
 * non-finite coordinates.
 */
std::vector<double> SimplexQualityInEmbedding(const std::vector<std::int32_t>& cells,
  int simplexDim, const std::vector<double>& coords, int dim);

/**
 * The metric at each site: barycentric interpolation of the per-vertex metric of `mesh`
 * (the mesh the sites live on, e.g. the input mesh of the sampler) in the site's cell. On a
 * surface with rank-2 vertex metrics each is first moved into the cell's plane
 * (MoveSurfaceMetric), so the result is rank 2 in that plane.
 * Throws InputError on wrong sizes or cell ids.
 */
MetricField InterpolateMetricAtSites(
  const SimplexMesh& mesh, const MetricField& metric, const SiteSet& sites);

/// The metric (6 packed values) at barycentric `lambda` of `cell`, as InterpolateMetricAtSites;
/// `normals`: SurfaceMetricNormals(metric) on a surface, empty otherwise. No checks.
void InterpolateMetricInCell(const SimplexMesh& mesh,
  const MetricField& metric,
  const std::vector<Eigen::Vector3d>& normals,
  std::int32_t cell,
  const double* lambda,
  double* out);

} // namespace av

#endif
