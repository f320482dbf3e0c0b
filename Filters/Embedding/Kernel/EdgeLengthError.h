// SPDX-License-Identifier: BSD-3-Clause
// EdgeLengthError: the paper's §5.1 embedding quality measure (relative edge length error).
#ifndef av_EdgeLengthError_h
#define av_EdgeLengthError_h

#include "MetricAlgebra.h" // MoveSurfaceMetric
#include "SimplexMesh.h"

#include <Eigen/Dense>

#include <cstdint>
#include <vector>

namespace av
{

/// Summary of the relative edge length errors (percent), optionally per edge / per cell.
struct EdgeLengthErrorResult
{
  double AveragePercent = 0.0; ///< L_avg: mean over unique edges of |l_emb - l| / l, in %
  double MaxPercent = 0.0;     ///< L_max, in %
  std::size_t NumEdges = 0;
  std::vector<std::int32_t> Edges;   ///< (a, b) pairs, only when per-edge output was asked
  std::vector<double> EdgePercent;   ///< error of each edge in %, same order as Edges
  std::vector<double> CellMaxPercent; ///< largest error over the edges of each cell, in %
};

/// The §5.1 A of every vertex: the symmetric square root of its metric (zero-padded to 3 x 3
/// for 2D domains, ambientDim 2). Parallel.
std::vector<Eigen::Matrix3d> VertexMetricRoots(const MetricField& metric, int ambientDim);

/// The squared §5.1 metric length |(A_a + A_b) / 2 (b − a)|² of the edge (a, b).
inline double MetricEdgeLength2(
  const SimplexMesh& mesh, const std::vector<Eigen::Matrix3d>& roots, std::int32_t a, std::int32_t b)
{
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  for (int k = 0; k < mesh.AmbientDim; ++k)
  {
    d(k) = mesh.Point(b)[k] - mesh.Point(a)[k];
  }
  return (0.5 * (roots[a] + roots[b]) * d).squaredNorm();
}

/// The same on a surface whose vertex metrics are rank 2 with normals `normals`
/// (SurfaceMetricNormals; 0 = full rank): each A is first moved by the smallest rotation that puts
/// the edge into its tangent plane, so that an edge along a vertex normal (a thin CAD rim) is
/// measured with that vertex's tangent lengths instead of getting almost none.
inline double SurfaceMetricEdgeLength2(const SimplexMesh& mesh,
  const std::vector<Eigen::Matrix3d>& roots,
  const std::vector<Eigen::Vector3d>& normals,
  std::int32_t a,
  std::int32_t b)
{
  const Eigen::Vector3d d = Eigen::Map<const Eigen::Vector3d>(mesh.Point(b)) -
    Eigen::Map<const Eigen::Vector3d>(mesh.Point(a));
  return SurfaceEdgeMetricLength2(d, roots[a], normals[a], roots[b], normals[b]);
}

/**
 * Precomputes the unique edges of a mesh and their metric lengths l_ab = |Q_ab (v_b - v_a)|,
 * Q_ab = (A(v_a) + A(v_b)) / 2, A the symmetric square root of the vertex metric (paper §5.1),
 * so that the error of many embeddings of the same mesh (e.g. one per solver iteration) is cheap.
 */
class EdgeLengthErrorEvaluator
{
public:
  /// Throws InputError on size mismatch or when an edge has zero metric length.
  EdgeLengthErrorEvaluator(const SimplexMesh& mesh, const MetricField& metric);

  /// Errors of an embedding of the same mesh (Embedding.NumPoints() must match). Parallel.
  EdgeLengthErrorResult Evaluate(const Embedding& embedding, bool perEdge = false, bool perCell = false) const;

  std::size_t NumEdges() const { return this->MetricLength.size(); }

private:
  const SimplexMesh* Mesh;
  std::vector<std::int32_t> Edges;
  std::vector<double> MetricLength;
};

/// One-shot convenience: L_avg / L_max (and per-cell maxima) of an embedding.
EdgeLengthErrorResult ComputeEdgeLengthError(const SimplexMesh& mesh, const MetricField& metric,
  const Embedding& embedding, bool perEdge = false, bool perCell = false);

} // namespace av

#endif
