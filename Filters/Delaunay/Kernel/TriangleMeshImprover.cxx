// SPDX-License-Identifier: BSD-3-Clause
#include "TriangleMeshImprover.h"

#include "MetricAlgebra.h"
#include "MetricSimplexQuality.h"
#include "TriangleBvh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace av
{
namespace
{
constexpr double Pi = 3.14159265358979323846;
constexpr std::int32_t kDead = SimplexStarMesh<2>::kDead;
constexpr auto IndexIn = &SimplexStarMesh<2>::IndexIn;
} // namespace

TriangleMeshImprover::TriangleMeshImprover(SimplexMesh& mesh,
  std::vector<Eigen::Matrix3d> sqrtMetrics,
  const std::vector<std::uint8_t>* fixed,
  const MeshImprovementOptions& options)
  : Mesh(mesh)
  , Surface(mesh.AmbientDim == 3)
  , Options(options)
  , Work(mesh, std::move(sqrtMetrics), fixed)
  , P(Work.Points)
  , N(Work.Normals)
  , S(Work.SqrtMetrics)
  , Tris(Work.Simplices)
  , Star(Work.Stars)
  , Fixed(Work.Fixed)
  , Moved(Work.Moved)
  , Smoother(Work,
      Options,
      false,
      [this](std::int32_t v, const Eigen::Vector3d& x) { return Place(v, Hint[v], x); })
{
  const std::size_t np = mesh.NumPoints();
  Hint.resize(np);
  for (std::size_t i = 0; i < np; ++i)
    Hint[i] = static_cast<std::int32_t>(i);
  // Orientation reference: +z in 2D; on a surface the domain's normal at the vertex, else the
  // area-weighted normal of its triangles.
  if (Surface)
    for (std::size_t i = 0; i < np; ++i)
    {
      Eigen::Vector3d n = Eigen::Vector3d::Zero();
      for (std::int32_t t : Star[i])
        n += (P[Tris[t][1]] - P[Tris[t][0]]).cross(P[Tris[t][2]] - P[Tris[t][0]]);
      double placed[3], normal[3], metric[6];
      if (!Star[i].empty() && Options.PlacePoint &&
        Options.PlacePoint(static_cast<std::int32_t>(i), P[i].data(), placed, normal, metric))
        n = Eigen::Map<const Eigen::Vector3d>(normal);
      if (n.norm() > 0.0)
        N[i] = n.normalized();
    }
  CosFlipDihedral = std::cos(Options.SurfaceFlipMaxDihedral * Pi / 180.0);
  Slides.assign(np, 0);
  if (Surface && fixed && Options.ProjectToFeatureLine && Options.PlacePoint)
  {
    for (std::size_t i = 0; i < np && i < fixed->size(); ++i)
      Slides[i] = (*fixed)[i] == FeatureLinePoint ? 1 : 0;
    // Steps along the line only: the rest of the ascent would be undone by the projection.
    Smoother.SetDirectionFilter(
      [this](std::int32_t v, Eigen::Vector3d& g)
      {
        double placed[3], tangent[3];
        if (!Slides[v] || !Options.ProjectToFeatureLine(v, P[v].data(), placed, tangent))
          return;
        const Eigen::Map<const Eigen::Vector3d> t(tangent);
        g = t * t.dot(g);
      });
  }
  MarkBoundaryAndNonManifold();
}

bool TriangleMeshImprover::Accepts(double after, double before) const
{
  return AcceptsImprovement(after, before, Options.AcceptWorsening);
}

// Vertices on edges of one triangle (the boundary) or of more than two never move.
void TriangleMeshImprover::MarkBoundaryAndNonManifold()
{
  std::vector<std::pair<std::int32_t, std::int32_t>> edges;
  edges.reserve(Tris.size() * 3);
  for (const Tri& t : Tris)
    for (int e = 0; e < 3; ++e)
      edges.emplace_back(std::min(t[e], t[(e + 1) % 3]), std::max(t[e], t[(e + 1) % 3]));
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();)
  {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j] == edges[i])
      ++j;
    if (j - i != 2)
    {
      Fixed[edges[i].first] = Fixed[edges[i].second] = 1;
      Slides[edges[i].first] = Slides[edges[i].second] = 0;
    }
    i = j;
  }
}

std::int32_t TriangleMeshImprover::OtherTriangle(std::int32_t tri,
  std::int32_t a,
  std::int32_t b,
  int* count) const
{
  std::int32_t other = -1;
  *count = 0;
  for (std::int32_t t : Star[a])
    if (t != tri && IndexIn(Tris[t], b) >= 0)
    {
      other = t;
      ++*count;
    }
  return other;
}

