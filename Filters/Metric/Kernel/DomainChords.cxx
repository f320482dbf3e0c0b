// SPDX-License-Identifier: BSD-3-Clause
#include "DomainChords.h"

#include "MeshTopology.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Dense>

#include <cmath>
#include <limits>
#include <string>

namespace av
{
namespace
{
template <int D>
using Vec = Eigen::Matrix<double, D, 1>;
template <int D>
using Mat = Eigen::Matrix<double, D, D>;

template <int D>
std::vector<double> ChordDirections()
{
  std::vector<double> d;
  if constexpr (D == 3)
  {
    const int dirs[13][3] = { { 1, 0, 0 },
      { 0, 1, 0 },
      { 0, 0, 1 },
      { 1, 1, 0 },
      { 1, -1, 0 },
      { 1, 0, 1 },
      { 1, 0, -1 },
      { 0, 1, 1 },
      { 0, 1, -1 },
      { 1, 1, 1 },
      { 1, 1, -1 },
      { 1, -1, 1 },
      { -1, 1, 1 } };
    for (const auto& v : dirs)
    {
      const Vec<3> u = Vec<3>(v[0], v[1], v[2]).normalized();
      d.insert(d.end(), { u[0], u[1], u[2] });
    }
  }
  else
  {
    for (int k = 0; k < 8; ++k)
    {
      const double a = k * 3.14159265358979323846 / 8.0;
      d.insert(d.end(), { std::cos(a), std::sin(a) });
    }
  }
  return d;
}

template <int D>
Vec<D> PointOf(const SimplexMesh& mesh, std::int32_t i)
{
  return Eigen::Map<const Vec<D>>(mesh.Point(static_cast<std::size_t>(i)));
}

/// Distance from x (inside `cell`) along unit d to where the walk leaves the domain; +inf after
/// maxSteps elements. Barycentric coordinates along the ray are affine in t: the ray leaves an
/// element through the facet whose coordinate reaches 0 first.
template <int D>
double WalkToBoundary(const SimplexMesh& mesh,
  const std::vector<std::int32_t>& adjacency,
  std::int32_t cell,
  const Vec<D>& x,
  const Vec<D>& d,
  int maxSteps)
{
  double t = 0.0;
  std::int32_t previous = -1;
  for (int step = 0; step < maxSteps; ++step)
  {
    const std::int32_t* v = mesh.Cell(static_cast<std::size_t>(cell));
    const Vec<D> v0 = PointOf<D>(mesh, v[0]);
    Mat<D> edges;
    for (int a = 0; a < D; ++a)
      edges.col(a) = PointOf<D>(mesh, v[a + 1]) - v0;
    const Mat<D> inverse = edges.inverse();
    const Vec<D> l = inverse * (x + t * d - v0); // coordinates 1..D at the current point
    const Vec<D> m = inverse * d;                // their rates along the ray
    double lambda[D + 1], rate[D + 1];
    lambda[0] = 1.0 - l.sum();
    rate[0] = -m.sum();
    for (int a = 0; a < D; ++a)
    {
      lambda[a + 1] = l[a];
      rate[a + 1] = m[a];
    }
    int exitFacet = -1;
    double exitT = std::numeric_limits<double>::infinity();
    // Not back into the element we came from (round-off at the shared facet), unless no other
    // facet is ahead.
    for (int pass = 0; pass < 2 && exitFacet < 0; ++pass)
      for (int a = 0; a <= D; ++a)
      {
        const std::int32_t across = adjacency[static_cast<std::size_t>(cell) * (D + 1) + a];
        if (!(rate[a] < 0.0) || (pass == 0 && across >= 0 && across == previous))
          continue;
        const double dt = std::max(0.0, -lambda[a] / rate[a]);
        if (dt < exitT)
        {
          exitT = dt;
          exitFacet = a;
        }
      }
    if (exitFacet < 0 || !std::isfinite(exitT))
      return t; // degenerate element: stop where we are
    t += exitT;
    const std::int32_t next = adjacency[static_cast<std::size_t>(cell) * (D + 1) + exitFacet];
    if (next < 0)
      return t;
    previous = cell;
    cell = next;
  }
  return std::numeric_limits<double>::infinity();
}

template <int D>
DomainChords Compute(const SimplexMesh& mesh, int maxSteps)
{
  DomainChords r;
  r.Dimension = D;
  r.Directions = ChordDirections<D>();
  const std::size_t n = mesh.NumPoints(), nd = r.NumDirections();
  const std::vector<std::int32_t> adjacency = ComputeElementAdjacency(mesh);
  // The largest element of each vertex: its centroid is the interior point the chords go through.
  std::vector<std::int32_t> owner(n, -1);
  std::vector<double> ownerMeasure(n, -1.0);
  for (std::size_t c = 0; c < mesh.NumCells(); ++c)
  {
    const std::int32_t* v = mesh.Cell(c);
    Mat<D> edges;
    for (int a = 0; a < D; ++a)
      edges.col(a) = PointOf<D>(mesh, v[a + 1]) - PointOf<D>(mesh, v[0]);
    const double measure = std::abs(edges.determinant());
    for (int a = 0; a <= D; ++a)
      if (measure > ownerMeasure[static_cast<std::size_t>(v[a])])
      {
        ownerMeasure[static_cast<std::size_t>(v[a])] = measure;
        owner[static_cast<std::size_t>(v[a])] = static_cast<std::int32_t>(c);
      }
  }
  r.Chord.assign(n * nd, std::numeric_limits<double>::infinity());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256),
    [&](const tbb::blocked_range<std::size_t>& range)
    {
      for (std::size_t i = range.begin(); i != range.end(); ++i)
      {
        const std::int32_t c = owner[i];
        if (c < 0 || !(ownerMeasure[i] > 0.0))
          continue; // unused vertex or only degenerate elements: no limit
        const std::int32_t* v = mesh.Cell(static_cast<std::size_t>(c));
        Vec<D> x = Vec<D>::Zero();
        for (int a = 0; a <= D; ++a)
          x += PointOf<D>(mesh, v[a]);
        x /= D + 1;
        for (std::size_t k = 0; k < nd; ++k)
        {
          const Vec<D> d = Eigen::Map<const Vec<D>>(r.Directions.data() + k * D);
          r.Chord[i * nd + k] = WalkToBoundary<D>(mesh, adjacency, c, x, d, maxSteps) +
            WalkToBoundary<D>(mesh, adjacency, c, x, Vec<D>(-d), maxSteps);
        }
      }
    });
  return r;
}
} // namespace

