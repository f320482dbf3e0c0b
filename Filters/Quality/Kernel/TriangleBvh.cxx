// SPDX-License-Identifier: BSD-3-Clause
#include "TriangleBvh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

namespace av
{

Eigen::Vector3d ClosestPointOnTriangle(const Eigen::Vector3d& p,
  const Eigen::Vector3d& a,
  const Eigen::Vector3d& b,
  const Eigen::Vector3d& c)
{
  // Voronoi regions of the vertices, then of the edges, else the face (Ericson, 5.1.5).
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0)
    return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3)
    return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0)
    return a + (d1 / (d1 - d3)) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6)
    return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0)
    return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double denom = va + vb + vc;
  if (!(std::abs(denom) > 0.0))
    return a; // degenerate triangle: every region test failed only by round-off
  return a + ab * (vb / denom) + ac * (vc / denom);
}

TriangleBvh::TriangleBvh(const SimplexMesh& surface)
  : Surface(surface)
{
  if (surface.AmbientDim != 3 || surface.SimplexDim != 2 || surface.NumCells() == 0)
  {
    throw InputError("TriangleBvh: needs a non-empty triangle surface in 3D");
  }
  const std::size_t n = surface.NumCells();
  if (n > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max() / 2))
  {
    throw InputError("TriangleBvh: too many triangles");
  }
  this->Boxes.resize(n);
  this->Centroids.resize(n);
  this->Order.resize(n);
  for (std::size_t t = 0; t < n; ++t)
  {
    Eigen::AlignedBox3d box;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k)
    {
      const std::int32_t v = surface.Cell(t)[k];
      if (v < 0 || static_cast<std::size_t>(v) >= surface.NumPoints())
      {
        throw InputError(
          "TriangleBvh: triangle " + std::to_string(t) + " has a point id out of range");
      }
      const Eigen::Map<const Eigen::Vector3d> p(surface.Point(v));
      box.extend(p);
      sum += p;
    }
    this->Boxes[t] = box;
    this->Centroids[t] = sum / 3.0;
    this->Order[t] = static_cast<std::int32_t>(t);
  }
  this->Nodes.reserve(2 * n);
  this->Nodes.emplace_back();
  this->Build(0, 0, static_cast<std::int32_t>(n), 0);
}

void TriangleBvh::Build(std::int32_t node, std::int32_t begin, std::int32_t end, int depth)
{
  Eigen::AlignedBox3d box, centers;
  for (std::int32_t k = begin; k < end; ++k)
  {
    box.extend(this->Boxes[this->Order[k]]);
    centers.extend(this->Centroids[this->Order[k]]);
  }
  this->Nodes[node].Box = box;
  if (end - begin <= 4 || depth >= 60)
  {
    this->Nodes[node].First = begin;
    this->Nodes[node].Count = end - begin;
    return;
  }
  int axis = 0;
  centers.sizes().maxCoeff(&axis);
  const std::int32_t mid = begin + (end - begin) / 2;
  std::nth_element(this->Order.begin() + begin,
    this->Order.begin() + mid,
    this->Order.begin() + end,
    [&](std::int32_t s, std::int32_t t)
    { return this->Centroids[s][axis] < this->Centroids[t][axis]; });
  const std::int32_t left = static_cast<std::int32_t>(this->Nodes.size());
  this->Nodes.emplace_back();
  this->Nodes.emplace_back();
  this->Nodes[node].First = left;
  this->Nodes[node].Count = 0;
  this->Build(left, begin, mid, depth + 1);
  this->Build(left + 1, mid, end, depth + 1);
}

double TriangleBvh::ClosestDistance2(const Eigen::Vector3d& p, std::int32_t* triangle) const
{
  double best = std::numeric_limits<double>::infinity();
  std::int32_t bestTriangle = -1;
  std::pair<double, std::int32_t> stack[128];
  int top = 0;
  stack[top++] = { this->Nodes[0].Box.squaredExteriorDistance(p), 0 };
  while (top > 0)
  {
    const auto [bound, id] = stack[--top];
    if (bound >= best)
      continue;
    const Node& n = this->Nodes[id];
    if (n.Count > 0)
    {
      for (std::int32_t k = n.First; k < n.First + n.Count; ++k)
      {
        const std::int32_t* v = this->Surface.Cell(this->Order[k]);
        const Eigen::Vector3d q = ClosestPointOnTriangle(p,
          Eigen::Map<const Eigen::Vector3d>(this->Surface.Point(v[0])),
          Eigen::Map<const Eigen::Vector3d>(this->Surface.Point(v[1])),
          Eigen::Map<const Eigen::Vector3d>(this->Surface.Point(v[2])));
        const double d2 = (q - p).squaredNorm();
        if (d2 < best)
        {
          best = d2;
          bestTriangle = this->Order[k];
        }
      }
      continue;
    }
    // Nearer child last, so it is popped first and tightens the bound sooner.
    const double dl = this->Nodes[n.First].Box.squaredExteriorDistance(p);
    const double dr = this->Nodes[n.First + 1].Box.squaredExteriorDistance(p);
    if (dl < dr)
    {
      stack[top++] = { dr, n.First + 1 };
      stack[top++] = { dl, n.First };
    }
    else
    {
      stack[top++] = { dl, n.First };
      stack[top++] = { dr, n.First + 1 };
    }
  }
  if (triangle)
    *triangle = bestTriangle;
  return best;
}

} // namespace av