// Puts vertex v at x on the domain with the domain's normal and metric there.
bool TriangleMeshImprover::Place(std::int32_t v, std::int32_t near, const Eigen::Vector3d& x)
{
  if (!Options.PlacePoint)
  {
    P[v] = x;
    return true;
  }
  double placed[3], normal[3], metric[6];
  Eigen::Vector3d onLine = x;
  double tangent[3];
  if (Slides[v] && !Options.ProjectToFeatureLine(v, x.data(), onLine.data(), tangent))
    return false;
  if (!Options.PlacePoint(near, onLine.data(), placed, normal, metric))
    return false;
  P[v] = Slides[v] ? onLine : Eigen::Vector3d(Eigen::Map<const Eigen::Vector3d>(placed));
  if (Surface)
  {
    N[v] = Eigen::Map<const Eigen::Vector3d>(normal);
    S[v] = SymmetricSqrt(UnpackSymmetric(metric));
  }
  else
  {
    P[v].z() = 0.0;
    S[v].setZero();
    S[v].topLeftCorner<2, 2>() = SymmetricSqrt(UnpackSymmetric2(metric));
  }
  return true;
}

// ---- Journal: every mutation goes through these, so a compound operation can be undone.

void TriangleMeshImprover::Touch(std::int32_t t)
{
  if (!Undo.Active || std::find(Undo.Touched.begin(), Undo.Touched.end(), t) != Undo.Touched.end())
    return;
  Undo.Touched.push_back(t);
  if (static_cast<std::size_t>(t) < Undo.NumTris && Alive(t))
    Undo.WorstBefore = std::min(Undo.WorstBefore, Quality(Tris[t]));
}

void TriangleMeshImprover::SetTri(std::int32_t t, const Tri& tri)
{
  if (Undo.Active)
  {
    Touch(t);
    Undo.Tris.emplace_back(t, Tris[t]);
  }
  Tris[t] = tri;
}

std::int32_t TriangleMeshImprover::AddTri(const Tri& tri)
{
  const auto t = static_cast<std::int32_t>(Tris.size());
  Tris.push_back(tri);
  Touch(t);
  for (std::int32_t v : tri)
    StarAdd(v, t);
  return t;
}

void TriangleMeshImprover::StarErase(std::int32_t v, std::int32_t t)
{
  if (Undo.Active)
    Undo.Stars.emplace_back(v, Star[v]);
  Star[v].erase(std::find(Star[v].begin(), Star[v].end(), t));
}

void TriangleMeshImprover::StarAdd(std::int32_t v, std::int32_t t)
{
  if (Undo.Active)
    Undo.Stars.emplace_back(v, Star[v]);
  Star[v].push_back(t);
}

// Before a vertex moves: its old state and the quality of its star as it is now.
void TriangleMeshImprover::SaveVertex(std::int32_t v)
{
  if (!Undo.Active)
    return;
  Undo.Vertices.push_back({ v, P[v], N[v], S[v] });
  for (std::int32_t t : Star[v])
    Touch(t);
}

std::int32_t TriangleMeshImprover::AddVertex(const Eigen::Vector3d& p,
  const Eigen::Matrix3d& s,
  const Eigen::Vector3d& n,
  bool fixed,
  std::int32_t hint)
{
  Hint.push_back(hint);
  Slides.push_back(0);
  P.push_back(p);
  S.push_back(s);
  N.push_back(n);
  Fixed.push_back(fixed ? 1 : 0);
  Star.emplace_back();
  Moved.push_back(1);
  return static_cast<std::int32_t>(P.size() - 1);
}

void TriangleMeshImprover::Begin()
{
  Undo.Active = true;
  Undo.Tris.clear();
  Undo.Stars.clear();
  Undo.Vertices.clear();
  Undo.Touched.clear();
  Undo.WorstBefore = std::numeric_limits<double>::infinity();
  Undo.NumTris = Tris.size();
  Undo.NumPoints = P.size();
  Undo.Flips = Flips;
  Undo.Smoothed = Smoothed;
}

