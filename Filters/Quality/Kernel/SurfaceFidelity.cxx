// SPDX-License-Identifier: BSD-3-Clause
#include "SurfaceFidelity.h"

#include "TriangleBvh.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>

namespace av
{
namespace
{
using Vec3 = Eigen::Vector3d;

void CheckSurface(const SimplexMesh& s, const char* who)
{
  if (s.AmbientDim != 3 || s.SimplexDim != 2 || s.NumCells() == 0)
  {
    throw InputError(std::string(who) + ": needs a non-empty triangle surface in 3D");
  }
  for (std::int32_t v : s.Cells)
  {
    if (v < 0 || static_cast<std::size_t>(v) >= s.NumPoints())
    {
      throw InputError(std::string(who) + ": a triangle has a point id out of range");
    }
  }
}

Vec3 P(const SimplexMesh& s, std::int32_t v)
{
  return Vec3(s.Point(v)[0], s.Point(v)[1], s.Point(v)[2]);
}

double Diagonal(const SimplexMesh& s)
{
  Eigen::AlignedBox3d box;
  for (std::size_t i = 0; i < s.NumPoints(); ++i)
    box.extend(P(s, static_cast<std::int32_t>(i)));
  return box.diagonal().norm();
}

struct DistanceSums
{
  double Max = 0.0, Sum = 0.0;
  std::size_t Count = 0;
};

/// Max and sum of the distances of the barycentric grid points of `from` to `to`.
DistanceSums SampleDistances(const SimplexMesh& from, const TriangleBvh& to, int n)
{
  return tbb::parallel_reduce(
    tbb::blocked_range<std::size_t>(0, from.NumCells(), 256),
    DistanceSums{},
    [&](const tbb::blocked_range<std::size_t>& r, DistanceSums acc)
    {
      for (std::size_t t = r.begin(); t != r.end(); ++t)
      {
        const std::int32_t* v = from.Cell(t);
        const Vec3 a = P(from, v[0]), b = P(from, v[1]), c = P(from, v[2]);
        for (int i = 0; i <= n; ++i)
        {
          for (int j = 0; j <= n - i; ++j)
          {
            const Vec3 p = (double(i) * a + double(j) * b + double(n - i - j) * c) / double(n);
            const double d = std::sqrt(to.ClosestDistance2(p));
            acc.Max = std::max(acc.Max, d);
            acc.Sum += d;
            ++acc.Count;
          }
        }
      }
      return acc;
    },
    [](DistanceSums x, const DistanceSums& y)
    {
      x.Max = std::max(x.Max, y.Max);
      x.Sum += y.Sum;
      x.Count += y.Count;
      return x;
    });
}

/// Sign of det[b - a, c - a, d - a] (positive: d above the plane of a, b, c seen
/// counter-clockwise), double with Shewchuk's static filter, else binary128.
int Orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
  const Vec3 u = b - a, v = c - a, w = d - a;
  const double m1 = u[1] * v[2] - u[2] * v[1], m2 = u[2] * v[0] - u[0] * v[2],
               m3 = u[0] * v[1] - u[1] * v[0];
  const double det = w[0] * m1 + w[1] * m2 + w[2] * m3;
  const double permanent = std::abs(w[0]) * (std::abs(u[1] * v[2]) + std::abs(u[2] * v[1])) +
    std::abs(w[1]) * (std::abs(u[2] * v[0]) + std::abs(u[0] * v[2])) +
    std::abs(w[2]) * (std::abs(u[0] * v[1]) + std::abs(u[1] * v[0]));
  const double bound = 1.0e-15 * permanent; // > (7 + 56 eps) eps: Shewchuk's o3derrboundA
  if (det > bound)
    return 1;
  if (det < -bound)
    return -1;
  using Q = __float128;
  Q U[3], V[3], W[3];
  for (int k = 0; k < 3; ++k)
  {
    U[k] = static_cast<Q>(b[k]) - static_cast<Q>(a[k]); // exact: doubles differ by < 2^60
    V[k] = static_cast<Q>(c[k]) - static_cast<Q>(a[k]);
    W[k] = static_cast<Q>(d[k]) - static_cast<Q>(a[k]);
  }
  const Q q = W[0] * (U[1] * V[2] - U[2] * V[1]) + W[1] * (U[2] * V[0] - U[0] * V[2]) +
    W[2] * (U[0] * V[1] - U[1] * V[0]);
  return q > 0 ? 1 : (q < 0 ? -1 : 0);
}

/// Sign of the 2D orientation of (a, b, c) in the plane that drops coordinate `drop`.
int Orient2d(const Vec3& a, const Vec3& b, const Vec3& c, int drop)
{
  const int x = (drop + 1) % 3, y = (drop + 2) % 3;
  const double det = (b[x] - a[x]) * (c[y] - a[y]) - (b[y] - a[y]) * (c[x] - a[x]);
  const double bound =
    4.0e-16 * (std::abs((b[x] - a[x]) * (c[y] - a[y])) + std::abs((b[y] - a[y]) * (c[x] - a[x])));
  if (det > bound)
    return 1;
  if (det < -bound)
    return -1;
  using Q = __float128;
  const Q q = (static_cast<Q>(b[x]) - a[x]) * (static_cast<Q>(c[y]) - a[y]) -
    (static_cast<Q>(b[y]) - a[y]) * (static_cast<Q>(c[x]) - a[x]);
  return q > 0 ? 1 : (q < 0 ? -1 : 0);
}

bool SegmentsCross2d(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, int drop)
{
  const int s1 = Orient2d(p, q, a, drop), s2 = Orient2d(p, q, b, drop);
  const int s3 = Orient2d(a, b, p, drop), s4 = Orient2d(a, b, q, drop);
  if (s1 * s2 > 0 || s3 * s4 > 0)
    return false;
  if (s1 == 0 && s2 == 0) // collinear: overlap of the projections on the line
  {
    const int x = (drop + 1) % 3, y = (drop + 2) % 3;
    const int axis = std::abs(q[x] - p[x]) >= std::abs(q[y] - p[y]) ? x : y;
    return std::max(std::min(p[axis], q[axis]), std::min(a[axis], b[axis])) <=
      std::min(std::max(p[axis], q[axis]), std::max(a[axis], b[axis]));
  }
  return true;
}

bool InsideTriangle2d(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, int drop)
{
  const int s1 = Orient2d(a, b, p, drop), s2 = Orient2d(b, c, p, drop),
            s3 = Orient2d(c, a, p, drop);
  return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}

/// Does segment pq meet triangle abc (boundary included)?
bool SegmentMeetsTriangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c)
{
  const int op = Orient3d(a, b, c, p), oq = Orient3d(a, b, c, q);
  if (op * oq > 0)
    return false;
  if (op == 0 && oq == 0)
  {
    int drop = 0;
    ((b - a).cross(c - a)).cwiseAbs().maxCoeff(&drop);
    return InsideTriangle2d(p, a, b, c, drop) || InsideTriangle2d(q, a, b, c, drop) ||
      SegmentsCross2d(p, q, a, b, drop) || SegmentsCross2d(p, q, b, c, drop) ||
      SegmentsCross2d(p, q, c, a, drop);
  }
  const int s1 = Orient3d(p, q, a, b), s2 = Orient3d(p, q, b, c), s3 = Orient3d(p, q, c, a);
  return !((s1 > 0 || s2 > 0 || s3 > 0) && (s1 < 0 || s2 < 0 || s3 < 0));
}

