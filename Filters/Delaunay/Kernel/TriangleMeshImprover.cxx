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
constexpr std::int32_t kDead = -1;

int IndexIn(const std::array<std::int32_t, 3>& t, std::int32_t v)
{
  for (int i = 0; i < 3; ++i)
    if (t[i] == v)
      return i;
  return -1;
}

/// Two unit vectors orthogonal to n (and to each other): the plane a vertex moves in.
void TangentBasis(const Eigen::Vector3d& n, Eigen::Vector3d& t1, Eigen::Vector3d& t2)
{
  Eigen::Index axis = 0;
  n.cwiseAbs().minCoeff(&axis);
  t1 = Eigen::Vector3d::Unit(axis).cross(n).normalized();
  t2 = n.cross(t1).normalized();
}
} // namespace

TriangleMeshImprover::TriangleMeshImprover(SimplexMesh& mesh,
  std::vector<Eigen::Matrix3d> sqrtMetrics,
  const std::vector<std::uint8_t>* fixed,
  const MeshImprovementOptions& options)
  : Mesh(mesh)
  , Surface(mesh.AmbientDim == 3)
  , S(std::move(sqrtMetrics))
  , Options(options)
{
  const std::size_t np = mesh.NumPoints();
  const int dim = mesh.AmbientDim;
  P.resize(np);
  for (std::size_t i = 0; i < np; ++i)
    P[i] = Eigen::Vector3d(mesh.Point(i)[0], mesh.Point(i)[1], dim == 3 ? mesh.Point(i)[2] : 0.0);
  Star.resize(np);
  Fixed.assign(np, 0);
  if (fixed)
    for (std::size_t i = 0; i < np; ++i)
      Fixed[i] = (*fixed)[i] ? 1 : 0;
  Moved.assign(np, 0);
  Hint.resize(np);
  for (std::size_t i = 0; i < np; ++i)
    Hint[i] = static_cast<std::int32_t>(i);
  Tris.resize(mesh.NumCells());
  for (std::size_t c = 0; c < mesh.NumCells(); ++c)
  {
    const std::int32_t* v = mesh.Cell(c);
    Tris[c] = { v[0], v[1], v[2] };
    for (int i = 0; i < 3; ++i)
      Star[v[i]].push_back(static_cast<std::int32_t>(c));
  }
  // Orientation reference: +z in 2D; on a surface the domain's normal at the vertex, else the
  // area-weighted normal of its triangles.
  N.assign(np, Eigen::Vector3d::UnitZ());
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
  MarkBoundaryAndNonManifold();
}

double TriangleMeshImprover::Quality(const Tri& t) const
{
  return OrientedTriangleMetricQuality(
    P[t[0]], P[t[1]], P[t[2]], S[t[0]], S[t[1]], S[t[2]], N[t[0]] + N[t[1]] + N[t[2]]);
}

double TriangleMeshImprover::WorstQuality() const
{
  double worst = std::numeric_limits<double>::infinity();
  for (const Tri& t : Tris)
    if (t[0] != kDead)
      worst = std::min(worst, Quality(t));
  return worst;
}

double TriangleMeshImprover::StarWorst(std::int32_t v) const
{
  double worst = std::numeric_limits<double>::infinity();
  for (std::int32_t t : Star[v])
    worst = std::min(worst, Quality(Tris[t]));
  return worst;
}

// §5.1 edge length: Q_ab = (S_a + S_b) / 2.
double TriangleMeshImprover::EdgeLength(std::int32_t a, std::int32_t b) const
{
  return (0.5 * (S[a] + S[b]) * (P[b] - P[a])).norm();
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
      Fixed[edges[i].first] = Fixed[edges[i].second] = 1;
    i = j;
  }
}

