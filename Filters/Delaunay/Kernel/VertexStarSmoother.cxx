// SPDX-License-Identifier: BSD-3-Clause
#include "VertexStarSmoother.h"

#include "MetricSimplexQuality.h"

#include <algorithm>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <cmath>
#include <limits>
#include <utility>

namespace av
{
namespace
{
constexpr double Pi = 3.14159265358979323846;

/// Two unit vectors orthogonal to n (and to each other): the plane a vertex moves in.
void TangentBasis(const Eigen::Vector3d& n, Eigen::Vector3d& t1, Eigen::Vector3d& t2)
{
  Eigen::Index axis = 0;
  n.cwiseAbs().minCoeff(&axis);
  t1 = Eigen::Vector3d::Unit(axis).cross(n).normalized();
  t2 = n.cross(t1).normalized();
}
} // namespace

template <int K>
VertexStarSmoother<K>::VertexStarSmoother(SimplexStarMesh<K>& mesh,
  const MeshImprovementOptions& options,
  bool requireMove,
  PlaceVertex place,
  EdgeCount outOfRangeEdges)
  : Mesh(mesh)
  , Options(options)
  , RequireMove(requireMove)
  , Place(std::move(place))
  , OutOfRangeEdges(std::move(outOfRangeEdges))
{
}

template <int K>
typename VertexStarSmoother<K>::VertexState VertexStarSmoother<K>::Save(std::int32_t v) const
{
  VertexState s{ Mesh.Points[v], Eigen::Vector3d::Zero(), Mesh.SqrtMetrics[v] };
  if constexpr (K == 2)
    s.Normal = Mesh.Normals[v];
  return s;
}

template <int K>
void VertexStarSmoother<K>::Restore(std::int32_t v, const VertexState& state)
{
  Mesh.Points[v] = state.Point;
  Mesh.SqrtMetrics[v] = state.SqrtMetric;
  if constexpr (K == 2)
    Mesh.Normals[v] = state.Normal;
}

// Central differences of the worst simplex's quality. Tets move freely (along the axes);
// triangles in the domain's tangent plane at v (2D: the plane itself). The two probe
// formulas are the ones each copy had: their rounding differs.
template <int K>
Eigen::Vector3d VertexStarSmoother<K>::WorstGradient(std::int32_t v, double h)
{
  const auto& worst = Mesh.Simplices[Mesh.WorstInStar(v)];
  Eigen::Vector3d& p = Mesh.Points[v];
  const Eigen::Vector3d here = p;
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  if constexpr (K == 3)
    for (int k = 0; k < 3; ++k)
    {
      p = here;
      p[k] += h;
      const double qp = Mesh.Quality(worst);
      p[k] -= 2.0 * h;
      const double qm = Mesh.Quality(worst);
      g[k] = (qp - qm) / (2.0 * h);
    }
  else
  {
    Eigen::Vector3d t[2];
    TangentBasis(Mesh.Normals[v], t[0], t[1]);
    for (int k = 0; k < 2; ++k)
    {
      p = here + h * t[k];
      const double qp = Mesh.Quality(worst);
      p = here - h * t[k];
      const double qm = Mesh.Quality(worst);
      g += (qp - qm) / (2.0 * h) * t[k];
    }
  }
  p = here;
  return g;
}

template <int K>
double VertexStarSmoother<K>::StarScale(std::int32_t v) const
{
  double scale = std::numeric_limits<double>::infinity();
  for (std::int32_t t : Mesh.Stars[v])
    for (std::int32_t w : Mesh.Simplices[t])
      if (w != v)
        scale = std::min(scale, (Mesh.Points[w] - Mesh.Points[v]).norm());
  return scale;
}

template <int K>
template <typename Accept>
bool VertexStarSmoother<K>::LineSearch(
  std::int32_t v, const Eigen::Vector3d& g, double first, double last, Accept&& accept)
{
  const double gn = g.norm();
  if (!(gn > 0.0) || !std::isfinite(gn))
    return false;
  const VertexState here = Save(v);
  for (double alpha = first; alpha > last; alpha *= 0.5)
  {
    const Eigen::Vector3d x = here.Point + (alpha / gn) * g;
    bool placed = true;
    if (Place)
      placed = Place(v, x);
    else
      Mesh.Points[v] = x;
    if (placed && accept())
      return true;
    Restore(v, here);
  }
  return false;
}

template <int K>
bool VertexStarSmoother<K>::Commit(
  std::int32_t v, const VertexState& start, bool accept, bool deferCommit)
{
  if (!accept ||
    (!deferCommit && Options.AcceptMove && !Options.AcceptMove(v, Mesh.Points[v].data())))
  {
    Restore(v, start);
    return false;
  }
  if (!deferCommit)
    Mesh.Moved[v] = 1;
  return true;
}

// Steepest ascent of the worst simplex of v's star, with a halving line search; a step is
// kept only if the star's worst rises (and the edge rule holds).
template <int K>
bool VertexStarSmoother<K>::TrySmooth(std::int32_t v, bool deferCommit)
{
  if (!Mesh.CanMove(v))
    return false;
  const VertexState start = Save(v);
  const double scale = StarScale(v); // steps are scaled by the shortest edge of the star
  const double before = Mesh.StarWorst(v);
  double current = before;
  const int outBefore = OutOfRangeEdges ? OutOfRangeEdges(v) : 0;
  for (int iter = 0; iter < 8; ++iter)
  {
    Eigen::Vector3d g = WorstGradient(v, 1e-6 * scale);
    if (Filter)
      Filter(v, g);
    const bool stepped = LineSearch(v, g, 0.2 * scale, 1e-4 * scale,
      [&]
      {
        const double q = Mesh.StarWorst(v);
        if (!(q > current + 1e-12 && (!OutOfRangeEdges || OutOfRangeEdges(v) <= outBefore)))
          return false;
        current = q;
        return true;
      });
    if (!stepped)
      break;
  }
  const bool unmoved = Mesh.Points[v] == start.Point;
  const bool accept = AcceptsImprovement(current, before, Options.AcceptWorsening) &&
    !(RequireMove && Options.AcceptWorsening && unmoved);
  return Commit(v, start, accept, deferCommit);
}

template <int K>
template <typename F>
Eigen::Vector3d VertexStarSmoother<K>::Gradient(std::int32_t v, double h, F&& f)
{
  Eigen::Vector3d& p = Mesh.Points[v];
  const Eigen::Vector3d here = p;
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  Eigen::Vector3d t[3] = { Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
    Eigen::Vector3d::UnitZ() };
  int dirs = 3;
  if constexpr (K == 2)
  {
    TangentBasis(Mesh.Normals[v], t[0], t[1]);
    dirs = 2;
  }
  for (int k = 0; k < dirs; ++k)
  {
    p = here + h * t[k];
    const double qp = f();
    p = here - h * t[k];
    const double qm = f();
    g += (qp - qm) / (2.0 * h) * t[k];
  }
  p = here;
  return g;
}

template <int K>
Eigen::Vector3d VertexStarSmoother<K>::MeanGradient(std::int32_t v, double h)
{
  return Gradient(v, h, [&] { return Mesh.StarMeanRatio(v); });
}

// Steepest ascent of the star's mean G with a halving line search. A step must raise the mean,
// keep the star's worst quality above its floor and keep the edge rule. Where the floor blocks
// the ascent, the direction is turned to leave the worst simplex's quality unchanged to first
// order (plus a tenth of its own ascent), which lets the vertex slide along the constraint.
template <int K>
bool VertexStarSmoother<K>::TryMeanSmooth(std::int32_t v, double floor, bool deferCommit)
{
  if (!Mesh.CanMove(v))
    return false;
  const VertexState start = Save(v);
  const double scale = StarScale(v);
  const double worstBefore = Mesh.StarWorst(v);
  if (!(worstBefore > kMinImprovementQuality))
    return false; // an inverted or flat star is the worst-first passes' business
  const double meanBefore = Mesh.StarMeanRatio(v);
  // (AcceptWorsening, the test hook: no floor, so the tests can show they would see one.)
  const double floorWorst =
    Options.AcceptWorsening ? -std::numeric_limits<double>::infinity() : std::min(worstBefore, floor);
  double current = meanBefore;
  const int outBefore = OutOfRangeEdges ? OutOfRangeEdges(v) : 0;
  auto accept = [&]
  {
    double q = 0.0, worst = 0.0;
    Mesh.StarMeanAndWorst(v, q, worst);
    if (!(q > current + 1e-12 && worst >= floorWorst &&
          (!OutOfRangeEdges || OutOfRangeEdges(v) <= outBefore)))
      return false;
    current = q;
    return true;
  };
  for (int iter = 0; iter < 4; ++iter)
  {
    Eigen::Vector3d g = MeanGradient(v, 1e-6 * scale);
    if (Filter)
      Filter(v, g);
    if (LineSearch(v, g, 0.1 * scale, 1e-2 * scale, accept))
      continue;
    // Blocked, usually by the worst simplex at the floor: the part of g that leaves the worst
    // simplex's quality unchanged to first order.
    Eigen::Vector3d w = WorstGradient(v, 1e-6 * scale);
    if (Filter)
      Filter(v, w);
    const double ww = w.squaredNorm();
    if (!(ww > 0.0) || g.dot(w) >= 0.0)
      break;
    const Eigen::Vector3d slide =
      g - (g.dot(w) / ww) * w + 0.1 * std::sqrt(g.squaredNorm() / ww) * w;
    if (!LineSearch(v, slide, 0.1 * scale, 1e-2 * scale, accept))
      break;
  }
  return Commit(v, start, current > meanBefore + 1e-9, deferCommit);
}

template <int K>
double VertexStarSmoother<K>::MeanSmoothingFloor() const
{
  return std::max(Mesh.WorstQuality(), std::sin(Options.TargetAngle * Pi / 180.0));
}

template <int K>
std::size_t VertexStarSmoother<K>::MeanSmoothingSweeps(const std::vector<std::int32_t>& vertices)
{
  if (vertices.empty() || Options.MeanSmoothingSweeps <= 0)
    return 0;
  const double floor = MeanSmoothingFloor();
  const std::vector<std::vector<std::int32_t>> classes = Mesh.IndependentClasses(vertices);
  std::vector<char> moved(Mesh.Points.size(), 0);
  std::size_t total = 0;
  for (int sweep = 0; sweep < Options.MeanSmoothingSweeps; ++sweep)
  {
    std::fill(moved.begin(), moved.end(), 0);
    for (const std::vector<std::int32_t>& members : classes)
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, members.size(), 16),
        [&](const tbb::blocked_range<std::size_t>& r)
        {
          for (std::size_t i = r.begin(); i != r.end(); ++i)
            moved[members[i]] = TryMeanSmooth(members[i], floor) ? 1 : 0;
        });
    const std::size_t count = static_cast<std::size_t>(std::count(moved.begin(), moved.end(), 1));
    total += count;
    if (count == 0)
      break;
  }
  return total;
}

template class VertexStarSmoother<2>;
template class VertexStarSmoother<3>;

} // namespace av
