// SPDX-License-Identifier: BSD-3-Clause
// SurfaceFidelity: Hausdorff distances with known answers (parallel squares, a half square),
// self-intersection counts of crossing, coplanar, touching and separate triangle pairs and of
// generated surfaces, flipped-triangle counts, Euler characteristic and boundary loops of
// closed and open tori.
#include "AnisoTestChecks.h"
#include "SurfaceFidelity.h"
#include "SurfaceGenerators.h"
#include "TriangleBvh.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <initializer_list>

namespace
{
/// Unit square [0, 1]^2 at height z as an n x n grid of triangles; x in [0, width].
av::SimplexMesh Square(double z, int n, double width = 1.0)
{
  av::SimplexMesh m;
  m.AmbientDim = 3;
  m.SimplexDim = 2;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      m.Points.insert(m.Points.end(), { width * i / n, 1.0 * j / n, z });
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
    {
      const std::int32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      m.Cells.insert(m.Cells.end(), { a, b, d, a, d, c });
    }
  return m;
}

/// Two triangles, given as 6 points, as one mesh (they share no vertex).
av::SimplexMesh Pair(std::initializer_list<double> xyz)
{
  av::SimplexMesh m;
  m.AmbientDim = 3;
  m.SimplexDim = 2;
  m.Points = xyz;
  m.Cells = { 0, 1, 2, 3, 4, 5 };
  return m;
}

av::SimplexMesh Concatenate(const av::SimplexMesh& a, const av::SimplexMesh& b)
{
  av::SimplexMesh m = a;
  const auto offset = static_cast<std::int32_t>(a.NumPoints());
  m.Points.insert(m.Points.end(), b.Points.begin(), b.Points.end());
  for (std::int32_t v : b.Cells)
    m.Cells.push_back(v + offset);
  return m;
}
} // namespace

