// SPDX-License-Identifier: BSD-3-Clause
// EdgeLengthError: the paper's §5.1 embedding quality measure (relative edge length error).
#ifndef av_EdgeLengthError_h
#define av_EdgeLengthError_h

#include "SimplexMesh.h"

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
