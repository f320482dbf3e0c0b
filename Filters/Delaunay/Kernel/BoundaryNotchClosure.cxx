// SPDX-License-Identifier: BSD-3-Clause
#include "BoundaryNotchClosure.h"

#include "MeshTopology.h"
#include "TriangleBvh.h"

#include <Eigen/Dense>

#include <algorithm>
#include <memory>
#include <unordered_map>

namespace av
{

std::vector<std::uint8_t> SitesOnOpenBoundary(const SimplexMesh& mesh,
  const std::vector<std::int32_t>& adjacency,
  const SiteSet& sites,
  double tolerance)
{
  const std::size_t ns = sites.NumSites();
  std::vector<std::uint8_t> on(ns, 0);
  if (mesh.SimplexDim != 2 || mesh.AmbientDim != 3 || adjacency.size() != 3 * mesh.NumCells())
    return on;
  // Input vertices on an open edge.
  std::vector<std::uint8_t> boundaryPoint(mesh.NumPoints(), 0);
  bool open = false;
  for (std::size_t c = 0; c < mesh.NumCells(); ++c)
    for (int i = 0; i < 3; ++i)
      if (adjacency[3 * c + i] < 0)
      {
        open = true;
        boundaryPoint[static_cast<std::size_t>(mesh.Cell(c)[(i + 1) % 3])] = 1;
        boundaryPoint[static_cast<std::size_t>(mesh.Cell(c)[(i + 2) % 3])] = 1;
      }
  if (!open)
    return on;
  for (std::size_t s = 0; s < ns; ++s)
  {
    const std::int32_t cell = sites.CellIds[s];
    if (cell < 0 || static_cast<std::size_t>(cell) >= mesh.NumCells())
      continue;
    const double* l = sites.Bary.data() + 4 * s;
    for (int i = 0; i < 3 && !on[s]; ++i)
    {
      // On edge i (opposite vertex i) of an open edge, or at a vertex of the open boundary.
      if (l[i] <= tolerance && adjacency[3 * static_cast<std::size_t>(cell) + i] < 0)
        on[s] = 1;
      else if (l[i] >= 1.0 - tolerance &&
        boundaryPoint[static_cast<std::size_t>(mesh.Cell(static_cast<std::size_t>(cell))[i])])
        on[s] = 1;
    }
  }
  return on;
}

BoundaryNotchResult CloseBoundaryNotches(const SimplexMesh& mesh,
  const SiteSet& sites,
  const std::vector<std::uint8_t>& onBoundary,
  RestrictedDelaunayMesh& rdt)
{
  BoundaryNotchResult r;
  const std::size_t ns = rdt.Points.size() / 3;
  if (rdt.SimplexDim != 2 || rdt.AmbientDim != 3 || mesh.SimplexDim != 2 ||
    mesh.AmbientDim != 3 || onBoundary.size() != ns || sites.NumSites() != ns ||
    std::find(onBoundary.begin(), onBoundary.end(), 1) == onBoundary.end())
    return r; // no site on an open boundary (a closed surface): nothing to follow
  std::vector<std::int32_t>& cells = rdt.Cells;
  // Undirected edge -> its triangle count and, for a boundary edge, its direction in its one
  // triangle. next / prev: a vertex's boundary edges out and in (-1 none, -2 more than one).
  struct Edge
  {
    int Count = 0;
    std::int32_t From = -1, Tri = -1;
  };
  std::unordered_map<std::uint64_t, Edge> edges;
  edges.reserve(cells.size());
  for (std::size_t t = 0; t < cells.size() / 3; ++t)
    for (int i = 0; i < 3; ++i)
    {
      Edge& e = edges[EdgeKey(cells[3 * t + i], cells[3 * t + (i + 1) % 3])];
      ++e.Count;
      e.From = cells[3 * t + i];
      e.Tri = static_cast<std::int32_t>(t);
    }
  std::vector<std::int32_t> next(ns, -1), prev(ns, -1);
  auto link = [](std::int32_t& slot, std::int32_t v) { slot = slot == -1 ? v : -2; };
  for (const auto& [key, e] : edges)
    if (e.Count == 1)
    {
      const std::int32_t lo = static_cast<std::int32_t>(key >> 32);
      const std::int32_t hi = static_cast<std::int32_t>(key & 0xffffffffu);
      const std::int32_t to = e.From == lo ? hi : lo;
      link(next[static_cast<std::size_t>(e.From)], to);
      link(prev[static_cast<std::size_t>(to)], e.From);
    }
  auto offBoundary = [&](std::int32_t v)
  { return (next[v] != -1 || prev[v] != -1) && !onBoundary[static_cast<std::size_t>(v)]; };
  std::vector<std::int32_t> queue;
  for (std::size_t v = 0; v < ns; ++v)
    if (offBoundary(static_cast<std::int32_t>(v)))
      queue.push_back(static_cast<std::int32_t>(v));
  r.Notches = queue.size();
  if (queue.empty())
    return r;

  auto point = [&](std::int32_t s)
  { return Eigen::Map<const Eigen::Vector3d>(rdt.Points.data() + 3 * s); };
  auto inputNormal = [&](std::int32_t cell)
  {
    const std::int32_t* e = mesh.Cell(static_cast<std::size_t>(cell));
    const Eigen::Map<const Eigen::Vector3d> a(mesh.Point(e[0])), b(mesh.Point(e[1])),
      c(mesh.Point(e[2]));
    return Eigen::Vector3d((b - a).cross(c - a));
  };
  auto triNormal = [&](std::int32_t t)
  {
    const std::int32_t* v = cells.data() + 3 * t;
    return Eigen::Vector3d((point(v[1]) - point(v[0])).cross(point(v[2]) - point(v[0])));
  };
  const TriangleBvh bvh(mesh);
  // The ear (a, c, b) over the boundary path a -> b -> c, if it lies along the surface: within
  // kMaxTilt of the triangles on a-b and b-c and of the input triangles at a, b, c and nearest
  // its centroid. Mere positivity is not enough: where the surface meets its boundary at a
  // right angle to the chord (the rim of an open tube), an ear across the rim's curve faces
  // nearly perpendicular to the surface and would span the tube's opening.
  constexpr double kMinCos = 0.5; // kMaxTilt = 60 degrees
  auto earFits = [&](std::int32_t a, std::int32_t b, std::int32_t c)
  {
    const Eigen::Vector3d n = (point(c) - point(a)).cross(point(b) - point(a));
    const double scale = (point(c) - point(a)).squaredNorm() + (point(b) - point(a)).squaredNorm();
    if (!(n.norm() > 1e-9 * scale))
      return false;
    const Eigen::Vector3d u = n.normalized();
    auto along = [&](const Eigen::Vector3d& m) { return u.dot(m.normalized()) >= kMinCos; };
    if (!along(triNormal(edges[EdgeKey(a, b)].Tri)) || !along(triNormal(edges[EdgeKey(b, c)].Tri)))
      return false;
    for (std::int32_t s : { a, b, c })
      if (!along(inputNormal(sites.CellIds[static_cast<std::size_t>(s)])))
        return false;
    std::int32_t nearest = -1;
    bvh.ClosestDistance2((point(a) + point(b) + point(c)) / 3.0, &nearest);
    return nearest >= 0 && along(inputNormal(nearest));
  };

  while (!queue.empty())
  {
    const std::int32_t b = queue.back();
    queue.pop_back();
    if (next[b] < 0 || prev[b] < 0)
      continue;
    const std::int32_t a = prev[b], c = next[b];
    if (a == c || next[a] != b || prev[c] != b || edges.count(EdgeKey(a, c)) || !earFits(a, b, c))
      continue;
    const std::int32_t t = static_cast<std::int32_t>(cells.size() / 3);
    cells.insert(cells.end(), { a, c, b });
    rdt.CellElement.push_back(sites.CellIds[static_cast<std::size_t>(b)]);
    rdt.Inverted.push_back(0);
    edges[EdgeKey(a, b)].Count = 2;
    edges[EdgeKey(b, c)].Count = 2;
    Edge& ac = edges[EdgeKey(a, c)];
    ac.Count = 1;
    ac.From = a;
    ac.Tri = t;
    next[a] = c;
    prev[c] = a;
    next[b] = prev[b] = -1;
    ++r.Closed;
    for (std::int32_t v : { a, c })
      if (!onBoundary[static_cast<std::size_t>(v)])
        queue.push_back(v);
  }
  for (std::size_t v = 0; v < ns; ++v)
    r.Left += offBoundary(static_cast<std::int32_t>(v)) ? 1 : 0;
  return r;
}

} // namespace av