bool TrianglesIntersect(const std::array<Vec3, 3>& s, const std::array<Vec3, 3>& t)
{
  for (int k = 0; k < 3; ++k)
  {
    if (SegmentMeetsTriangle(s[k], s[(k + 1) % 3], t[0], t[1], t[2]) ||
      SegmentMeetsTriangle(t[k], t[(k + 1) % 3], s[0], s[1], s[2]))
      return true;
  }
  return false;
}

std::int32_t Find(std::vector<std::int32_t>& parent, std::int32_t x)
{
  while (parent[x] != x)
  {
    parent[x] = parent[parent[x]];
    x = parent[x];
  }
  return x;
}

/// SampledHausdorffDistance on trees already built (EvaluateSurfaceFidelity shares them).
HausdorffResult HausdorffWith(const SimplexMesh& surface,
  const SimplexMesh& reference,
  const TriangleBvh& toReference,
  const TriangleBvh& toSurface,
  int samplesPerEdge)
{
  const DistanceSums forward = SampleDistances(surface, toReference, samplesPerEdge);
  const DistanceSums backward = SampleDistances(reference, toSurface, samplesPerEdge);
  HausdorffResult r;
  r.ForwardMax = forward.Max;
  r.BackwardMax = backward.Max;
  r.Max = std::max(forward.Max, backward.Max);
  r.ForwardMean = forward.Count ? forward.Sum / static_cast<double>(forward.Count) : 0.0;
  r.Diagonal = Diagonal(reference);
  r.MaxPercent = r.Diagonal > 0.0 ? 100.0 * r.Max / r.Diagonal : 0.0;
  r.Samples = forward.Count + backward.Count;
  return r;
}

