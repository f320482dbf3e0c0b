// SPDX-License-Identifier: BSD-3-Clause
#include "TetMeshImprover.h"

#include "MetricAlgebra.h"
#include "MetricSimplexQuality.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace av
{
namespace
{
constexpr double Pi = 3.14159265358979323846;
constexpr char kMaxSnapTrials = 8;

// Index orders that put vertex m last by an even permutation: the face opposite m, in this
// order, is counterclockwise seen from m in a positive tet.
constexpr int FaceOpposite[4][3] = { { 1, 3, 2 }, { 0, 2, 3 }, { 0, 3, 1 }, { 0, 1, 2 } };

bool IsEvenPermutation(const int* idx) // positions of 4 distinct values 0..3
{
  int inversions = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      inversions += idx[i] > idx[j] ? 1 : 0;
  return inversions % 2 == 0;
}

constexpr auto IndexIn = &SimplexStarMesh<3>::IndexIn;
} // namespace

TetMeshImprover::TetMeshImprover(SimplexMesh& mesh,
  std::vector<Eigen::Matrix3d> sqrtMetrics,
  const std::vector<std::uint8_t>* fixed,
  const MeshImprovementOptions& options)
  : Mesh(mesh)
  , Options(options)
  , Work(mesh, std::move(sqrtMetrics), fixed)
  , P(Work.Points)
  , Tets(Work.Simplices)
  , Star(Work.Stars)
  // Only the tets keep the edge-length rule and refuse an ascent that ends where it began.
  , Smoother(
      Work,
      Options,
      true,
      // A vertex of a planar boundary patch stays in its plane (exactly, up to rounding).
      [this](std::int32_t v, const Eigen::Vector3d& x)
      {
        const Eigen::Vector3d& t = LineDirection[v];
        if (t.squaredNorm() > 0.0)
        {
          Work.Points[v] += t * t.dot(x - Work.Points[v]);
          return true;
        }
        const Eigen::Vector3d& n = PlaneNormal[v];
        const Eigen::Vector3d inPlane = x - n * n.dot(x - Work.Points[v]);
        if (!Curved[v])
        {
          Work.Points[v] = inPlane;
          return true;
        }
        Eigen::Vector3d placed;
        if (!Options.ProjectToBoundary(v, inPlane.data(), n.data(), placed.data(), nullptr))
          return false;
        Work.Points[v] = placed;
        return true;
      },
      Options.KeepEdgeLengths && !Options.AcceptWorsening
        ? VertexStarSmoother<3>::EdgeCount([this](std::int32_t v) { return OutOfRangeAround(v); })
        : VertexStarSmoother<3>::EdgeCount())
{
  PlaneNormal.assign(P.size(), Eigen::Vector3d::Zero());
  LineDirection.assign(P.size(), Eigen::Vector3d::Zero());
  Curved.assign(P.size(), 0);
  OffBoundary.assign(P.size(), 0);
  for (const Tet& t : Tets)
    MeshVolume += std::abs(Volume(t));
  MarkBoundaryAndNonManifold(fixed);
  if (Options.PlanarBoundary)
    Smoother.SetDirectionFilter(
      [this](std::int32_t v, Eigen::Vector3d& g)
      {
        const Eigen::Vector3d& t = LineDirection[v];
        if (t.squaredNorm() > 0.0)
          g = t * t.dot(g);
        else
          g -= PlaneNormal[v] * PlaneNormal[v].dot(g);
      });
  if (Options.KeepEdgeLengths)
    ComputeMedianEdgeLength();
}

void TetMeshImprover::ComputeMedianEdgeLength()
{
  std::vector<std::pair<std::int32_t, std::int32_t>> edges;
  edges.reserve(Tets.size() * 6);
  for (const Tet& t : Tets)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        edges.emplace_back(std::min(t[i], t[j]), std::max(t[i], t[j]));
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<double> lengths(edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e)
  {
    const auto [a, b] = edges[e];
    lengths[e] = Work.EdgeLength(a, b);
  }
  if (lengths.empty())
    return;
  std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
  MedianEdge = lengths[lengths.size() / 2];
}

// The §5.1 edge length (Q_ab = (S_a + S_b) / 2) against the UGAWG range around the median.
bool TetMeshImprover::OutOfRange(std::int32_t a, std::int32_t b) const
{
  if (!(MedianEdge > 0.0) || EdgeRuleWaived)
    return false;
  const double l = Work.EdgeLength(a, b) / MedianEdge;
  return l < std::sqrt(0.5) || l > std::sqrt(2.0);
}

int TetMeshImprover::OutOfRangeAround(std::int32_t v) const
{
  int n = 0;
  for (std::int32_t t : Star[v])
    for (std::int32_t w : Tets[t])
      if (w != v)
        n += OutOfRange(v, w) ? 1 : 0;
  return n;
}

// Vertices on faces of one tet (the boundary) or of more than two (non-manifold) never move:
// that keeps the domain and leaves configurations the flips do not understand alone. The
// exceptions (PlanarBoundary) are a vertex inside a planar or smooth boundary patch, which
// moves in its (tangent) plane, and one on a straight crease, which slides along it.
void TetMeshImprover::MarkBoundaryAndNonManifold(const std::vector<std::uint8_t>* userFlags)
{
  std::vector<std::uint8_t> flags(P.size(), 0);
  for (std::size_t v = 0; v < P.size(); ++v)
    flags[v] = Work.Fixed[v] ? 1 : 0;
  if (userFlags)
    for (std::size_t v = 0; v < userFlags->size() && v < P.size(); ++v)
      flags[v] = (*userFlags)[v] == FeatureLinePoint ? FeatureLinePoint : flags[v];
  // Each face sorted (for matching) and in its tet's order, counterclockwise seen from the
  // opposite vertex, i.e. clockwise seen from outside.
  struct Face
  {
    std::array<std::int32_t, 3> Sorted, Ordered;
    bool operator<(const Face& o) const { return Sorted < o.Sorted; }
  };
  std::vector<Face> faces;
  faces.reserve(Tets.size() * 4);
  for (const Tet& t : Tets)
    for (int m = 0; m < 4; ++m)
    {
      Face f;
      f.Ordered = { t[FaceOpposite[m][0]], t[FaceOpposite[m][1]], t[FaceOpposite[m][2]] };
      f.Sorted = f.Ordered;
      std::sort(f.Sorted.begin(), f.Sorted.end());
      faces.push_back(f);
    }
  std::sort(faces.begin(), faces.end());
  std::vector<std::array<std::int32_t, 3>> boundary;
  std::vector<char> nonManifold(P.size(), 0);
  for (std::size_t i = 0; i < faces.size();)
  {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].Sorted == faces[i].Sorted)
      ++j;
    if (j - i != 2)
      for (std::int32_t v : faces[i].Sorted)
      {
        Work.Fixed[v] = 1;
        nonManifold[v] = j - i > 2 ? 1 : nonManifold[v];
      }
    if (j - i == 1)
      boundary.push_back(faces[i].Ordered);
    i = j;
  }
  if (!Options.PlanarBoundary)
    return;
  for (std::size_t v = 0; v < flags.size(); ++v)
    flags[v] = nonManifold[v] ? 1 : flags[v];
  FindMovableBoundaryVertices(boundary, flags);
}