void TriangleMeshImprover::Rollback()
{
  for (auto it = Undo.Vertices.rbegin(); it != Undo.Vertices.rend(); ++it)
    if (static_cast<std::size_t>(it->Id) < Undo.NumPoints)
    {
      P[it->Id] = it->P;
      N[it->Id] = it->N;
      S[it->Id] = it->S;
    }
  for (auto it = Undo.Tris.rbegin(); it != Undo.Tris.rend(); ++it)
    if (static_cast<std::size_t>(it->first) < Undo.NumTris)
      Tris[it->first] = it->second;
  for (auto it = Undo.Stars.rbegin(); it != Undo.Stars.rend(); ++it)
    if (static_cast<std::size_t>(it->first) < Undo.NumPoints)
      Star[it->first] = std::move(it->second);
  Tris.resize(Undo.NumTris);
  P.resize(Undo.NumPoints);
  S.resize(Undo.NumPoints);
  N.resize(Undo.NumPoints);
  Fixed.resize(Undo.NumPoints);
  Hint.resize(Undo.NumPoints);
  Slides.resize(Undo.NumPoints);
  Star.resize(Undo.NumPoints);
  Moved.resize(Undo.NumPoints);
  Flips = Undo.Flips;
  Smoothed = Undo.Smoothed;
  Undo.Active = false;
}

// Hands the new and moved vertices to the caller; a refusal undoes the whole operation.
bool TriangleMeshImprover::Commit()
{
  for (std::size_t v = Undo.NumPoints; v < P.size(); ++v)
  {
    if (Options.AddPoint && !Options.AddPoint(static_cast<std::int32_t>(v), Hint[v], P[v].data()))
    {
      Rollback();
      return false;
    }
    Hint[v] = static_cast<std::int32_t>(v); // the caller knows it now
  }
  for (const Journal::Vertex& saved : Undo.Vertices)
  {
    const std::int32_t v = saved.Id;
    if (static_cast<std::size_t>(v) >= Undo.NumPoints || P[v] == saved.P)
      continue;
    if (Options.AcceptMove && !Options.AcceptMove(v, P[v].data()))
    {
      Rollback();
      return false;
    }
    Moved[v] = 1;
  }
  Undo.Active = false;
  return true;
}

// After a collapse or split around `center`: smooth it, flip its link edges, smooth again;
// keep the lot only if the worst triangle it touched got better.
bool TriangleMeshImprover::FinishCompound(std::int32_t center)
{
  if (Options.Smoothing)
    TrySmooth(center);
  if (Options.Flips)
  {
    const std::vector<std::int32_t> ring = Star[center];
    for (std::int32_t t : ring)
    {
      const int i = IndexIn(Tris[t], center);
      if (i >= 0)
        TryFlip(t, (i + 1) % 3);
    }
  }
  if (Options.Smoothing)
    TrySmooth(center);
  double after = std::numeric_limits<double>::infinity();
  for (std::int32_t t : Undo.Touched)
    if (Alive(t))
      after = std::min(after, Quality(Tris[t]));
  if (!Accepts(after, Undo.WorstBefore))
  {
    Rollback();
    return false;
  }
  return Commit();
}

// ---- Operations.

// 2-2 flip of edge `edge` (t[edge], t[edge+1]) of triangle `tri`: (a, b, c) and (b, a, d)
// become (c, a, d) and (d, b, c). Boundary-adjacent edges flip too; boundary edges cannot.
bool TriangleMeshImprover::TryFlip(std::int32_t tri, int edge)
{
  const Tri t1 = Tris[tri];
  const std::int32_t a = t1[edge], b = t1[(edge + 1) % 3], c = t1[(edge + 2) % 3];
  int count = 0;
  const std::int32_t other = OtherTriangle(tri, a, b, &count);
  if (count != 1)
    return false; // boundary or non-manifold edge
  const Tri t2 = Tris[other];
  const std::int32_t d =
    t2[0] != a && t2[0] != b ? t2[0] : (t2[1] != a && t2[1] != b ? t2[1] : t2[2]);
  if (d == c || Work.HasEdge(c, d))
    return false;
  if (Surface)
  {
    // Only nearly coplanar pairs: across a crease the flip would cut the surface.
    const Eigen::Vector3d n1 = (P[b] - P[a]).cross(P[c] - P[a]);
    const Eigen::Vector3d n2 = (P[a] - P[b]).cross(P[d] - P[b]);
    if (!(n1.dot(n2) >= CosFlipDihedral * n1.norm() * n2.norm()))
      return false;
  }
  const Tri n1 = { c, a, d }, n2 = { d, b, c };
  const double before = std::min(Quality(t1), Quality(t2));
  const double after = std::min(Quality(n1), Quality(n2));
  if (!Accepts(after, before))
    return false;
  SetTri(tri, n1);
  SetTri(other, n2);
  StarErase(a, other);
  StarErase(b, tri);
  StarAdd(c, other);
  StarAdd(d, tri);
  ++Flips;
  return true;
}

