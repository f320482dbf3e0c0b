// SPDX-License-Identifier: BSD-3-Clause
// SimplexStarMesh: the working copy of a mesh that TetMeshImprover (K = 3) and
// TriangleMeshImprover (K = 2) change: points, metric square roots, simplices (a removed one
// keeps its id, all kDead) and, per vertex, its star (the alive simplices on it).
#ifndef av_SimplexStarMesh_h
#define av_SimplexStarMesh_h

#include "MetricAlgebra.h" // MoveSurfaceMetric, SurfaceEdgeMetricLength2
#include "MetricSimplexQuality.h"
#include "SimplexMesh.h"

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

namespace av
{

template <int K>
class SimplexStarMesh
{
public:
  static_assert(K == 2 || K == 3, "triangles (2D or surfaces) or tets");
  using Simplex = std::array<std::int32_t, K + 1>;
  static constexpr std::int32_t kDead = -1;

  /// Copies the points (z = 0 in 2D) and cells of `mesh`; `sqrtMetrics`: one symmetric square
  /// root per point (2D: the 2x2 one padded with zeros); `fixed`: per point, nonzero = never
  /// moves. K = 2: every normal starts as +z.
  SimplexStarMesh(const SimplexMesh& mesh,
    std::vector<Eigen::Matrix3d> sqrtMetrics,
    const std::vector<std::uint8_t>* fixed);

  /// The metric quality (MetricSimplexQuality.h); triangles are oriented by their normals, and
  /// each vertex's (rank-2, normal Normals[v]) metric is moved into the triangle's plane first
  /// (MoveSurfaceMetric: a no-op in 2D).
  double Quality(const Simplex& t) const
  {
    if constexpr (K == 3)
      return TetQuality(Mapped(t));
    else
      return TriangleQuality(Mapped(t));
  }
  /// The §5.2 shape measure G of simplex t in the metric, mapped as Quality maps it
  /// (MetricSimplexQuality.h: TetMeanRatio, TriangleMeanRatio).
  double MeanRatio(const Simplex& t) const
  {
    if constexpr (K == 3)
      return TetMeanRatio(Mapped(t));
    else
      return TriangleMeanRatio(Mapped(t));
  }
  bool IsAlive(std::int32_t t) const { return Simplices[t][0] != kDead; }
  bool CanMove(std::int32_t v) const { return !Fixed[v] && !Stars[v].empty(); }
  double WorstQuality() const;            ///< over the alive simplices; +inf if none
  double StarWorst(std::int32_t v) const; ///< over v's star; +inf if empty
  double StarMeanRatio(std::int32_t v) const; ///< mean MeanRatio over v's star; 0 if empty
  /// StarMeanRatio and StarWorst in one pass (each simplex mapped once).
  void StarMeanAndWorst(std::int32_t v, double& mean, double& worst) const;
  /// Splits `vertices` into classes of which no two members share a simplex (greedy, in the
  /// given order): the members of one class can move at the same time.
  std::vector<std::vector<std::int32_t>> IndependentClasses(
    const std::vector<std::int32_t>& vertices) const;
  /// The first simplex of v's non-empty star with its worst quality.
  std::int32_t WorstInStar(std::int32_t v) const;
  /// §5.1 edge length: Q_ab = (S_a + S_b) / 2; triangles: each S moved so that the edge lies in
  /// its tangent plane (SurfaceEdgeMetricLength2; the same in 2D).
  double EdgeLength(std::int32_t a, std::int32_t b) const
  {
    if constexpr (K == 3)
      return (0.5 * (SqrtMetrics[a] + SqrtMetrics[b]) * (Points[b] - Points[a])).norm();
    else
      return std::sqrt(SurfaceEdgeMetricLength2(
        Points[b] - Points[a], SqrtMetrics[a], Normals[a], SqrtMetrics[b], Normals[b]));
  }
  bool HasEdge(std::int32_t a, std::int32_t b) const;
  static int IndexIn(const Simplex& t, std::int32_t v); ///< position of v in t, -1 if none

  std::int32_t Add(const Simplex& t); ///< appends an alive simplex to the stars, returns its id
  void Kill(std::int32_t id);         ///< off the stars; the id stays, dead
  /// Undoes Kill(id): simplex t (what id held) is alive again under its old id.
  void Revive(std::int32_t id, const Simplex& t);
  /// Drops the simplices from id `count` on; they must all be dead (the tail of a tried
  /// operation that was undone).
  void TruncateDead(std::size_t count);
  /// Appends a free point with metric square root `s` and an empty star; returns its id.
  std::int32_t AddPoint(const Eigen::Vector3d& x, const Eigen::Matrix3d& s);
  /// Drops the last point; its star must be empty.
  void RemoveLastPoint();

  /// Up to `maxPasses` passes; each calls `improve` on the alive simplices below `target`,
  /// worst first (ties by id), and a pass in which none returns true is the last. Returns the
  /// number of passes.
  int ImproveWorstFirst(double target,
    int maxPasses,
    const std::function<bool(std::int32_t)>& improve);

  /// Writes the alive simplices (by id) and the moved points into `mesh`, resized to them.
  void WriteBack(SimplexMesh& mesh) const;

  /// Simplex t mapped as Quality describes: a MappedTet, or a MappedTriangle.
  auto Mapped(const Simplex& t) const
  {
    const auto& p = Points;
    const auto& s = SqrtMetrics;
    if constexpr (K == 3)
      return MappedTet(p[t[0]], p[t[1]], p[t[2]], p[t[3]], s[t[0]], s[t[1]], s[t[2]], s[t[3]]);
    else
    {
      const Eigen::Vector3d n = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]);
      const double len = n.norm();
      auto moved = [&](int i) -> Eigen::Matrix3d
      { return len > 0.0 ? MoveSurfaceMetric(s[t[i]], Normals[t[i]], n / len) : s[t[i]]; };
      return MappedTriangle(p[t[0]],
        p[t[1]],
        p[t[2]],
        moved(0),
        moved(1),
        moved(2),
        Normals[t[0]] + Normals[t[1]] + Normals[t[2]]);
    }
  }

  // The arrays themselves: the improvers' undo journals save and restore them directly.
  std::vector<Eigen::Vector3d> Points;
  std::vector<Eigen::Matrix3d> SqrtMetrics;
  std::vector<Eigen::Vector3d> Normals; ///< K = 2: unit domain normals (2D: +z); K = 3: none
  std::vector<Simplex> Simplices;
  std::vector<std::vector<std::int32_t>> Stars; ///< vertex -> alive simplices
  std::vector<char> Fixed;
  std::vector<std::uint8_t> Moved; ///< per point, 1 once a move of it was committed
};

extern template class SimplexStarMesh<2>;
extern template class SimplexStarMesh<3>;

} // namespace av

#endif