void TetMeshImprover::FindMovableBoundaryVertices(
  const std::vector<std::array<std::int32_t, 3>>& boundary,
  const std::vector<std::uint8_t>& flags)
{
  // Boundary faces per vertex: the link edge (b, c) of face (v, b, c) in its order.
  std::vector<std::vector<std::pair<std::int32_t, std::int32_t>>> link(P.size());
  std::vector<Eigen::Vector3d> areaSum(P.size(), Eigen::Vector3d::Zero());
  for (const auto& f : boundary)
  {
    const Eigen::Vector3d n = (P[f[1]] - P[f[0]]).cross(P[f[2]] - P[f[0]]);
    for (int i = 0; i < 3; ++i)
    {
      link[f[i]].emplace_back(f[(i + 1) % 3], f[(i + 2) % 3]);
      areaSum[f[i]] += n;
    }
  }
  std::vector<std::size_t> order;
  for (std::size_t v = 0; v < P.size(); ++v)
  {
    const auto& edges = link[v];
    const bool onlyCrease = flags[v] == FeatureLinePoint;
    if (edges.size() < 3 || (flags[v] && !onlyCrease) || (onlyCrease && !Options.StraightCreases))
      continue;
    // One disc: following the link edges from the first closes a cycle through all of them.
    order.assign(1, 0);
    std::int32_t at = edges[0].second;
    while (order.size() <= edges.size())
    {
      std::size_t found = 0, next = 0;
      for (std::size_t e = 0; e < edges.size(); ++e)
        if (edges[e].first == at)
        {
          ++found;
          next = e;
        }
      if (found != 1 || next == 0)
        break;
      order.push_back(next);
      at = edges[next].second;
    }
    if (order.size() != edges.size() || at != edges[0].first)
    {
      // Not one disc: it may still be snapped onto the boundary.
      if (!flags[v] && areaSum[v].norm() > 0.0)
        ClassifyByDomainBoundary(
          static_cast<std::int32_t>(v), areaSum[v].normalized(), edges, false);
      continue;
    }
    if (Options.StraightCreases)
    {
      const Eigen::Vector3d t = CreaseDirection(static_cast<std::int32_t>(v), edges, order);
      if (t.squaredNorm() > 0.0)
      {
        LineDirection[v] = t;
        Work.Fixed[v] = 0;
        continue;
      }
    }
    if (onlyCrease || !(areaSum[v].norm() > 0.0))
      continue;
    // Coplanar: every link vertex within a tiny fraction of its distance from the plane.
    // Smooth: every face within BoundaryFlipMaxDihedral of that (mean) plane.
    const Eigen::Vector3d n = areaSum[v].normalized();
    const double cosMax = std::cos(Options.BoundaryFlipMaxDihedral * Pi / 180.0);
    bool planar = true, smooth = true;
    for (const auto& [b, c] : edges)
    {
      const Eigen::Vector3d d = P[b] - P[v];
      planar = planar && std::abs(n.dot(d)) <= 1e-10 * d.norm();
      const Eigen::Vector3d fn = d.cross(P[c] - P[v]);
      smooth = smooth && fn.norm() > 0.0 && fn.normalized().dot(n) >= cosMax;
    }
    const bool curved = !planar && smooth && static_cast<bool>(Options.ProjectToBoundary);
    if (!planar && !curved)
    {
      ClassifyByDomainBoundary(static_cast<std::int32_t>(v), n, edges, true);
      continue;
    }
    PlaneNormal[v] = n;
    Curved[v] = curved ? 1 : 0;
    Work.Fixed[v] = 0;
  }
}

void TetMeshImprover::ClassifyByDomainBoundary(std::int32_t v,
  const Eigen::Vector3d& meanNormal,
  const std::vector<std::pair<std::int32_t, std::int32_t>>& link,
  bool disc)
{
  if ((!Options.SnapToBoundary && !(Options.InputBoundaryMoves && disc)) ||
    !Options.ProjectToBoundary)
    return;
  Eigen::Vector3d placed, normal = meanNormal;
  if (!Options.ProjectToBoundary(v, P[v].data(), meanNormal.data(), placed.data(), normal.data()))
    return;
  double shortest = std::numeric_limits<double>::infinity();
  for (const auto& [b, c] : link)
    shortest = std::min(shortest, (P[b] - P[v]).norm());
  if (!(normal.norm() > 0.0))
    return;
  // On the boundary to rounding (a sampled boundary site): nothing to snap.
  if (!((placed - P[v]).norm() > 1e-9 * shortest))
  {
    if (Options.InputBoundaryMoves && disc)
    {
      // On the domain's boundary, its faces folded or chamfered: it moves on the domain's
      // boundary as a vertex of a curved patch, in the domain's tangent plane there.
      PlaneNormal[v] = normal.normalized();
      Curved[v] = 1;
      Work.Fixed[v] = 0;
    }
    return;
  }
  if (!Options.SnapToBoundary)
    return;
  // The surface's normal: the side of the boundary the snap's projection must find again.
  PlaneNormal[v] = normal.normalized();
  OffBoundary[v] = 1;
  Work.Fixed[v] = 0;
}

