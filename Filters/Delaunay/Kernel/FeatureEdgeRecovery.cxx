// SPDX-License-Identifier: BSD-3-Clause
#include "FeatureEdgeRecovery.h"

#include "FeatureSiteLookup.h"
#include "MeshTopology.h"
#include "TriangleBvh.h"

#include <Eigen/Dense>

#include <algorithm>
#include <memory>
#include <unordered_map>
#include <unordered_set>
#include <utility>

namespace av
{
namespace
{
/// The sites on each feature edge (parameter from its first point) and at feature vertices.
struct SitesOnFeatures
{
  std::vector<std::vector<std::pair<double, std::int32_t>>> OnEdge; // per feature edge, sorted
  std::unordered_map<std::int32_t, std::int32_t> AtVertex;          // mesh point -> site
};

SitesOnFeatures LocateFeatureSites(
  const SimplexMesh& mesh, const SharpFeatures& features, const SiteSet& sites)
{
  SitesOnFeatures on;
  on.OnEdge.resize(features.NumEdges());
  const FeatureSiteLookup lookup(features);
  const bool hasVertexEdges = features.PointEdgeOffsets.size() == mesh.NumPoints() + 1;
  for (std::size_t s = 0; s < sites.NumSites(); ++s)
  {
    const std::int32_t cell = sites.CellIds[s];
    if (cell < 0 || static_cast<std::size_t>(cell) >= mesh.NumCells())
      continue;
    const std::int32_t* tri = mesh.Cell(static_cast<std::size_t>(cell));
    const double* b = sites.Bary.data() + 4 * s;
    int zeros = 0, one = -1;
    for (int i = 0; i < 3; ++i)
    {
      if (b[i] == 0.0)
        ++zeros;
      else
        one = i;
    }
    if (zeros == 1)
    {
      double t = 0.0;
      const std::int32_t e = lookup.EdgeOfSite(mesh, sites, s, &t);
      if (e >= 0)
        on.OnEdge[static_cast<std::size_t>(e)].emplace_back(t, static_cast<std::int32_t>(s));
    }
    else if (zeros == 2 && hasVertexEdges)
    {
      const std::int32_t w = tri[one];
      if (features.PointEdgeOffsets[w + 1] > features.PointEdgeOffsets[w])
        on.AtVertex.emplace(w, static_cast<std::int32_t>(s));
    }
  }
  for (auto& list : on.OnEdge)
    std::sort(list.begin(), list.end());
  return on;
}
} // namespace

std::vector<std::array<std::int32_t, 2>> ConsecutiveFeatureSites(
  const SimplexMesh& mesh, const SharpFeatures& features, const SiteSet& sites)
{
  std::vector<std::array<std::int32_t, 2>> pairs;
  if (features.NumEdges() == 0 || features.PointEdgeOffsets.size() != mesh.NumPoints() + 1)
    return pairs;
  const SitesOnFeatures on = LocateFeatureSites(mesh, features, sites);
  auto degree = [&](std::int32_t w)
  { return features.PointEdgeOffsets[w + 1] - features.PointEdgeOffsets[w]; };
  auto siteAt = [&](std::int32_t w)
  {
    const auto it = on.AtVertex.find(w);
    return it == on.AtVertex.end() ? -1 : it->second;
  };
  // The other feature edge at point w, which has exactly two.
  auto otherEdgeAt = [&](std::int32_t w, std::int32_t e)
  {
    const std::int32_t* inc = features.PointEdges.data() + features.PointEdgeOffsets[w];
    return inc[0] == e ? inc[1] : inc[0];
  };
  // The first site met entering feature edge e at its point `from`, then on along the line.
  const std::size_t maxSteps = features.NumEdges();
  auto walk = [&](std::int32_t e, std::int32_t from) -> std::int32_t
  {
    for (std::size_t step = 0; step < maxSteps; ++step)
    {
      const std::int32_t u = features.Edges[2 * static_cast<std::size_t>(e)];
      const std::int32_t v = features.Edges[2 * static_cast<std::size_t>(e) + 1];
      const auto& list = on.OnEdge[static_cast<std::size_t>(e)];
      if (!list.empty())
        return from == u ? list.front().second : list.back().second;
      const std::int32_t to = from == u ? v : u;
      const std::int32_t at = siteAt(to);
      if (at >= 0)
        return at;
      if (degree(to) != 2)
        return -1;
      e = otherEdgeAt(to, e);
      from = to;
    }
    return -1;
  };
  // Leaving a line at point w (towards its other edges): the site there or beyond.
  auto beyond = [&](std::int32_t e, std::int32_t w) -> std::int32_t
  {
    const std::int32_t at = siteAt(w);
    if (at >= 0)
      return at;
    return degree(w) == 2 ? walk(otherEdgeAt(w, e), w) : -1;
  };
  auto add = [&](std::int32_t a, std::int32_t b)
  {
    if (a >= 0 && b >= 0 && a != b)
      pairs.push_back({ std::min(a, b), std::max(a, b) });
  };
  for (std::size_t e = 0; e < features.NumEdges(); ++e)
  {
    const auto& list = on.OnEdge[e];
    if (list.empty())
      continue;
    for (std::size_t i = 0; i + 1 < list.size(); ++i)
      add(list[i].second, list[i + 1].second);
    const std::int32_t ei = static_cast<std::int32_t>(e);
    add(list.front().second, beyond(ei, features.Edges[2 * e]));
    add(list.back().second, beyond(ei, features.Edges[2 * e + 1]));
  }
  for (const auto& corner : on.AtVertex)
  {
    const std::int32_t w = corner.first;
    for (std::int32_t q = features.PointEdgeOffsets[w]; q < features.PointEdgeOffsets[w + 1]; ++q)
      add(corner.second, walk(features.PointEdges[q], w));
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

FeatureEdgeRecoveryResult RecoverFeatureEdges(const SimplexMesh& mesh,
  const SiteSet& sites,
  const std::vector<std::array<std::int32_t, 2>>& required,
  RestrictedDelaunayMesh& rdt,
  int maxPasses)
{
  FeatureEdgeRecoveryResult r;
  r.Required = required.size();
  const std::size_t ns = rdt.Points.size() / 3;
  if (rdt.SimplexDim != 2 || rdt.AmbientDim != 3 || mesh.SimplexDim != 2 ||
    mesh.AmbientDim != 3 || required.empty())
  {
    return r;
  }
  std::vector<std::int32_t>& cells = rdt.Cells;
  const std::size_t nt = cells.size() / 3;
  // Edge -> its triangles (a third one marks the edge non-manifold), vertex -> triangles.
  struct EdgeTris
  {
    std::int32_t T[2] = { -1, -1 };
    int Count = 0;
  };
  std::unordered_map<std::uint64_t, EdgeTris> edges;
  edges.reserve(nt * 3);
  std::vector<std::vector<std::int32_t>> star(ns);
  for (std::size_t t = 0; t < nt; ++t)
  {
    const std::int32_t* v = cells.data() + 3 * t;
    for (int i = 0; i < 3; ++i)
    {
      EdgeTris& et = edges[EdgeKey(v[i], v[(i + 1) % 3])];
      if (et.Count < 2)
        et.T[et.Count] = static_cast<std::int32_t>(t);
      ++et.Count;
      star[static_cast<std::size_t>(v[i])].push_back(static_cast<std::int32_t>(t));
    }
  }
  std::unordered_set<std::uint64_t> requiredKeys;
  for (const auto& p : required)
    requiredKeys.insert(EdgeKey(p[0], p[1]));

  auto point = [&](std::int32_t s) { return Eigen::Map<const Eigen::Vector3d>(rdt.Points.data() + 3 * s); };
  auto inputNormal = [&](std::int32_t s)
  {
    const std::int32_t* e = mesh.Cell(static_cast<std::size_t>(sites.CellIds[s]));
    const Eigen::Map<const Eigen::Vector3d> a(mesh.Point(e[0])), b(mesh.Point(e[1])), c(mesh.Point(e[2]));
    return Eigen::Vector3d((b - a).cross(c - a));
  };
  std::unique_ptr<TriangleBvh> bvh; // built at the first flip tried (none when nothing is missing)
  auto normal = [&](std::int32_t p, std::int32_t q, std::int32_t o)
  { return Eigen::Vector3d((point(q) - point(p)).cross(point(o) - point(p))); };
  // Whether triangle (p, q, o) is not degenerate, faces the input's way at o and the way of the
  // two triangles it replaces (`before`: the sum of their unit normals; a site on a crease may
  // hold an input triangle of either face, so o's alone can be misleading).
  auto faces = [&](std::int32_t p, std::int32_t q, std::int32_t o, const Eigen::Vector3d& before)
  {
    const Eigen::Vector3d n = normal(p, q, o);
    const double scale = (point(q) - point(p)).squaredNorm() + (point(o) - point(p)).squaredNorm();
    if (!(n.norm() > 1e-9 * scale && n.dot(inputNormal(o)) > 0.0 && n.dot(before) > 0.0))
      return false;
    // And the way of the input triangle nearest its centroid (a triangle between two sites on
    // parallel creases lies on the narrow face between them, whose normal is neither's).
    std::int32_t nearest = -1;
    if (!bvh)
      bvh = std::make_unique<TriangleBvh>(mesh);
    bvh->ClosestDistance2((point(p) + point(q) + point(o)) / 3.0, &nearest);
    if (nearest < 0)
      return false;
    const std::int32_t* e = mesh.Cell(static_cast<std::size_t>(nearest));
    const Eigen::Map<const Eigen::Vector3d> x(mesh.Point(e[0])), y(mesh.Point(e[1])),
      z(mesh.Point(e[2]));
    return n.dot((y - x).cross(z - x)) > 0.0;
  };
  auto eraseFrom = [](std::vector<std::int32_t>& list, std::int32_t t)
  { list.erase(std::remove(list.begin(), list.end(), t), list.end()); };
  auto retarget = [&](std::int32_t a, std::int32_t b, std::int32_t from, std::int32_t to)
  {
    EdgeTris& et = edges[EdgeKey(a, b)];
    for (std::int32_t& t : et.T)
      if (t == from)
        t = to;
  };
  // One flip that makes (a, b) an edge, if the configuration allows it.
  auto tryFlip = [&](std::int32_t a, std::int32_t b)
  {
    for (std::int32_t t : star[static_cast<std::size_t>(a)])
    {
      std::int32_t* v = cells.data() + 3 * t;
      const int ia = v[0] == a ? 0 : (v[1] == a ? 1 : 2);
      const std::int32_t c = v[(ia + 1) % 3], d = v[(ia + 2) % 3];
      const auto it = edges.find(EdgeKey(c, d));
      if (it == edges.end() || it->second.Count != 2 || requiredKeys.count(it->first))
        continue;
      const std::int32_t t2 = it->second.T[0] == t ? it->second.T[1] : it->second.T[0];
      std::int32_t* w = cells.data() + 3 * t2;
      // t = (a, c, d); a consistently oriented t2 = (d, c, b) in some rotation.
      const int id = w[0] == d ? 0 : (w[1] == d ? 1 : (w[2] == d ? 2 : -1));
      if (id < 0 || w[(id + 1) % 3] != c || w[(id + 2) % 3] != b)
        continue;
      const Eigen::Vector3d before =
        normal(a, c, d).normalized() + normal(w[0], w[1], w[2]).normalized();
      if (!faces(b, a, c, before) || !faces(a, b, d, before)) // new (a, c, b) and (a, b, d)
        continue;
      v[0] = a, v[1] = c, v[2] = b;
      w[0] = a, w[1] = b, w[2] = d;
      edges.erase(it);
      EdgeTris ab;
      ab.T[0] = t, ab.T[1] = t2, ab.Count = 2;
      edges[EdgeKey(a, b)] = ab;
      retarget(c, b, t2, t);
      retarget(d, a, t, t2);
      eraseFrom(star[static_cast<std::size_t>(c)], t2);
      eraseFrom(star[static_cast<std::size_t>(d)], t);
      star[static_cast<std::size_t>(a)].push_back(t2);
      star[static_cast<std::size_t>(b)].push_back(t);
      return true;
    }
    return false;
  };

  std::vector<std::array<std::int32_t, 2>> missing;
  for (const auto& p : required)
  {
    if (p[0] < 0 || p[1] < 0 || static_cast<std::size_t>(p[0]) >= ns ||
      static_cast<std::size_t>(p[1]) >= ns)
      continue;
    if (edges.count(EdgeKey(p[0], p[1])))
      ++r.Present;
    else
      missing.push_back(p);
  }
  for (int pass = 0; pass < maxPasses && !missing.empty(); ++pass)
  {
    std::size_t flips = 0;
    std::vector<std::array<std::int32_t, 2>> still;
    for (const auto& p : missing)
    {
      if (edges.count(EdgeKey(p[0], p[1])))
        continue; // made by an earlier flip's neighbour? (not counted twice)
      if (tryFlip(p[0], p[1]) || tryFlip(p[1], p[0]))
      {
        ++flips;
        ++r.Recovered;
      }
      else
        still.push_back(p);
    }
    missing.swap(still);
    if (flips == 0)
      break;
  }
  r.Missing = missing.size();
  return r;
}

} // namespace av