void CheckSamplesPerEdge(int samplesPerEdge)
{
  if (samplesPerEdge < 1 || samplesPerEdge > 64)
  {
    throw InputError("SampledHausdorffDistance: samplesPerEdge must be in [1, 64]");
  }
}

/// CountSelfIntersections with the surface's tree already built.
std::size_t SelfIntersectionsWith(const SimplexMesh& surface, const TriangleBvh& bvh)
{
  return tbb::parallel_reduce(
    tbb::blocked_range<std::size_t>(0, surface.NumCells(), 128),
    std::size_t(0),
    [&](const tbb::blocked_range<std::size_t>& r, std::size_t count)
    {
      for (std::size_t i = r.begin(); i != r.end(); ++i)
      {
        const std::int32_t* vi = surface.Cell(i);
        const std::array<Vec3, 3> s = { P(surface, vi[0]), P(surface, vi[1]), P(surface, vi[2]) };
        bvh.ForEachOverlapping(bvh.TriangleBox(static_cast<std::int32_t>(i)),
          [&](std::int32_t j)
          {
            if (static_cast<std::size_t>(j) <= i)
              return; // each pair once
            const std::int32_t* vj = surface.Cell(j);
            for (int a = 0; a < 3; ++a)
              for (int b = 0; b < 3; ++b)
                if (vi[a] == vj[b])
                  return; // adjacent: they share a vertex
            const std::array<Vec3, 3> t = {
              P(surface, vj[0]), P(surface, vj[1]), P(surface, vj[2])
            };
            count += TrianglesIntersect(s, t) ? 1 : 0;
          });
      }
      return count;
    },
    [](std::size_t x, std::size_t y) { return x + y; });
}

/// ClosestTriangleNormals with the reference's tree already built.
std::vector<double> NormalsWith(const SimplexMesh& surface,
  const SimplexMesh& reference,
  const TriangleBvh& bvh)
{
  std::vector<double> normals(3 * surface.NumPoints(), 0.0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, surface.NumPoints(), 512),
    [&](const tbb::blocked_range<std::size_t>& r)
    {
      for (std::size_t i = r.begin(); i != r.end(); ++i)
      {
        std::int32_t t = -1;
        bvh.ClosestDistance2(P(surface, static_cast<std::int32_t>(i)), &t);
        if (t < 0)
          continue;
        const std::int32_t* v = reference.Cell(static_cast<std::size_t>(t));
        const Vec3 a = P(reference, v[0]);
        const Vec3 n = (P(reference, v[1]) - a).cross(P(reference, v[2]) - a);
        const double len = n.norm();
        if (len > 0.0)
          Eigen::Map<Vec3>(normals.data() + 3 * i) = n / len;
      }
    });
  return normals;
}
/// Triangles of `surface` whose normal does not agree with that of the reference triangle
/// closest to their centroid. Per-vertex closest normals (CountFlippedTriangles with
/// NormalsWith) are ambiguous on a crease: every triangle sharing the crease edge is at
/// distance 0 from a vertex on it, so a triangle lying exactly in one face is flagged when its
/// crease vertices pick the other face's normal (turbine with the crease sites kept: 2 such
/// triangles, normal = the face's). This test has the opposite ambiguity: the centroid of a
/// triangle that cuts across a crease may project onto the face nearly perpendicular to it
/// (turbine, fandisk: normal products -0.05 and -0.01).
std::size_t FlippedAtCentroids(const SimplexMesh& surface,
  const SimplexMesh& reference,
  const TriangleBvh& bvh,
  std::vector<std::uint8_t>& flags)
{
  flags.assign(surface.NumCells(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, surface.NumCells(), 512),
    [&](const tbb::blocked_range<std::size_t>& range)
    {
      for (std::size_t t = range.begin(); t != range.end(); ++t)
      {
        const std::int32_t* v = surface.Cell(t);
        const Vec3 a = P(surface, v[0]), b = P(surface, v[1]), c = P(surface, v[2]);
        std::int32_t closest = -1;
        bvh.ClosestDistance2((a + b + c) / 3.0, &closest);
        if (closest < 0)
          continue;
        const std::int32_t* w = reference.Cell(static_cast<std::size_t>(closest));
        const Vec3 o = P(reference, w[0]);
        const Vec3 ref = (P(reference, w[1]) - o).cross(P(reference, w[2]) - o);
        flags[t] = (b - a).cross(c - a).dot(ref) > 0.0 ? 0 : 1;
      }
    });
  return static_cast<std::size_t>(std::count(flags.begin(), flags.end(), std::uint8_t(1)));
}
} // namespace