Eigen::Vector3d TetMeshImprover::CreaseDirection(std::int32_t v,
  const std::vector<std::pair<std::int32_t, std::int32_t>>& link,
  const std::vector<std::size_t>& order) const
{
  const Eigen::Vector3d none = Eigen::Vector3d::Zero();
  const std::size_t m = order.size();
  auto normal = [&](std::size_t k)
  {
    const auto& [b, c] = link[order[k % m]];
    return Eigen::Vector3d((P[b] - P[v]).cross(P[c] - P[v]));
  };
  // The fans' ends: consecutive faces that are not parallel (or fold back).
  std::size_t breaks[2] = { 0, 0 };
  int numBreaks = 0;
  for (std::size_t k = 0; k < m; ++k)
  {
    const Eigen::Vector3d n0 = normal(k), n1 = normal(k + 1);
    if (!(n0.norm() > 0.0) || !(n1.norm() > 0.0))
      return none;
    if (n0.dot(n1) > 0.0 && n0.normalized().cross(n1.normalized()).norm() <= 1e-8)
      continue;
    if (numBreaks == 2)
      return none;
    breaks[numBreaks++] = k;
  }
  if (numBreaks != 2)
    return none;
  auto fanOf = [&](std::size_t k) { return k > breaks[0] && k <= breaks[1] ? 0 : 1; };
  Eigen::Vector3d fanNormal[2] = { none, none };
  for (std::size_t k = 0; k < m; ++k)
    fanNormal[fanOf(k)] += normal(k);
  for (Eigen::Vector3d& n : fanNormal)
  {
    if (!(n.norm() > 0.0))
      return none;
    n.normalize();
  }
  // Each fan exactly planar (as the planar patches), the two planes really distinct.
  for (std::size_t k = 0; k < m; ++k)
  {
    const Eigen::Vector3d& n = fanNormal[fanOf(k)];
    for (std::int32_t w : { link[order[k]].first, link[order[k]].second })
    {
      const Eigen::Vector3d d = P[w] - P[v];
      if (std::abs(n.dot(d)) > 1e-10 * d.norm())
        return none;
    }
  }
  Eigen::Vector3d t = fanNormal[0].cross(fanNormal[1]);
  if (!(t.norm() > 1e-6))
    return none;
  t.normalize();
  // The crease neighbours (shared by the fans) on the line, on either side of v.
  const std::int32_t w0 = link[order[breaks[0]]].second, w1 = link[order[breaks[1]]].second;
  for (std::int32_t w : { w0, w1 })
  {
    const Eigen::Vector3d d = P[w] - P[v];
    if ((d - t * t.dot(d)).norm() > 1e-10 * d.norm())
      return none;
  }
  if (!(t.dot(P[w0] - P[v]) * t.dot(P[w1] - P[v]) < 0.0))
    return none;
  // The chord of the two neighbours is the same line; its direction has exact zeros where they
  // share a coordinate (an axis-aligned crease stays exactly on its two planes).
  return (P[w1] - P[w0]).normalized();
}

double TetMeshImprover::Volume(const Tet& t) const
{
  return (P[t[1]] - P[t[0]]).cross(P[t[2]] - P[t[0]]).dot(P[t[3]] - P[t[0]]);
}

bool TetMeshImprover::Accepts(double after, double before) const
{
  return AcceptsImprovement(after, before, Options.AcceptWorsening);
}

// Orders the link of edge (a, b) into a ring r0..r(n-1) such that every tet (a, b, ri, ri+1)
// is an even permutation of a stored tet. False if the edge is on the boundary or the link is
// not one cycle.
std::size_t TetMeshImprover::CollectEdgeLink(std::int32_t a, std::int32_t b)
{
  EdgeTets.clear();
  for (std::int32_t t : Star[a])
    if (IndexIn(Tets[t], b) >= 0)
      EdgeTets.push_back(t);
  // Pairs (c, d) with (a, b, c, d) even.
  Next.clear();
  for (std::int32_t t : EdgeTets)
  {
    const Tet& q = Tets[t];
    int idx[4] = { IndexIn(q, a), IndexIn(q, b), -1, -1 };
    int k = 2;
    for (int i = 0; i < 4; ++i)
      if (i != idx[0] && i != idx[1])
        idx[k++] = i;
    if (!IsEvenPermutation(idx))
      std::swap(idx[2], idx[3]);
    Next.push_back(q[idx[2]]);
    Next.push_back(q[idx[3]]);
  }
  return EdgeTets.size();
}

std::int32_t TetMeshImprover::Successor(std::int32_t v, std::size_t n) const
{
  std::int32_t succ = -1;
  int found = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (Next[2 * i] == v)
    {
      succ = Next[2 * i + 1];
      ++found;
    }
  return found == 1 ? succ : -1;
}

bool TetMeshImprover::BuildRing(std::int32_t a, std::int32_t b)
{
  const std::size_t n = CollectEdgeLink(a, b);
  if (n < 3 || n > static_cast<std::size_t>(Options.MaxEdgeRemovalRing))
    return false;
  Ring.clear();
  Ring.push_back(Next[0]);
  for (std::size_t step = 0; step < n; ++step)
  {
    const std::int32_t succ = Successor(Ring.back(), n);
    if (succ < 0)
      return false;
    if (step + 1 == n)
      return succ == Ring.front();
    if (std::find(Ring.begin(), Ring.end(), succ) != Ring.end())
      return false;
    Ring.push_back(succ);
  }
  return false;
}

bool TetMeshImprover::BuildOpenRing(std::int32_t a, std::int32_t b, bool& curved)
{
  curved = false;
  const std::size_t n = CollectEdgeLink(a, b);
  if (n < 2 || n + 1 > static_cast<std::size_t>(Options.MaxEdgeRemovalRing))
    return false;
  // The path starts at the one vertex that follows no other.
  std::int32_t start = -1;
  for (std::size_t i = 0; i < n; ++i)
  {
    bool isSuccessor = false;
    for (std::size_t j = 0; j < n; ++j)
      isSuccessor = isSuccessor || Next[2 * j + 1] == Next[2 * i];
    if (!isSuccessor)
    {
      if (start >= 0)
        return false;
      start = Next[2 * i];
    }
  }
  if (start < 0)
    return false;
  Ring.assign(1, start);
  for (std::size_t step = 0; step < n; ++step)
  {
    const std::int32_t succ = Successor(Ring.back(), n);
    if (succ < 0 || std::find(Ring.begin(), Ring.end(), succ) != Ring.end())
      return false;
    Ring.push_back(succ);
  }
  // The two boundary faces (a, b, r0) and (a, b, rn) in one plane, or nearly.
  const Eigen::Vector3d normal = (P[b] - P[a]).cross(P[Ring.front()] - P[a]);
  const Eigen::Vector3d d = P[Ring.back()] - P[a];
  if (!(normal.norm() > 0.0) || !(d.norm() > 0.0))
    return false;
  if (std::abs(normal.normalized().dot(d)) <= 1e-10 * d.norm())
    return true;
  // Outward normals of the two faces (r0 and rn are on opposite sides of a b).
  const Eigen::Vector3d n0 = (P[Ring.front()] - P[a]).cross(P[b] - P[a]).normalized();
  const Eigen::Vector3d n1 = (P[b] - P[a]).cross(P[Ring.back()] - P[a]).normalized();
  curved = true;
  return n0.dot(n1) >= std::cos(Options.BoundaryFlipMaxDihedral * Pi / 180.0);
}