// In the domain's tangent plane at v, each trial placed on the domain (on a surface: projected
// onto it); inside a compound operation the journal's Commit asks AcceptMove and marks moves.
bool TriangleMeshImprover::TrySmooth(std::int32_t v)
{
  const bool slides = Slides[v] && !Star[v].empty();
  if ((!Work.CanMove(v) && !slides) || (Surface && !Options.PlacePoint))
    return false;
  SaveVertex(v);
  // A sliding vertex is movable for the smoother only (Fixed keeps it out of the collapses).
  Fixed[v] = slides ? 0 : Fixed[v];
  const bool smoothed = Smoother.TrySmooth(v, Undo.Active);
  Fixed[v] = slides ? 1 : Fixed[v];
  if (!smoothed)
    return false;
  ++Smoothed;
  return true;
}

// Removal of a vertex of the triangle's shortest metric edge (then the next shortest), into
// the other end: for a triangle squeezed by two sites too close together.
bool TriangleMeshImprover::TryCollapse(std::int32_t tri)
{
  const Tri t = Tris[tri];
  int order[3] = { 0, 1, 2 };
  std::sort(order,
    order + 3,
    [&](int i, int j)
    { return Work.EdgeLength(t[i], t[(i + 1) % 3]) < Work.EdgeLength(t[j], t[(j + 1) % 3]); });
  for (int k = 0; k < 2; ++k)
  {
    const std::int32_t a = t[order[k]], b = t[(order[k] + 1) % 3];
    if (CollapseInto(a, b) || CollapseInto(b, a))
      return true;
  }
  return false;
}

bool TriangleMeshImprover::CollapseInto(std::int32_t keep, std::int32_t remove)
{
  if (Fixed[remove])
    return false; // boundary, feature and non-manifold vertices stay
  std::vector<std::int32_t> shared, ringKeep, ringRemove;
  for (std::int32_t t : Star[remove])
    if (IndexIn(Tris[t], keep) >= 0)
      shared.push_back(t);
  if (shared.size() != 2)
    return false;
  for (std::int32_t t : Star[keep])
    for (std::int32_t w : Tris[t])
      ringKeep.push_back(w);
  for (std::int32_t t : Star[remove])
    for (std::int32_t w : Tris[t])
      ringRemove.push_back(w);
  std::sort(ringKeep.begin(), ringKeep.end());
  std::sort(ringRemove.begin(), ringRemove.end());
  ringKeep.erase(std::unique(ringKeep.begin(), ringKeep.end()), ringKeep.end());
  ringRemove.erase(std::unique(ringRemove.begin(), ringRemove.end()), ringRemove.end());
  std::vector<std::int32_t> common;
  std::set_intersection(ringKeep.begin(),
    ringKeep.end(),
    ringRemove.begin(),
    ringRemove.end(),
    std::back_inserter(common));
  // Link condition: only the two opposite vertices (and the edge's ends) are shared, so the
  // collapse keeps the mesh a manifold with the same topology.
  if (common.size() != 4)
    return false;
  if (Surface)
  {
    // The removed vertex must stay close to the fan that replaces its star, or the collapse
    // would cut into a strongly curved part (a thin tube) of the surface.
    double distance = std::numeric_limits<double>::infinity();
    for (std::int32_t t : Star[remove])
      if (IndexIn(Tris[t], keep) < 0)
      {
        Tri nt = Tris[t];
        nt[IndexIn(nt, remove)] = keep;
        distance = std::min(distance,
          (ClosestPointOnTriangle(P[remove], P[nt[0]], P[nt[1]], P[nt[2]]) - P[remove]).norm());
        // Each new triangle also keeps the orientation of the one it replaces, as a flip.
        const Eigen::Vector3d n0 =
          (P[Tris[t][1]] - P[Tris[t][0]]).cross(P[Tris[t][2]] - P[Tris[t][0]]);
        const Eigen::Vector3d n1 = (P[nt[1]] - P[nt[0]]).cross(P[nt[2]] - P[nt[0]]);
        if (!(n0.dot(n1) >= CosFlipDihedral * n0.norm() * n1.norm()))
          return false;
      }
    if (!(distance <= Options.SurfaceCollapseMaxDeviation * (P[keep] - P[remove]).norm()))
      return false;
  }
  Begin();
  const std::vector<std::int32_t> star = Star[remove];
  for (std::int32_t t : star)
  {
    Tri nt = Tris[t];
    StarErase(remove, t);
    if (IndexIn(nt, keep) >= 0)
    {
      for (std::int32_t w : nt)
        if (w != remove)
          StarErase(w, t);
      SetTri(t, { kDead, kDead, kDead });
      continue;
    }
    nt[IndexIn(nt, remove)] = keep;
    SetTri(t, nt);
    StarAdd(keep, t);
  }
  if (!FinishCompound(keep))
    return false;
  ++Collapses;
  return true;
}