HausdorffResult SampledHausdorffDistance(const SimplexMesh& surface,
  const SimplexMesh& reference,
  int samplesPerEdge)
{
  CheckSurface(surface, "SampledHausdorffDistance");
  CheckSurface(reference, "SampledHausdorffDistance");
  CheckSamplesPerEdge(samplesPerEdge);
  const TriangleBvh toReference(reference), toSurface(surface);
  return HausdorffWith(surface, reference, toReference, toSurface, samplesPerEdge);
}

std::size_t CountSelfIntersections(const SimplexMesh& surface)
{
  CheckSurface(surface, "CountSelfIntersections");
  const TriangleBvh bvh(surface);
  return SelfIntersectionsWith(surface, bvh);
}

std::vector<std::uint8_t> SelfIntersectingTriangles(const SimplexMesh& surface)
{
  CheckSurface(surface, "SelfIntersectingTriangles");
  const TriangleBvh bvh(surface);
  std::vector<std::uint8_t> flags(surface.NumCells(), 0);
  // Each triangle tests all its candidates and sets only its own flag: no shared writes.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, surface.NumCells(), 128),
    [&](const tbb::blocked_range<std::size_t>& r)
    {
      for (std::size_t i = r.begin(); i != r.end(); ++i)
      {
        const std::int32_t* vi = surface.Cell(i);
        const std::array<Vec3, 3> s = { P(surface, vi[0]), P(surface, vi[1]), P(surface, vi[2]) };
        bvh.ForEachOverlapping(bvh.TriangleBox(static_cast<std::int32_t>(i)),
          [&](std::int32_t j)
          {
            if (flags[i] || static_cast<std::size_t>(j) == i)
              return;
            const std::int32_t* vj = surface.Cell(j);
            for (int a = 0; a < 3; ++a)
              for (int b = 0; b < 3; ++b)
                if (vi[a] == vj[b])
                  return;
            const std::array<Vec3, 3> t = {
              P(surface, vj[0]), P(surface, vj[1]), P(surface, vj[2])
            };
            if (TrianglesIntersect(s, t))
              flags[i] = 1;
          });
      }
    });
  return flags;
}

std::size_t CountFlippedTriangles(const SimplexMesh& surface,
  const std::vector<double>& vertexNormals,
  std::vector<std::uint8_t>* flipped)
{
  CheckSurface(surface, "CountFlippedTriangles");
  if (vertexNormals.size() != 3 * surface.NumPoints())
  {
    throw InputError("CountFlippedTriangles: need 3 normal values per vertex");
  }
  if (flipped)
    flipped->assign(surface.NumCells(), 0);
  std::size_t count = 0;
  for (std::size_t t = 0; t < surface.NumCells(); ++t)
  {
    const std::int32_t* v = surface.Cell(t);
    const Vec3 a = P(surface, v[0]);
    const Vec3 n = (P(surface, v[1]) - a).cross(P(surface, v[2]) - a);
    Vec3 ref = Vec3::Zero();
    for (int k = 0; k < 3; ++k)
      ref += Eigen::Map<const Vec3>(vertexNormals.data() + 3 * v[k]);
    if (!(n.dot(ref) > 0.0))
    {
      ++count;
      if (flipped)
        (*flipped)[t] = 1;
    }
  }
  return count;
}