// Edge removal (Shewchuk): the n tets around an interior edge are replaced by the 2(n-2) tets
// joining a and b to the best triangulation of their ring, found by dynamic programming over
// the ring's sub-polygons, maximizing the worst tet.
// On a planar boundary the ring is a path r0..r(n-1) and the polygon's closing side r0 r(n-1)
// is a new boundary edge: the faces (a, b, r0) and (a, b, r(n-1)) become (a, r0, r(n-1)) and
// (b, r(n-1), r0), which cover the same part of the plane.
bool TetMeshImprover::TryEdgeRemoval(std::int32_t a, std::int32_t b)
{
  bool open = false, curved = false;
  if (!BuildRing(a, b))
  {
    if (!Options.PlanarBoundary || !BuildOpenRing(a, b, curved))
      return false;
    open = true;
  }
  const int n = static_cast<int>(Ring.size());
  double before = std::numeric_limits<double>::infinity();
  for (std::int32_t t : EdgeTets)
    before = std::min(before, Quality(Tets[t]));
  Best.assign(static_cast<std::size_t>(n * n), std::numeric_limits<double>::infinity());
  Choice.assign(static_cast<std::size_t>(n * n), -1);
  for (int len = 2; len < n; ++len)
    for (int i = 0; i + len < n; ++i)
    {
      const int j = i + len;
      double best = -std::numeric_limits<double>::infinity();
      for (int k = i + 1; k < j; ++k)
      {
        const double q = std::min(std::min(Best[i * n + k], Best[k * n + j]),
          std::min(
            Quality({ a, Ring[i], Ring[k], Ring[j] }), Quality({ b, Ring[j], Ring[k], Ring[i] })));
        if (q > best)
        {
          best = q;
          Choice[i * n + j] = k;
        }
      }
      Best[i * n + j] = best;
    }
  const double after = Best[n - 1];
  if (!Accepts(after, before))
    return false;
  // Collect the triangles; their diagonals must be new edges.
  std::vector<std::array<int, 3>> tris;
  std::vector<std::pair<int, int>> stack = { { 0, n - 1 } };
  while (!stack.empty())
  {
    const auto [i, j] = stack.back();
    stack.pop_back();
    if (j - i < 2)
      continue;
    const int k = Choice[i * n + j];
    tris.push_back({ i, k, j });
    stack.push_back({ i, k });
    stack.push_back({ k, j });
  }
  auto isRingEdge = [&](int u, int w)
  { return std::abs(u - w) == 1 || (!open && std::abs(u - w) == n - 1); };
  for (const auto& t : tris)
    for (int e = 0; e < 3; ++e)
    {
      const int u = t[e], w = t[(e + 1) % 3];
      if (!isRingEdge(u, w) && Work.HasEdge(Ring[u], Ring[w]))
        return false;
    }
  if (Options.KeepEdgeLengths && !Options.AcceptWorsening)
  {
    // Each diagonal is counted twice (it is on two triangles), an open ring's closing side once.
    int outNew = 0;
    for (const auto& t : tris)
      for (int e = 0; e < 3; ++e)
      {
        const int u = t[e], w = t[(e + 1) % 3];
        const int weight = open && std::abs(u - w) == n - 1 ? 2 : 1;
        outNew += !isRingEdge(u, w) && OutOfRange(Ring[u], Ring[w]) ? weight : 0;
      }
    if (outNew / 2 > (OutOfRange(a, b) ? 1 : 0))
      return false;
  }
  double volumeChange = 0.0;
  if (open)
  {
    // The new tets must fill the old ones exactly: the same volume (coplanar faces, convex
    // quad). On a curved boundary they differ by the thin tet (a, b, r0, rn) between the old and
    // the new boundary faces, within the budget.
    double oldVolume = 0.0, newVolume = 0.0;
    for (std::int32_t t : EdgeTets)
      oldVolume += Volume(Tets[t]);
    for (const auto& t : tris)
      newVolume += Volume({ a, Ring[t[0]], Ring[t[1]], Ring[t[2]] }) +
        Volume({ b, Ring[t[2]], Ring[t[1]], Ring[t[0]] });
    const double allowed = curved ? std::abs(Volume({ a, b, Ring.front(), Ring.back() })) : 0.0;
    volumeChange = std::abs(newVolume - oldVolume);
    if (!(volumeChange <= allowed + 1e-9 * std::abs(oldVolume)))
      return false;
    if (curved &&
      BoundaryVolumeChange + volumeChange > Options.BoundaryFlipVolumeBudget * MeshVolume)
      return false;
    volumeChange = curved ? volumeChange : 0.0;
  }
  const std::vector<std::int32_t> old = EdgeTets;
  for (std::int32_t t : old)
    Work.Kill(t);
  for (const auto& t : tris)
  {
    Work.Add({ a, Ring[t[0]], Ring[t[1]], Ring[t[2]] });
    Work.Add({ b, Ring[t[2]], Ring[t[1]], Ring[t[0]] });
  }
  ++EdgeRemovals;
  BoundaryEdgeRemovals += open ? 1 : 0;
  BoundaryVolumeChange += volumeChange;
  return true;
}

// 2-3 flip of the face opposite `apexIndex` of `tet`: the two tets sharing it become three
// around the edge joining their apexes.
bool TetMeshImprover::TryFlip23(std::int32_t tet, int apexIndex, double worst)
{
  const Tet t1 = Tets[tet];
  const std::int32_t d = t1[apexIndex];
  const std::int32_t x = t1[FaceOpposite[apexIndex][0]], y = t1[FaceOpposite[apexIndex][1]],
                     z = t1[FaceOpposite[apexIndex][2]];
  std::int32_t other = -1;
  for (std::int32_t t : Star[x])
    if (t != tet && IndexIn(Tets[t], y) >= 0 && IndexIn(Tets[t], z) >= 0)
      other = t;
  if (other < 0)
    return false;
  const Tet& t2 = Tets[other];
  std::int32_t e = -1;
  for (std::int32_t v : t2)
    if (v != x && v != y && v != z)
      e = v;
  if (e < 0 || e == d || Work.HasEdge(d, e))
    return false;
  if (Options.KeepEdgeLengths && !Options.AcceptWorsening && OutOfRange(d, e))
    return false;
  const double before = std::min(worst, Quality(t2));
  const Tet n0 = { e, d, x, y }, n1 = { e, d, y, z }, n2 = { e, d, z, x };
  const double after = std::min(std::min(Quality(n0), Quality(n1)), Quality(n2));
  if (!Accepts(after, before))
    return false;
  Work.Kill(tet);
  Work.Kill(other);
  Work.Add(n0);
  Work.Add(n1);
  Work.Add(n2);
  ++Flips23;
  return true;
}

// A boundary vertex's move is committed here: its volume change (none in a plane, the thin
// shell between the old and the new faces on a curved patch) must fit the budget first.
bool TetMeshImprover::TrySmooth(std::int32_t v)
{
  const bool crease = LineDirection[v].squaredNorm() > 0.0;
  const bool boundary = crease || PlaneNormal[v].squaredNorm() > 0.0;
  if (!boundary)
  {
    if (!Smoother.TrySmooth(v, false))
      return false;
    ++Smoothed;
    return true;
  }
  if (OffBoundary[v])
  {
    // Its only move; tried a few times (its neighbours change), not for every bad tet.
    if (OffBoundary[v] > kMaxSnapTrials)
      return false;
    ++OffBoundary[v];
    return TrySnap(v);
  }
  const Eigen::Vector3d start = P[v];
  const double before = StarVolume(v);
  if (!Smoother.TrySmooth(v, true) || !KeepBoundaryMove(v, start, before))
    return false;
  ++Smoothed;
  CreaseSmoothed += crease ? 1 : 0;
  return true;
}