DomainChords ComputeDomainChords(const SimplexMesh& mesh, int maxSteps)
{
  const std::string who = "domain chords: ";
  if (mesh.NumCells() == 0)
    throw InputError(who + "the mesh is empty");
  if (maxSteps < 1)
    throw InputError(who + "maxSteps must be >= 1");
  CheckCellIds(mesh, who, "cell");
  if (mesh.SimplexDim == 3 && mesh.AmbientDim == 3)
    return Compute<3>(mesh, maxSteps);
  if (mesh.SimplexDim == 2 && mesh.AmbientDim == 2)
    return Compute<2>(mesh, maxSteps);
  if (mesh.SimplexDim == 2 && mesh.AmbientDim == 3)
  {
    for (std::size_t i = 0; i < mesh.NumPoints(); ++i)
      if (mesh.Point(i)[2] != mesh.Point(0)[2])
        throw InputError(who + "a triangle mesh must be flat (one z)");
    SimplexMesh flat;
    flat.AmbientDim = 2;
    flat.SimplexDim = 2;
    flat.Cells = mesh.Cells;
    flat.Points.reserve(2 * mesh.NumPoints());
    for (std::size_t i = 0; i < mesh.NumPoints(); ++i)
      flat.Points.insert(flat.Points.end(), { mesh.Point(i)[0], mesh.Point(i)[1] });
    return Compute<2>(flat, maxSteps);
  }
  throw InputError(who + "needs tetrahedra in 3D or flat triangles");
}

} // namespace av