bool TriangleMeshImprover::HasEdge(std::int32_t a, std::int32_t b) const
{
  for (std::int32_t t : Star[a])
    if (IndexIn(Tris[t], b) >= 0)
      return true;
  return false;
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
  if (!Options.PlacePoint(near, x.data(), placed, normal, metric))
    return false;
  P[v] = Eigen::Map<const Eigen::Vector3d>(placed);
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
  if (d == c || HasEdge(c, d))
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

// Steepest ascent of the worst triangle of v's star in the domain's tangent plane at v, each
// trial placed on the domain (on a surface: projected onto it), as TetMeshImprover::TrySmooth.
bool TriangleMeshImprover::TrySmooth(std::int32_t v)
{
  if (Fixed[v] || Star[v].empty() || (Surface && !Options.PlacePoint))
    return false;
  SaveVertex(v);
  const Eigen::Vector3d startP = P[v], startN = N[v];
  const Eigen::Matrix3d startS = S[v];
  double scale = std::numeric_limits<double>::infinity();
  for (std::int32_t t : Star[v])
    for (std::int32_t w : Tris[t])
      if (w != v)
        scale = std::min(scale, (P[w] - startP).norm());
  const double before = StarWorst(v);
  double current = before;
  for (int iter = 0; iter < 8; ++iter)
  {
    std::int32_t worstTri = Star[v][0];
    for (std::int32_t t : Star[v])
      if (Quality(Tris[t]) < Quality(Tris[worstTri]))
        worstTri = t;
    const double h = 1e-6 * scale;
    const Eigen::Vector3d hereP = P[v], hereN = N[v];
    const Eigen::Matrix3d hereS = S[v];
    Eigen::Vector3d t[2];
    TangentBasis(hereN, t[0], t[1]);
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    for (int k = 0; k < 2; ++k)
    {
      P[v] = hereP + h * t[k];
      const double qp = Quality(Tris[worstTri]);
      P[v] = hereP - h * t[k];
      const double qm = Quality(Tris[worstTri]);
      g += (qp - qm) / (2.0 * h) * t[k];
    }
    P[v] = hereP;
    const double gn = g.norm();
    if (!(gn > 0.0) || !std::isfinite(gn))
      break;
    bool stepped = false;
    for (double alpha = 0.2 * scale; alpha > 1e-4 * scale; alpha *= 0.5)
    {
      if (Place(v, Hint[v], hereP + (alpha / gn) * g))
      {
        const double q = StarWorst(v);
        if (q > current + 1e-12)
        {
          current = q;
          stepped = true;
          break;
        }
      }
      P[v] = hereP;
      N[v] = hereN;
      S[v] = hereS;
    }
    if (!stepped)
      break;
  }
  if (!Accepts(current, before) ||
    (!Undo.Active && Options.AcceptMove && !Options.AcceptMove(v, P[v].data())))
  {
    P[v] = startP;
    N[v] = startN;
    S[v] = startS;
    return false;
  }
  if (!Undo.Active)
    Moved[v] = 1;
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
    { return EdgeLength(t[i], t[(i + 1) % 3]) < EdgeLength(t[j], t[(j + 1) % 3]); });
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
    { return EdgeLength(t[i], t[(i + 1) % 3]) > EdgeLength(t[j], t[(j + 1) % 3]); });
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
  result.WorstBefore = Tris.empty() ? 0.0 : angle(WorstQuality());
  const double target = std::sin(Options.TargetAngle * Pi / 180.0);
  std::vector<std::pair<double, std::int32_t>> bad;
  for (int pass = 0; pass < Options.MaxPasses; ++pass)
  {
    bad.clear();
    for (std::size_t t = 0; t < Tris.size(); ++t)
      if (Alive(static_cast<std::int32_t>(t)))
      {
        const double q = Quality(Tris[t]);
        if (q < target)
          bad.emplace_back(q, static_cast<std::int32_t>(t));
      }
    std::sort(bad.begin(), bad.end());
    std::size_t changes = 0;
    for (const auto& item : bad)
      if (Improve(item.second, target))
        ++changes;
    ++result.Passes;
    if (changes == 0)
      break;
  }
  result.WorstAfter = Tris.empty() ? 0.0 : angle(WorstQuality());
  Mesh.Cells.clear();
  for (const Tri& t : Tris)
    if (t[0] != kDead)
      Mesh.Cells.insert(Mesh.Cells.end(), t.begin(), t.end());
  const int dim = Mesh.AmbientDim;
  Mesh.Points.resize(P.size() * static_cast<std::size_t>(dim));
  for (std::size_t i = 0; i < P.size(); ++i)
    if (Moved[i])
      for (int d = 0; d < dim; ++d)
        Mesh.Points[i * dim + d] = P[i][d];
  result.NumFlips22 = Flips;
  result.NumSmoothed = Smoothed;
  result.NumSplits = Splits;
  result.NumCollapses = Collapses;
  result.Moved = std::move(Moved);
}

} // namespace av