double TetMeshImprover::StarVolume(std::int32_t v) const
{
  double sum = 0.0;
  for (std::int32_t t : Star[v])
    sum += Volume(Tets[t]);
  return sum;
}

// A curved-patch move changes the volume by the change of v's star: charged to the budget.
bool TetMeshImprover::KeepBoundaryMove(
  std::int32_t v, const Eigen::Vector3d& start, double volumeBefore)
{
  const double change = Curved[v] ? std::abs(StarVolume(v) - volumeBefore) : 0.0;
  if (BoundaryVolumeChange + change > Options.BoundaryFlipVolumeBudget * MeshVolume ||
    (Options.AcceptMove && !Options.AcceptMove(v, P[v].data())))
  {
    Work.Points[v] = start;
    return false;
  }
  Work.Moved[v] = 1;
  BoundaryVolumeChange += change;
  ++BoundarySmoothed;
  return true;
}

// The move of an off-boundary vertex onto its closest boundary point, with its free interior
// neighbours smoothed after it (a site just inside the boundary often has one between it and
// the boundary, which the snap alone would invert): kept if the worst tet of the stars rises,
// no more of their tets are below EdgeLengthRuleMinAngle and, above that bar, no more of v's
// edges leave the range.
bool TetMeshImprover::TrySnap(std::int32_t v)
{
  const Eigen::Vector3d start = P[v];
  Eigen::Vector3d placed, normal = PlaneNormal[v];
  if (!Options.ProjectToBoundary(
        v, start.data(), PlaneNormal[v].data(), placed.data(), normal.data()))
    return false;
  SnapNeighbours.clear();
  for (std::int32_t t : Star[v])
    for (std::int32_t w : Tets[t])
      if (w != v && Work.CanMove(w) && PlaneNormal[w].squaredNorm() == 0.0 &&
        LineDirection[w].squaredNorm() == 0.0 && !OffBoundary[w] &&
        std::find(SnapNeighbours.begin(), SnapNeighbours.end(), w) == SnapNeighbours.end())
        SnapNeighbours.push_back(w);
  auto worstOf = [&](std::int32_t u)
  {
    double q = std::numeric_limits<double>::infinity();
    for (std::int32_t t : Star[u])
      q = std::min(q, Quality(Tets[t]));
    return q;
  };
  auto worst = [&]
  {
    double q = worstOf(v);
    for (std::int32_t w : SnapNeighbours)
      q = std::min(q, worstOf(w));
    return q;
  };
  // Tets below the §5.2 bar among the stars (shared ones counted once per star: the same
  // count before and after).
  const double bad = std::sin(Options.EdgeLengthRuleMinAngle * Pi / 180.0);
  auto numBad = [&]
  {
    int n = 0;
    for (std::int32_t t : Star[v])
      n += Quality(Tets[t]) < bad ? 1 : 0;
    for (std::int32_t w : SnapNeighbours)
      for (std::int32_t t : Star[w])
        n += Quality(Tets[t]) < bad ? 1 : 0;
    return n;
  };
  const double before = worst();
  const int badBefore = numBad();
  const int outBefore = Options.KeepEdgeLengths ? OutOfRangeAround(v) : 0;
  Work.Points[v] = placed;
  SnapMoved.clear();
  if (!Accepts(worstOf(v), before))
    for (std::int32_t w : SnapNeighbours)
    {
      const Eigen::Vector3d old = P[w];
      if (!(worstOf(w) > before) && Smoother.TrySmooth(w, true))
        SnapMoved.emplace_back(w, old);
    }
  bool better = Accepts(worst(), before) && (Options.AcceptWorsening || numBad() <= badBefore) &&
    (!Options.KeepEdgeLengths || Options.AcceptWorsening || OutOfRangeAround(v) <= outBefore);
  // Commit: the caller's AcceptMove for every moved vertex; one refusal undoes all.
  std::size_t accepted = 0;
  if (better && Options.AcceptMove)
  {
    better = Options.AcceptMove(v, placed.data());
    for (; better && accepted < SnapMoved.size(); ++accepted)
      better = Options.AcceptMove(SnapMoved[accepted].first, P[SnapMoved[accepted].first].data());
  }
  if (!better)
  {
    Work.Points[v] = start;
    for (const auto& [w, old] : SnapMoved)
      Work.Points[w] = old;
    if (Options.AcceptMove && accepted > 0)
    {
      // Put back the sites already relocated (their old positions were accepted before).
      Options.AcceptMove(v, start.data());
      for (std::size_t i = 0; i + 1 < accepted; ++i)
        Options.AcceptMove(SnapMoved[i].first, SnapMoved[i].second.data());
    }
    return false;
  }
  // Where it lands its boundary faces are no smooth patch yet: it stays there.
  PlaneNormal[v].setZero();
  Curved[v] = 0;
  Work.Fixed[v] = 1;
  OffBoundary[v] = 0;
  Work.Moved[v] = 1;
  for (const auto& moved : SnapMoved)
  {
    Work.Moved[moved.first] = 1;
    ++Smoothed;
  }
  ++Snaps;
  return true;
}

std::int32_t TetMeshImprover::Across(std::int32_t t, int m) const
{
  const Tet& q = Tets[t];
  const std::int32_t a = q[FaceOpposite[m][0]], b = q[FaceOpposite[m][1]],
                     c = q[FaceOpposite[m][2]];
  std::int32_t other = -1;
  int found = 0;
  for (std::int32_t u : Star[a])
    if (u != t && IndexIn(Tets[u], b) >= 0 && IndexIn(Tets[u], c) >= 0)
    {
      other = u;
      ++found;
    }
  return found == 1 ? other : -1;
}

void TetMeshImprover::CollectCavityFaces()
{
  CavityFaces.clear();
  CavityFaceOwner.clear();
  for (std::int32_t t : Cavity)
    for (int m = 0; m < 4; ++m)
    {
      const std::int32_t n = Across(t, m);
      if (n >= 0 && std::find(Cavity.begin(), Cavity.end(), n) != Cavity.end())
        continue;
      const Tet& q = Tets[t];
      CavityFaces.push_back(
        { q[FaceOpposite[m][0]], q[FaceOpposite[m][1]], q[FaceOpposite[m][2]] });
      CavityFaceOwner.push_back(t);
    }
}