SurfaceTopology ComputeSurfaceTopology(const SimplexMesh& surface)
{
  CheckSurface(surface, "ComputeSurfaceTopology");
  std::vector<std::pair<std::int32_t, std::int32_t>> edges;
  edges.reserve(3 * surface.NumCells());
  std::vector<std::int32_t> parent(surface.NumPoints());
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<char> used(surface.NumPoints(), 0);
  for (std::size_t t = 0; t < surface.NumCells(); ++t)
  {
    const std::int32_t* v = surface.Cell(t);
    for (int k = 0; k < 3; ++k)
    {
      used[v[k]] = 1;
      edges.emplace_back(std::min(v[k], v[(k + 1) % 3]), std::max(v[k], v[(k + 1) % 3]));
      parent[Find(parent, v[k])] = Find(parent, v[(k + 1) % 3]);
    }
  }
  std::sort(edges.begin(), edges.end());
  SurfaceTopology topo;
  std::vector<std::int32_t> loopParent(surface.NumPoints());
  std::iota(loopParent.begin(), loopParent.end(), 0);
  std::vector<char> onBoundary(surface.NumPoints(), 0);
  std::size_t unique = 0;
  for (std::size_t i = 0; i < edges.size();)
  {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i])
      ++j;
    ++unique;
    if (j - i == 1)
    {
      ++topo.BoundaryEdges;
      onBoundary[edges[i].first] = onBoundary[edges[i].second] = 1;
      loopParent[Find(loopParent, edges[i].first)] = Find(loopParent, edges[i].second);
    }
    else if (j - i > 2)
    {
      ++topo.NonManifoldEdges;
    }
    i = j;
  }
  long long vertices = 0;
  for (std::size_t v = 0; v < used.size(); ++v)
  {
    vertices += used[v];
    const auto id = static_cast<std::int32_t>(v);
    topo.Components += used[v] && Find(parent, id) == id ? 1 : 0;
    topo.BoundaryLoops += onBoundary[v] && Find(loopParent, id) == id ? 1 : 0;
  }
  topo.Euler =
    vertices - static_cast<long long>(unique) + static_cast<long long>(surface.NumCells());
  return topo;
}

std::vector<double> ClosestTriangleNormals(const SimplexMesh& surface, const SimplexMesh& reference)
{
  CheckSurface(surface, "ClosestTriangleNormals");
  CheckSurface(reference, "ClosestTriangleNormals");
  const TriangleBvh bvh(reference);
  return NormalsWith(surface, reference, bvh);
}

SurfaceFidelityResult EvaluateSurfaceFidelity(const SimplexMesh& surface,
  const SimplexMesh* reference,
  int samplesPerEdge)
{
  SurfaceFidelityResult r;
  r.Topology = ComputeSurfaceTopology(surface); // checks `surface`
  const TriangleBvh toSurface(surface);         // one tree per surface, shared by the measures
  r.SelfIntersections = SelfIntersectionsWith(surface, toSurface);
  if (!reference)
    return r;
  r.HasReference = true;
  r.ReferenceTopology = ComputeSurfaceTopology(*reference);
  CheckSamplesPerEdge(samplesPerEdge);
  const TriangleBvh toReference(*reference);
  r.Hausdorff = HausdorffWith(surface, *reference, toReference, toSurface, samplesPerEdge);
  // Flipped by both tests: each alone flags unflipped triangles at creases (see
  // FlippedAtCentroids), a triangle that faces against the surface fails both.
  std::vector<std::uint8_t> byVertices;
  CountFlippedTriangles(surface, NormalsWith(surface, *reference, toReference), &byVertices);
  FlippedAtCentroids(surface, *reference, toReference, r.FlippedFlags);
  for (std::size_t t = 0; t < r.FlippedFlags.size(); ++t)
    r.FlippedFlags[t] = r.FlippedFlags[t] && byVertices[t] ? 1 : 0;
  r.Flipped = static_cast<std::size_t>(
    std::count(r.FlippedFlags.begin(), r.FlippedFlags.end(), std::uint8_t(1)));
  return r;
}

} // namespace av