int TestSurfaceFidelity(int, char*[])
{
  // Closest point on a triangle: face, edge and vertex regions.
  {
    const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
    AV_CHECK(
      (av::ClosestPointOnTriangle({ 0.2, 0.2, 3 }, a, b, c) - Eigen::Vector3d(0.2, 0.2, 0)).norm() <
      1e-15);
    AV_CHECK(
      (av::ClosestPointOnTriangle({ 1, 1, 0 }, a, b, c) - Eigen::Vector3d(0.5, 0.5, 0)).norm() <
      1e-15);
    AV_CHECK((av::ClosestPointOnTriangle({ -1, -2, 1 }, a, b, c) - a).norm() < 1e-15);
    AV_CHECK(
      (av::ClosestPointOnTriangle({ 0.5, -1, 0 }, a, b, c) - Eigen::Vector3d(0.5, 0, 0)).norm() <
      1e-15);
  }

  // Hausdorff: two parallel squares 0.01 apart (different triangulations) are 0.01 apart.
  {
    const av::HausdorffResult h = av::SampledHausdorffDistance(Square(0.01, 7), Square(0.0, 10));
    AV_CHECK_NEAR(h.ForwardMax, 0.01, 1e-12);
    AV_CHECK_NEAR(h.BackwardMax, 0.01, 1e-12);
    AV_CHECK_NEAR(h.MaxPercent, 100.0 * 0.01 / std::sqrt(2.0), 1e-9);
    // Half a square against the whole: every point of the half is on the whole (forward 0),
    // the far edge of the whole is 0.5 from the half (backward).
    const av::HausdorffResult half =
      av::SampledHausdorffDistance(Square(0.0, 4, 0.5), Square(0.0, 8));
    AV_CHECK(half.ForwardMax < 1e-12);
    AV_CHECK_NEAR(half.BackwardMax, 0.5, 1e-12);
    // A torus of 120 x 60 against one of 240 x 120: the chords' sagitta, r (1 - cos(pi / 60))
    // at most for the tube, well below 0.5 % of the diagonal.
    const av::HausdorffResult t = av::SampledHausdorffDistance(
      av::MakeTorusSurface(3.0, 1.0, 120, 60), av::MakeTorusSurface(3.0, 1.0, 240, 120));
    AV_CHECK(t.Max > 1e-4 && t.Max < 4.0 * (1.0 - std::cos(3.14159265358979 / 60.0)));
    AV_CHECK(t.MaxPercent < 0.05);
  }

  // Self-intersections of pairs of triangles that share no vertex.
  {
    // Crossing: the second triangle pierces the first.
    AV_CHECK(av::CountSelfIntersections(
               Pair({ 0, 0, 0, 2, 0, 0, 0, 2, 0, 0.5, 0.5, -1, 0.5, 0.5, 1, 3, 3, 0.5 })) == 1);
    // Separate: the same, lifted above the first.
    AV_CHECK(av::CountSelfIntersections(
               Pair({ 0, 0, 0, 2, 0, 0, 0, 2, 0, 0.5, 0.5, 1, 0.5, 0.5, 3, 3, 3, 2 })) == 0);
    // Coplanar and overlapping; coplanar and apart.
    AV_CHECK(av::CountSelfIntersections(
               Pair({ 0, 0, 0, 2, 0, 0, 0, 2, 0, 0.2, 0.2, 0, 3, 0.2, 0, 0.2, 3, 0 })) == 1);
    AV_CHECK(av::CountSelfIntersections(
               Pair({ 0, 0, 0, 2, 0, 0, 0, 2, 0, 1.1, 1.1, 0, 3, 1.1, 0, 1.1, 3, 0 })) == 0);
    // Coplanar, one inside the other (no edges cross: only the containment test sees it).
    AV_CHECK(av::CountSelfIntersections(
               Pair({ 0, 0, 0, 2, 0, 0, 0, 2, 0, 0.2, 0.2, 0, 0.5, 0.2, 0, 0.2, 0.5, 0 })) == 1);
    // A vertex exactly on the other triangle's interior (touching counts).
    AV_CHECK(av::CountSelfIntersections(
               Pair({ 0, 0, 0, 2, 0, 0, 0, 2, 0, 0.5, 0.5, 0, 0.5, 0.5, 1, 1, 1, 1 })) == 1);
    // Nearly touching: 1e-13 above the plane is apart (the predicates are not fooled).
    AV_CHECK(av::CountSelfIntersections(
               Pair({ 0, 0, 0, 2, 0, 0, 0, 2, 0, 0.5, 0.5, 1e-13, 0.5, 0.5, 1, 1, 1, 1 })) == 0);
    // Generated surfaces are embedded; a torus overlapping a shifted copy of itself is not.
    const av::SimplexMesh torus = av::MakeTorusSurface(3.0, 1.0, 60, 30);
    AV_CHECK(av::CountSelfIntersections(torus) == 0);
    AV_CHECK(av::CountSelfIntersections(av::MakeDupinCyclideSurface(2.0, 1.9, 1.95, 90, 72)) == 0);
    av::SimplexMesh shifted = torus;
    for (std::size_t i = 0; i < shifted.NumPoints(); ++i)
      shifted.Points[3 * i] += 1.0;
    const av::SimplexMesh both = Concatenate(torus, shifted);
    AV_CHECK(av::CountSelfIntersections(both) > 100);
    // The flags mark the triangles of those pairs: none on the embedded torus; on the two
    // tori, only triangles of the overlap (those where the shifted copy crosses the first), in
    // both copies, and each flagged triangle really crosses one of the other copy.
    const std::vector<std::uint8_t> none = av::SelfIntersectingTriangles(torus);
    AV_CHECK(none.size() == torus.NumCells() &&
      std::count(none.begin(), none.end(), std::uint8_t(1)) == 0);
    const std::vector<std::uint8_t> flags = av::SelfIntersectingTriangles(both);
    const std::size_t n = torus.NumCells();
    const auto first = std::count(flags.begin(), flags.begin() + static_cast<std::ptrdiff_t>(n), 1);
    const auto second = std::count(flags.begin() + static_cast<std::ptrdiff_t>(n), flags.end(), 1);
    AV_CHECK_MSG(first > 10 && second > 10 && first + second < static_cast<std::ptrdiff_t>(n),
      first << " + " << second << " flagged of " << 2 * n);
    for (std::size_t t = 0; t < 2 * n; t += 97)
    {
      av::SimplexMesh pair = both;
      pair.Cells.clear();
      const std::size_t lo = t < n ? n : 0;
      pair.Cells.insert(
        pair.Cells.end(), both.Cells.begin() + 3 * t, both.Cells.begin() + 3 * t + 3);
      pair.Cells.insert(
        pair.Cells.end(), both.Cells.begin() + 3 * lo, both.Cells.begin() + 3 * (lo + n));
      // The triangle against the other copy alone: crossings with it are its own pairs.
      AV_CHECK((av::CountSelfIntersections(pair) > 0) == (flags[t] == 1));
    }
    // Two triangles that cross: both flagged.
    const std::vector<std::uint8_t> two = av::SelfIntersectingTriangles(
      Pair({ 0, 0, 0, 2, 0, 0, 0, 2, 0, 0.5, 0.5, -1, 0.5, 0.5, 1, 3, 3, 0.5 }));
    AV_CHECK(two.size() == 2 && two[0] == 1 && two[1] == 1);
  }

  // Flipped triangles against reference normals (+z): one reversed triangle of a square.
  {
    av::SimplexMesh sq = Square(0.0, 3);
    std::vector<double> up(3 * sq.NumPoints(), 0.0);
    for (std::size_t i = 0; i < sq.NumPoints(); ++i)
      up[3 * i + 2] = 1.0;
    AV_CHECK(av::CountFlippedTriangles(sq, up) == 0);
    std::swap(sq.Cells[3 * 4 + 1], sq.Cells[3 * 4 + 2]);
    std::vector<std::uint8_t> flags;
    AV_CHECK(av::CountFlippedTriangles(sq, up, &flags) == 1 && flags[4] == 1);
    AV_CHECK_THROWS(av::CountFlippedTriangles(sq, std::vector<double>(3)));
  }

  // Reference normals from the closest reference triangle, and all measures at once: a fine
  // sphere against a coarser one. One reversed triangle is found; a reversed reference flips all.
  {
    av::SimplexMesh fine = av::MakeIcosphere(1.0, 3);
    const av::SimplexMesh coarse = av::MakeIcosphere(1.0, 2);
    const std::vector<double> n = av::ClosestTriangleNormals(fine, coarse);
    for (std::size_t i = 0; i < fine.NumPoints(); ++i)
    {
      const Eigen::Vector3d p(fine.Point(i)[0], fine.Point(i)[1], fine.Point(i)[2]);
      AV_CHECK(Eigen::Map<const Eigen::Vector3d>(n.data() + 3 * i).dot(p.normalized()) > 0.95);
    }
    AV_CHECK(av::CountFlippedTriangles(fine, n) == 0);
    std::swap(fine.Cells[3 * 17 + 1], fine.Cells[3 * 17 + 2]);
    const av::SurfaceFidelityResult f = av::EvaluateSurfaceFidelity(fine, &coarse);
    AV_CHECK(f.HasReference && f.Flipped == 1 && f.FlippedFlags.size() == fine.NumCells() &&
      f.FlippedFlags[17] == 1);
    AV_CHECK(f.Topology.Euler == 2 && f.ReferenceTopology.Euler == 2 && f.SelfIntersections == 0);
    AV_CHECK(f.Hausdorff.Max > 1e-3 && f.Hausdorff.MaxPercent < 5.0);
    av::SimplexMesh inward = coarse;
    for (std::size_t t = 0; t < inward.NumCells(); ++t)
      std::swap(inward.Cells[3 * t + 1], inward.Cells[3 * t + 2]);
    AV_CHECK(av::EvaluateSurfaceFidelity(fine, &inward).Flipped == fine.NumCells() - 1);
    const av::SurfaceFidelityResult alone = av::EvaluateSurfaceFidelity(fine, nullptr);
    AV_CHECK(!alone.HasReference && alone.Flipped == 0 && alone.Topology.Euler == 2);
  }

  // A sharp crease (a sheet folded back over itself, normals 150 degrees apart): a triangle
  // lying in the lower face, correctly oriented, whose two vertices on the crease are nearest
  // the upper face. Its per-vertex reference normals call it flipped, the one at its centroid
  // does not: it is not counted. Reversed inside the lower face, it is.
  {
    const double c30 = std::cos(M_PI / 6.0), s30 = 0.5;
    av::SimplexMesh fold;
    fold.AmbientDim = 3;
    fold.SimplexDim = 2;
    fold.Points = { 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 1, c30, s30, 0, c30, s30 };
    fold.Cells = { 0, 2, 1, 0, 3, 2, 0, 1, 4, 0, 4, 5 }; // lower normals -z, upper (0, -1/2, c30)
    const double e = 1e-6;
    av::SimplexMesh tri;
    tri.AmbientDim = 3;
    tri.SimplexDim = 2;
    tri.Points = { 0.2, c30 * e, s30 * e, 0.5, 0.6, 0.0, 0.8, c30 * e, s30 * e };
    tri.Cells = { 0, 1, 2 }; // normal -z
    AV_CHECK(av::CountFlippedTriangles(tri, av::ClosestTriangleNormals(tri, fold)) == 1);
    AV_CHECK(av::EvaluateSurfaceFidelity(tri, &fold).Flipped == 0);
    av::SimplexMesh inside = tri;
    inside.Points = { 0.2, 0.2, 0.0, 0.5, 0.6, 0.0, 0.8, 0.2, 0.0 };
    AV_CHECK(av::EvaluateSurfaceFidelity(inside, &fold).Flipped == 0);
    std::swap(inside.Cells[1], inside.Cells[2]);
    AV_CHECK(av::EvaluateSurfaceFidelity(inside, &fold).Flipped == 1);
  }

  // Topology: closed torus (chi 0), half torus (a tube: chi 0, 2 loops), a quarter patch (a
  // disk: chi 1, 1 loop), a cyclide (chi 0), a sphere (chi 2).
  {
    const auto closed = av::ComputeSurfaceTopology(av::MakeTorusSurface(3.0, 1.0, 40, 20));
    AV_CHECK(closed.Euler == 0 && closed.BoundaryLoops == 0 && closed.Components == 1 &&
      closed.NonManifoldEdges == 0 && closed.BoundaryEdges == 0);
    const auto tube = av::ComputeSurfaceTopology(av::MakeTorusSurface(3.0, 1.0, 40, 20, 0.5));
    AV_CHECK(tube.Euler == 0 && tube.BoundaryLoops == 2 && tube.BoundaryEdges == 40);
    const auto disk = av::ComputeSurfaceTopology(av::MakeTorusSurface(3.0, 1.0, 40, 20, 0.5, 0.5));
    AV_CHECK(disk.Euler == 1 && disk.BoundaryLoops == 1 && disk.BoundaryEdges == 2 * (40 + 20));
    AV_CHECK(av::ComputeSurfaceTopology(av::MakeDupinCyclideSurface(2, 1, 1.5, 30, 20)).Euler == 0);
    AV_CHECK(av::ComputeSurfaceTopology(av::MakeIcosphere(1.0, 2)).Euler == 2);
    // Two tori: 2 components, chi 0.
    const av::SimplexMesh t = av::MakeTorusSurface(3.0, 1.0, 20, 10);
    AV_CHECK(av::ComputeSurfaceTopology(Concatenate(t, t)).Components == 2);
  }

  // Bad input.
  {
    av::SimplexMesh tets;
    tets.SimplexDim = 3;
    tets.Points = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1 };
    tets.Cells = { 0, 1, 2, 3 };
    AV_CHECK_THROWS(av::CountSelfIntersections(tets));
    AV_CHECK_THROWS(av::SampledHausdorffDistance(Square(0, 2), tets));
    av::SimplexMesh bad = Square(0, 2);
    bad.Cells[0] = 99;
    AV_CHECK_THROWS(av::ComputeSurfaceTopology(bad));
    AV_CHECK_THROWS(av::SampledHausdorffDistance(Square(0, 2), Square(0, 2), 0));
  }
  return AV_TEST_RESULT();
}