// Bowyer-Watson in the metric of the bad tet, then the usual correction: a face that x does
// not see from inside takes its tet out of the cavity, until x sees them all.
bool TetMeshImprover::BuildCavity(std::int32_t seed,
  const Eigen::Vector3d& x,
  const Eigen::Matrix3d& map)
{
  const Eigen::Vector3d mx = map * x;
  auto inCircumsphere = [&](const Tet& t)
  {
    const Eigen::Vector3d q0 = map * P[t[0]];
    Eigen::Matrix3d rows;
    Eigen::Vector3d rhs;
    for (int i = 1; i < 4; ++i)
    {
      const Eigen::Vector3d qi = map * P[t[i]];
      rows.row(i - 1) = 2.0 * (qi - q0).transpose();
      rhs[i - 1] = qi.squaredNorm() - q0.squaredNorm();
    }
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(rows);
    if (!lu.isInvertible())
      return true; // flat: any point is as good as inside
    const Eigen::Vector3d c = lu.solve(rhs);
    return (mx - c).squaredNorm() < (q0 - c).squaredNorm();
  };
  Cavity.assign(1, seed);
  const auto maxSize = static_cast<std::size_t>(std::max(1, Options.MaxInsertionCavity));
  for (std::size_t i = 0; i < Cavity.size() && Cavity.size() < maxSize; ++i)
    for (int m = 0; m < 4 && Cavity.size() < maxSize; ++m)
    {
      const std::int32_t n = Across(Cavity[i], m);
      if (n >= 0 && std::find(Cavity.begin(), Cavity.end(), n) == Cavity.end() &&
        inCircumsphere(Tets[n]))
        Cavity.push_back(n);
    }
  for (;;)
  {
    CollectCavityFaces();
    std::int32_t hidden = -1;
    for (std::size_t f = 0; f < CavityFaces.size() && hidden < 0; ++f)
    {
      const auto& q = CavityFaces[f];
      const double v = (P[q[1]] - P[q[0]]).cross(P[q[2]] - P[q[0]]).dot(x - P[q[0]]);
      const double scale =
        (P[q[1]] - P[q[0]]).norm() * (P[q[2]] - P[q[0]]).norm() * (x - P[q[0]]).norm();
      if (!(v > 1e-9 * scale))
        hidden = CavityFaceOwner[f];
    }
    if (hidden < 0)
      break;
    if (hidden == seed)
      return false;
    Cavity.erase(std::find(Cavity.begin(), Cavity.end(), hidden));
  }
  // Every vertex of the cavity's tets must stay on its boundary (none is removed).
  for (std::int32_t t : Cavity)
    for (std::int32_t v : Tets[t])
    {
      bool onFace = false;
      for (const auto& q : CavityFaces)
        onFace = onFace || q[0] == v || q[1] == v || q[2] == v;
      if (!onFace)
        return false;
    }
  // x sees every face from inside and the new tets fill the cavity exactly.
  double oldVolume = 0.0, newVolume = 0.0;
  for (std::int32_t t : Cavity)
    oldVolume += Volume(Tets[t]);
  for (const auto& q : CavityFaces)
    newVolume += (P[q[1]] - P[q[0]]).cross(P[q[2]] - P[q[0]]).dot(x - P[q[0]]);
  return std::abs(newVolume - oldVolume) <= 1e-9 * std::abs(oldVolume);
}

std::int32_t TetMeshImprover::ApplyInsertion(const Eigen::Vector3d& x, const Eigen::Matrix3d& s)
{
  const std::int32_t m = Work.AddPoint(x, s);
  PlaneNormal.emplace_back(Eigen::Vector3d::Zero());
  LineDirection.emplace_back(Eigen::Vector3d::Zero());
  Curved.push_back(0);
  OffBoundary.push_back(0);
  CavityTets.clear();
  for (std::int32_t t : Cavity)
  {
    CavityTets.push_back(Tets[t]);
    Work.Kill(t);
  }
  for (const auto& q : CavityFaces)
    Work.Add({ q[0], q[1], q[2], m });
  return m;
}

void TetMeshImprover::UndoInsertion(std::int32_t point, std::size_t firstNewTet)
{
  for (std::size_t t = firstNewTet; t < Tets.size(); ++t)
    if (Work.IsAlive(static_cast<std::int32_t>(t)))
      Work.Kill(static_cast<std::int32_t>(t));
  Work.TruncateDead(firstNewTet);
  for (std::size_t i = 0; i < Cavity.size(); ++i)
    Work.Revive(Cavity[i], CavityTets[i]);
  (void)point;
  Work.RemoveLastPoint();
  PlaneNormal.pop_back();
  LineDirection.pop_back();
  Curved.pop_back();
  OffBoundary.pop_back();
}

// Klingner & Shewchuk's insertion, simplified: a few trial points inside or on the bad tet
// (its metric circumcenter, centroid and edge midpoints), each with its metric Bowyer-Watson
// cavity joined to it and the new vertex smoothed; the best that raises the cavity's worst tet
// is kept.
bool TetMeshImprover::TryInsertion(std::int32_t tet)
{
  const Tet t = Tets[tet];
  const Eigen::Matrix3d map = 0.25 *
    (Work.SqrtMetrics[t[0]] + Work.SqrtMetrics[t[1]] + Work.SqrtMetrics[t[2]] +
      Work.SqrtMetrics[t[3]]);
  std::array<Eigen::Vector3d, 8> trials;
  int numTrials = 0;
  {
    Eigen::Matrix3d rows;
    Eigen::Vector3d rhs;
    const Eigen::Vector3d q0 = map * P[t[0]];
    for (int i = 1; i < 4; ++i)
    {
      const Eigen::Vector3d qi = map * P[t[i]];
      rows.row(i - 1) = 2.0 * (qi - q0).transpose();
      rhs[i - 1] = qi.squaredNorm() - q0.squaredNorm();
    }
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(rows);
    const Eigen::FullPivLU<Eigen::Matrix3d> mapLu(map);
    if (lu.isInvertible() && mapLu.isInvertible())
      trials[numTrials++] = mapLu.solve(lu.solve(rhs));
  }
  trials[numTrials++] = 0.25 * (P[t[0]] + P[t[1]] + P[t[2]] + P[t[3]]);
  // The two longest edges' midpoints (a cap or a sliver is split across its long edges).
  std::array<std::pair<double, int>, 6> edges;
  for (int i = 0, e = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j, ++e)
      edges[e] = { -Work.EdgeLength(t[i], t[j]), i * 4 + j };
  std::sort(edges.begin(), edges.end());
  for (int e = 0; e < 2; ++e)
    trials[numTrials++] = 0.5 * (P[t[edges[e].second / 4]] + P[t[edges[e].second % 4]]);

  const double badBelow = std::sin(Options.EdgeLengthRuleMinAngle * Pi / 180.0);
  double bestAfter = -std::numeric_limits<double>::infinity();
  Eigen::Vector3d bestPoint = Eigen::Vector3d::Zero();
  Eigen::Matrix3d bestRoot = Eigen::Matrix3d::Zero();
  std::vector<std::int32_t> bestCavity;
  for (int k = 0; k < numTrials; ++k)
  {
    const Eigen::Vector3d& x = trials[k];
    if (!x.allFinite() || !BuildCavity(tet, x, map))
      continue;
    Eigen::Matrix3d root = map;
    if (Options.PlacePoint)
    {
      double placed[3], normal[3], metric[6];
      if (!Options.PlacePoint(t[0], x.data(), placed, normal, metric))
        continue;
      root = SymmetricSqrt(UnpackSymmetric(metric));
    }
    double before = std::numeric_limits<double>::infinity();
    int badBefore = 0;
    for (std::int32_t c : Cavity)
    {
      const double q = Quality(Tets[c]);
      before = std::min(before, q);
      badBefore += q < badBelow ? 1 : 0;
    }
    const std::size_t firstNew = Tets.size();
    const std::int32_t m = ApplyInsertion(x, root);
    for (int round = 0; round < 3 && Smoother.TrySmooth(m, true); ++round)
    {
    }
    const double after = Work.StarWorst(m);
    int badAfter = 0;
    for (std::int32_t c : Star[m])
      badAfter += Quality(Tets[c]) < badBelow ? 1 : 0;
    // Also no more bad tets than before: a bad tet split into several less bad ones is no gain.
    if (Accepts(after, before) && (badAfter <= badBefore || Options.AcceptWorsening) &&
      after > bestAfter)
    {
      bestAfter = after;
      bestPoint = P[m];
      bestRoot = root;
      bestCavity = Cavity;
    }
    UndoInsertion(m, firstNew);
  }
  if (bestCavity.empty())
    return false;
  // Redo the best: the same cavity, the vertex where its smoothing ended.
  Cavity = bestCavity;
  CollectCavityFaces();
  const std::size_t firstNew = Tets.size();
  const std::int32_t m = ApplyInsertion(bestPoint, bestRoot);
  if (!(Work.StarWorst(m) > 0.0) ||
    (Options.AddPoint && !Options.AddPoint(m, t[0], bestPoint.data())))
  {
    UndoInsertion(m, firstNew);
    return false;
  }
  Work.Moved[m] = 1;
  ++Insertions;
  return true;
}