// A new vertex at the middle of the triangle's longest metric edge (then the next longest),
// placed on the domain; on the 2D boundary it stays on the edge and is fixed.
bool TriangleMeshImprover::TrySplit(std::int32_t tri)
{
  const Tri t = Tris[tri];
  int order[3] = { 0, 1, 2 };
  std::sort(order,
    order + 3,
    [&](int i, int j)
    { return Work.EdgeLength(t[i], t[(i + 1) % 3]) > Work.EdgeLength(t[j], t[(j + 1) % 3]); });
  for (int k = 0; k < 2; ++k)
  {
    const int e = order[k];
    const std::int32_t a = t[e], b = t[(e + 1) % 3], c = t[(e + 2) % 3];
    int count = 0;
    const std::int32_t other = OtherTriangle(tri, a, b, &count);
    const bool boundary = count == 0;
    if (count > 1 || (Surface && (boundary || (Fixed[a] && Fixed[b]))))
      continue; // non-manifold; on surfaces the boundary and feature lines are not sampled
    const Eigen::Vector3d x = 0.5 * (P[a] + P[b]);
    Begin();
    const std::int32_t m =
      AddVertex(x, 0.5 * (S[a] + S[b]), (N[a] + N[b]).normalized(), boundary, Hint[a]);
    if (!Place(m, Hint[a], x))
    {
      Rollback();
      continue;
    }
    if (boundary)
      P[m] = x; // exactly on the boundary edge: the covered domain stays
    SetTri(tri, { a, m, c });
    StarErase(b, tri);
    StarAdd(m, tri);
    AddTri({ m, b, c });
    if (!boundary)
    {
      const Tri t2 = Tris[other];
      const std::int32_t d =
        t2[0] != a && t2[0] != b ? t2[0] : (t2[1] != a && t2[1] != b ? t2[1] : t2[2]);
      SetTri(other, { m, a, d });
      StarErase(b, other);
      StarAdd(m, other);
      AddTri({ b, m, d });
    }
    if (FinishCompound(m))
    {
      ++Splits;
      return true;
    }
  }
  return false;
}

bool TriangleMeshImprover::Improve(std::int32_t tri, double target)
{
  if (!Alive(tri) || Quality(Tris[tri]) >= target)
    return false;
  if (Options.Flips)
    for (int e = 0; e < 3; ++e)
      if (TryFlip(tri, e))
        return true;
  bool any = false;
  if (Options.Smoothing)
  {
    const Tri t = Tris[tri];
    for (std::int32_t v : t)
      any = TrySmooth(v) || any;
  }
  if (any && Quality(Tris[tri]) >= target)
    return true;
  if (Options.Collapses && TryCollapse(tri))
    return true;
  if (Options.Splits && TrySplit(tri))
    return true;
  return any;
}

void TriangleMeshImprover::Run(MeshImprovementResult& result)
{
  auto angle = [](double q) { return std::asin(std::max(-1.0, std::min(1.0, q))) * 180.0 / Pi; };
  result.WorstBefore = Tris.empty() ? 0.0 : angle(Work.WorstQuality());
  const double target = std::sin(Options.TargetAngle * Pi / 180.0);
  result.Passes += Work.ImproveWorstFirst(
    target, Options.MaxPasses, [&](std::int32_t t) { return Improve(t, target); });
  // Then the average: free vertices only (boundary and feature-line vertices stay).
  std::size_t meanSmoothed = 0;
  if (Options.Smoothing && !(Surface && !Options.PlacePoint))
  {
    std::vector<std::int32_t> vertices;
    for (std::int32_t v = 0; v < static_cast<std::int32_t>(P.size()); ++v)
      if (Work.CanMove(v))
        vertices.push_back(v);
    meanSmoothed = Smoother.MeanSmoothingSweeps(vertices);
  }
  result.WorstAfter = Tris.empty() ? 0.0 : angle(Work.WorstQuality());
  Work.WriteBack(Mesh);
  result.NumFlips22 = Flips;
  result.NumSmoothed = Smoothed + meanSmoothed;
  result.NumMeanSmoothed = meanSmoothed;
  result.NumSplits = Splits;
  result.NumCollapses = Collapses;
  result.Moved = std::move(Moved);
}

} // namespace av
