// SPDX-License-Identifier: BSD-3-Clause
// VertexStarSmoother: the vertex move of mesh improvement, shared by tets and triangles:
// steepest ascent of the worst simplex of a vertex's star with a halving line search.
#ifndef av_VertexStarSmoother_h
#define av_VertexStarSmoother_h

#include "MeshImprovement.h"
#include "SimplexStarMesh.h"

#include <Eigen/Dense>

#include <cstdint>
#include <functional>

namespace av
{

template <int K>
class VertexStarSmoother
{
public:
  /// Puts vertex v at (or, on a surface, near) x, with what goes with it there (normal,
  /// metric); false if there is no such point. Empty: the point is just set to x.
  using PlaceVertex = std::function<bool(std::int32_t v, const Eigen::Vector3d& x)>;
  /// The number of out-of-range edges around a vertex; a step may not raise it. Empty: none.
  using EdgeCount = std::function<int(std::int32_t v)>;

  /// `requireMove`: under the AcceptWorsening test hook, an ascent that ends where it started
  /// is refused (the tets always did this, the triangles never).
  VertexStarSmoother(SimplexStarMesh<K>& mesh,
    const MeshImprovementOptions& options,
    bool requireMove,
    PlaceVertex place = PlaceVertex(),
    EdgeCount outOfRangeEdges = EdgeCount());

  /// Moves free vertex v if that raises the worst quality of its star (AcceptsImprovement),
  /// else leaves it where it was and returns false. Unless `deferCommit` (a journal asks later),
  /// Options.AcceptMove must agree too and v is marked moved.
  bool TrySmooth(std::int32_t v, bool deferCommit);

  /// Moves free vertex v if that raises the mean §5.2 shape measure G of its star
  /// (SimplexStarMesh::MeanRatio) while its worst quality (Quality) stays at least
  /// min(where it was, `floor`) and no more of its edges leave the range; else leaves it and
  /// returns false. Unless `deferCommit` (the caller decides), Options.AcceptMove must agree
  /// and v is marked moved. The optional Place and direction filter apply as in TrySmooth.
  /// Reads and writes only v and reads its star, so vertices that share no simplex may be
  /// smoothed at the same time.
  bool TryMeanSmooth(std::int32_t v, double floor, bool deferCommit = false);

  /// The floor of the mean-quality sweeps: the mesh's worst quality, or the sine of
  /// TargetAngle if higher.
  double MeanSmoothingFloor() const;

  /// MeshImprovementOptions::MeanSmoothingSweeps over `vertices`: the floor is the mesh's worst
  /// quality, or the sine of TargetAngle if higher (the sweeps never lower the worst element,
  /// and above the target the elements may trade); each sweep smooths the IndependentClasses
  /// one after the other, each in parallel (the result does not depend on the thread count).
  /// Returns the moves.
  std::size_t MeanSmoothingSweeps(const std::vector<std::int32_t>& vertices);

  /// Optional: restricts a search direction at v in place (tets on a planar boundary patch:
  /// its projection on the plane), so that the ascent is not spent on the normal component
  /// that Place would undo.
  using Direction = std::function<void(std::int32_t v, Eigen::Vector3d& g)>;
  void SetDirectionFilter(Direction filter) { this->Filter = std::move(filter); }

private:
  struct VertexState
  {
    Eigen::Vector3d Point, Normal;
    Eigen::Matrix3d SqrtMetric;
  };
  VertexState Save(std::int32_t v) const;
  void Restore(std::int32_t v, const VertexState& state);
  Eigen::Vector3d WorstGradient(std::int32_t v, double h); ///< of the star's worst simplex
  Eigen::Vector3d MeanGradient(std::int32_t v, double h);  ///< of the star's mean G
  double StarScale(std::int32_t v) const; ///< shortest edge from v in its star: the step unit
  /// Halving line search along g from v's position, steps from `first` down to `last`: the
  /// first placed point that `accept` takes is kept (true), else v is restored (false).
  template <typename Accept>
  bool LineSearch(
    std::int32_t v, const Eigen::Vector3d& g, double first, double last, Accept&& accept);
  /// Keeps v's move if `accept` and (unless deferCommit) Options.AcceptMove agree, marking it
  /// moved; else restores `start`.
  bool Commit(std::int32_t v, const VertexState& start, bool accept, bool deferCommit);
  /// Central differences of f at v: along the axes (tets), in v's tangent plane (triangles).
  template <typename F>
  Eigen::Vector3d Gradient(std::int32_t v, double h, F&& f);

  SimplexStarMesh<K>& Mesh;
  const MeshImprovementOptions& Options;
  bool RequireMove;
  PlaceVertex Place;
  EdgeCount OutOfRangeEdges;
  Direction Filter;
};

extern template class VertexStarSmoother<2>;
extern template class VertexStarSmoother<3>;

} // namespace av

#endif