// The tet's two boundary faces share an edge (a, b) that no other tet has; its two other faces
// (a, c, d) and (b, c, d) become the boundary. Refused when (c, d) is already on the boundary
// (the boundary would pinch there) or a or b is in no other tet.
bool TetMeshImprover::TryPeel(std::int32_t tet)
{
  const Tet t = Tets[tet];
  int boundaryFaces = 0;
  std::int32_t inner[2] = { -1, -1 };
  int nInner = 0;
  for (int m = 0; m < 4; ++m)
  {
    const std::int32_t n = Across(tet, m);
    if (n < 0)
      ++boundaryFaces;
    else if (nInner < 2)
      inner[nInner++] = n;
  }
  if (boundaryFaces == 3 && nInner == 1)
    return PeelEar(tet, inner[0]);
  if (boundaryFaces != 2 || nInner != 2)
    return false;
  // The two boundary faces are opposite c and d, i.e. they share the edge (a, b).
  std::int32_t onBoth[2], off[2];
  int nb = 0, no = 0;
  for (int m = 0; m < 4; ++m)
    (Across(tet, m) < 0 ? off[no++] : onBoth[nb++]) = t[m];
  const std::int32_t c = off[0], d = off[1], a = onBoth[0], b = onBoth[1];
  if (Star[a].size() < 2 || Star[b].size() < 2)
    return false;
  // (c, d) must be an interior edge: no boundary face on it.
  for (std::int32_t u : Star[c])
  {
    if (u == tet || IndexIn(Tets[u], d) < 0)
      continue;
    for (int m = 0; m < 4; ++m)
      if (Tets[u][m] != c && Tets[u][m] != d && Across(u, m) < 0)
        return false;
  }
  const double before = std::min({ Quality(t), Quality(Tets[inner[0]]), Quality(Tets[inner[1]]) });
  const double after = std::min(Quality(Tets[inner[0]]), Quality(Tets[inner[1]]));
  return CommitPeel(tet, after, before);
}

bool TetMeshImprover::CommitPeel(std::int32_t tet, double after, double before)
{
  const Tet t = Tets[tet];
  const double volume = std::abs(Volume(t));
  if (!Accepts(after, before) ||
    PeeledVolume + volume > Options.BoundaryPeelVolumeBudget * MeshVolume)
    return false;
  Work.Kill(tet);
  // The new boundary faces' vertices are no longer on a planar patch or a straight crease.
  for (std::int32_t v : t)
  {
    Work.Fixed[v] = 1;
    PlaneNormal[v].setZero();
    LineDirection[v].setZero();
    Curved[v] = 0;
    OffBoundary[v] = 0;
  }
  PeeledVolume += volume;
  ++Peels;
  return true;
}

// A tet with three boundary faces whose apex (the vertex on all three) has other tets: the ear
// touches the rest of the mesh only at that vertex (a pinched boundary, found at the creases of
// the real volumes). Its removal un-pinches the apex and leaves its base as boundary; every
// edge of the base keeps its number of boundary faces (one of the ear's for the base), so no
// edge becomes non-manifold.
bool TetMeshImprover::PeelEar(std::int32_t tet, std::int32_t inner)
{
  const Tet t = Tets[tet];
  std::int32_t apex = -1;
  for (int m = 0; m < 4; ++m)
    if (Across(tet, m) >= 0)
      apex = t[m];
  if (apex < 0 || Star[apex].size() < 2)
    return false;
  const double before = std::min(Quality(t), Quality(Tets[inner]));
  const double after = Quality(Tets[inner]);
  return CommitPeel(tet, after, before);
}

bool TetMeshImprover::OnBoundary(std::int32_t v) const
{
  for (std::int32_t u : Star[v])
    for (int m = 0; m < 4; ++m)
      if (Tets[u][m] != v && Across(u, m) < 0)
        return true;
  return false;
}

// Where a free interior vertex has a small star of flat tets around it (a site squeezed
// between its neighbours), no position of it is good: removing it is (Klingner & Shewchuk's
// edge contraction).
bool TetMeshImprover::TryContraction(std::int32_t tet)
{
  const Tet t = Tets[tet];
  std::array<std::pair<double, int>, 6> edges;
  int n = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      edges[n++] = { Work.EdgeLength(t[i], t[j]), 4 * i + j };
  std::sort(edges.begin(), edges.end());
  for (const auto& e : edges)
  {
    const std::int32_t a = t[e.second / 4], b = t[e.second % 4];
    if (ContractInto(b, a) || ContractInto(a, b))
      return true;
  }
  return false;
}

