// SPDX-License-Identifier: BSD-3-Clause
// TriangleMeshImprover: the planar-triangle half of ImproveMesh (2-2 edge flips, smoothing) on a
// mutable triangle list with vertex-to-triangle stars.
#ifndef av_TriangleMeshImprover_h
#define av_TriangleMeshImprover_h

#include "MeshImprovement.h"

#include <Eigen/Dense>

#include <array>
#include <vector>

namespace av
{

class TriangleMeshImprover
{
public:
  /// `sqrtMetrics`: one symmetric square root per point; `fixed`: per point, nonzero = never moves.
  TriangleMeshImprover(SimplexMesh& mesh,
    std::vector<Eigen::Matrix2d> sqrtMetrics,
    const std::vector<std::uint8_t>* fixed,
    const MeshImprovementOptions& options);

  /// Runs the passes, writes the triangles and points back into the mesh, fills the counts.
  void Run(MeshImprovementResult& result);

private:
  using Tri = std::array<std::int32_t, 3>;

  double Quality(const Tri& t) const;
  double WorstQuality() const;
  double StarWorst(std::int32_t v) const;
  void MarkBoundaryAndNonManifold();
  bool HasEdge(std::int32_t a, std::int32_t b) const;
  bool TryFlip(std::int32_t tri, int edge);
  bool TrySmooth(std::int32_t v);
  bool Improve(std::int32_t tri);
  bool Accepts(double after, double before) const;

  SimplexMesh& Mesh;
  std::vector<Eigen::Vector2d> P;
  std::vector<Eigen::Matrix2d> S;
  std::vector<Tri> Tris; // triangles stay in place: a flip rewrites the two it touches
  std::vector<std::vector<std::int32_t>> Star;
  std::vector<char> Fixed;
  MeshImprovementOptions Options;
  std::vector<std::uint8_t> Moved;
  std::size_t Flips = 0, Smoothed = 0;
};

} // namespace av

#endif