bool TetMeshImprover::ContractInto(std::int32_t keep, std::int32_t remove)
{
  if (Work.Fixed[remove] || Star[remove].empty() || OnBoundary(remove))
    return false;
  double before = std::numeric_limits<double>::infinity();
  double after = std::numeric_limits<double>::infinity();
  ContractedTets.clear();
  for (std::int32_t u : Star[remove])
  {
    const Tet& q = Tets[u];
    before = std::min(before, Quality(q));
    if (IndexIn(q, keep) >= 0)
      continue; // on the edge: dies
    Tet nq = q;
    nq[IndexIn(nq, remove)] = keep;
    after = std::min(after, Quality(nq));
    ContractedTets.push_back(nq);
  }
  if (ContractedTets.empty() || !Accepts(after, before))
    return false;
  // Every new edge (keep, w) must be new unless w is on the contracted edge's link.
  for (const Tet& nq : ContractedTets)
    for (std::int32_t w : nq)
      if (w != keep && Work.HasEdge(keep, w))
      {
        bool onLink = false;
        for (std::int32_t u : Star[remove])
          onLink = onLink || (IndexIn(Tets[u], keep) >= 0 && IndexIn(Tets[u], w) >= 0);
        if (!onLink)
          return false;
      }
  // No face on keep in more than two tets afterwards.
  ContractedFaces.clear();
  auto addFaces = [&](const Tet& q)
  {
    for (int m = 0; m < 4; ++m)
    {
      if (q[m] == keep)
        continue;
      std::array<std::int32_t, 3> f = {
        q[FaceOpposite[m][0]], q[FaceOpposite[m][1]], q[FaceOpposite[m][2]]
      };
      std::sort(f.begin(), f.end());
      ContractedFaces.push_back(f);
    }
  };
  for (std::int32_t u : Star[keep])
    if (IndexIn(Tets[u], remove) < 0)
      addFaces(Tets[u]);
  for (const Tet& nq : ContractedTets)
    addFaces(nq);
  std::sort(ContractedFaces.begin(), ContractedFaces.end());
  for (std::size_t i = 0; i + 2 < ContractedFaces.size(); ++i)
    if (ContractedFaces[i] == ContractedFaces[i + 2])
      return false;
  if (Options.KeepEdgeLengths && !EdgeRuleWaived)
    return false;
  const std::vector<std::int32_t> star = Star[remove];
  for (std::int32_t u : star)
    Work.Kill(u);
  for (const Tet& nq : ContractedTets)
    Work.Add(nq);
  Work.Fixed[remove] = 1; // unreferenced from now on
  ++Contractions;
  return true;
}

bool TetMeshImprover::Improve(std::int32_t tet)
{
  const Tet t = Tets[tet];
  const double worst = Quality(t);
  EdgeRuleWaived = worst < std::sin(Options.EdgeLengthRuleMinAngle * Pi / 180.0);
  if (Options.Flips)
  {
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        if (TryEdgeRemoval(t[i], t[j]))
          return true;
    for (int m = 0; m < 4; ++m)
      if (TryFlip23(tet, m, worst))
        return true;
  }
  bool any = false;
  if (Options.Smoothing)
    for (std::int32_t v : t)
      any = TrySmooth(v) || any;
  // Insertion adds short edges: only where the edge-length rule is waived.
  const double insertBelow = std::sin(
    (Options.KeepEdgeLengths ? Options.EdgeLengthRuleMinAngle : Options.TargetAngle) * Pi / 180.0);
  if (Options.Insertions && Work.IsAlive(tet) && Quality(Tets[tet]) < insertBelow &&
    TryInsertion(tet))
    return true;
  if (Options.Collapses && Work.IsAlive(tet) && Quality(Tets[tet]) < insertBelow &&
    TryContraction(tet))
    return true;
  if (Options.PeelBoundaryTets && Options.PlanarBoundary && Work.IsAlive(tet) &&
    Quality(Tets[tet]) < std::sin(Options.EdgeLengthRuleMinAngle * Pi / 180.0) && TryPeel(tet))
    return true;
  return any;
}

// Then the average: interior vertices, and boundary ones that move in their plane or along
// their straight crease, in parallel; then, one at a time, those of curved patches, whose moves
// change the volume and are charged to BoundaryFlipVolumeBudget.
void TetMeshImprover::MeanSmoothingSweeps()
{
  std::vector<std::int32_t> vertices, curved;
  for (std::int32_t v = 0; v < static_cast<std::int32_t>(P.size()); ++v)
  {
    if (!Work.CanMove(v) || OffBoundary[v])
      continue;
    const bool planar = PlaneNormal[v].squaredNorm() > 0.0 && !Curved[v];
    const bool line = LineDirection[v].squaredNorm() > 0.0;
    if (!OnBoundary(v) || planar || line)
      vertices.push_back(v);
    else if (Curved[v] && PlaneNormal[v].squaredNorm() > 0.0)
      curved.push_back(v);
  }
  const double floor = Smoother.MeanSmoothingFloor();
  MeanSmoothed += Smoother.MeanSmoothingSweeps(vertices);
  for (int sweep = 0; sweep < Options.MeanSmoothingSweeps && !curved.empty(); ++sweep)
  {
    std::size_t moved = 0;
    for (std::int32_t v : curved)
    {
      const Eigen::Vector3d start = P[v];
      const double before = StarVolume(v);
      if (Smoother.TryMeanSmooth(v, floor, true) && KeepBoundaryMove(v, start, before))
        ++moved;
    }
    MeanSmoothed += moved;
    if (moved == 0)
      break;
  }
}

void TetMeshImprover::Run(MeshImprovementResult& result)
{
  const double toDeg = 180.0 / Pi;
  auto angle = [&](double q) { return std::asin(std::max(-1.0, std::min(1.0, q))) * toDeg; };
  result.WorstBefore = Tets.empty() ? 0.0 : angle(Work.WorstQuality());
  const double target = std::sin(Options.TargetAngle * Pi / 180.0);
  result.Passes += Work.ImproveWorstFirst(
    target, Options.MaxPasses, [this](std::int32_t t) { return Work.IsAlive(t) && Improve(t); });
  if (Options.Smoothing && Options.MeanSmoothingSweeps > 0)
    MeanSmoothingSweeps();
  result.WorstAfter = Tets.empty() ? 0.0 : angle(Work.WorstQuality());
  Work.WriteBack(Mesh);
  result.NumFlips23 = Flips23;
  result.NumEdgeRemovals = EdgeRemovals;
  result.NumSmoothed = Smoothed + MeanSmoothed;
  result.NumMeanSmoothed = MeanSmoothed;
  result.NumBoundaryEdgeRemovals = BoundaryEdgeRemovals;
  result.NumBoundarySmoothed = BoundarySmoothed;
  result.NumCreaseSmoothed = CreaseSmoothed;
  result.NumInsertions = Insertions;
  result.NumBoundaryPeels = Peels;
  result.NumBoundarySnaps = Snaps;
  result.NumCollapses = Contractions;
  result.BoundaryVolumeChange =
    MeshVolume > 0.0 ? (BoundaryVolumeChange + PeeledVolume) / MeshVolume : 0.0;
  result.Moved = std::move(Work.Moved);
}

} // namespace av
