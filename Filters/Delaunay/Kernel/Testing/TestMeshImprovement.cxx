// SPDX-License-Identifier: BSD-3-Clause
// Tests of ImproveMesh: each operation on a hand-made bad configuration raises the worst
// quality (2-3 flip, 3-2 flip, edge removal of 4 and 5 tets, smoothing, 2-2 flip, triangle
// smoothing, the boundary 2-2 flip and the in-plane move on a planar boundary, refused across a
// crease, the slide along a straight crease, vertex insertion at a fixed sliver, the peel of a
// boundary sliver, the contraction of a squeezed interior vertex, the peel of a pinched ear);
// on perturbed grids nothing inverts, the volume and the boundary are kept
// exactly, every interior face stays shared by two tets, fixed vertices stay, the worst quality
// never drops; and the mutation hook that accepts worsening operations is caught by those checks.
#include "AnisoTestChecks.h"
#include "MeshImprovement.h"
#include "MeshQuality.h"
#include "MeshTopology.h"
#include "PropertyChecks.h"
#include "StructuredMeshes.h"
#include "TetMesher.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <map>
#include <random>
#include <vector>

using av_test::Checks;

namespace
{
const double Pi = 3.14159265358979323846;
const double Identity3[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
const double Identity2[4] = { 1, 0, 0, 1 };

av::MetricField IsotropicMetric(std::size_t n)
{
  av::MetricField m;
  m.Values.assign(6 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    m.Values[6 * i] = m.Values[6 * i + 1] = m.Values[6 * i + 2] = 1.0;
  return m;
}

// Worst (smallest) signed quality of the mesh's cells, isotropic metric.
double WorstQuality(const av::SimplexMesh& m)
{
  double worst = 1e300;
  for (std::size_t c = 0; c < m.NumCells(); ++c)
  {
    double p[4][3] = {};
    const double* pts[4];
    const double* sq[4];
    for (int i = 0; i <= m.SimplexDim; ++i)
    {
      for (int d = 0; d < m.AmbientDim; ++d)
        p[i][d] = m.Point(m.Cell(c)[i])[d];
      pts[i] = p[i];
      sq[i] = m.SimplexDim == 3 ? Identity3 : Identity2;
    }
    worst = std::min(worst, av::MetricSimplexQuality(m.SimplexDim, pts, sq));
  }
  return worst;
}

// Ring of n points on the unit circle (z = 0) and the apexes (0, 0, +-h): the n tets around
// the edge joining the apexes (edgeStar) or, for n = 3, the two tets on the ring's triangle.
av::SimplexMesh RingConfiguration(int n, double h, bool edgeStar)
{
  av::SimplexMesh m;
  for (int i = 0; i < n; ++i)
    m.Points.insert(m.Points.end(), { std::cos(2 * Pi * i / n), std::sin(2 * Pi * i / n), 0.0 });
  const std::int32_t d = n, e = n + 1;
  m.Points.insert(m.Points.end(), { 0.0, 0.0, h, 0.0, 0.0, -h });
  if (edgeStar)
    for (int i = 0; i < n; ++i)
      m.Cells.insert(m.Cells.end(), { e, d, i, (i + 1) % n });
  else
    m.Cells = { 0, 1, 2, d, 0, 2, 1, e };
  return m;
}

double Volume(const av::SimplexMesh& m)
{
  double v = 0.0;
  for (std::size_t c = 0; c < m.NumCells(); ++c)
    v += av::CellMeasure(m, c);
  return v;
}

// Sorted boundary faces (edges) and the multiplicity check of the interior ones.
std::vector<std::vector<std::int32_t>> BoundaryFaces(const av::SimplexMesh& m, bool& manifold)
{
  std::map<std::vector<std::int32_t>, int> count;
  const int k = m.SimplexDim + 1;
  for (std::size_t c = 0; c < m.NumCells(); ++c)
    for (int skip = 0; skip < k; ++skip)
    {
      std::vector<std::int32_t> f;
      for (int i = 0; i < k; ++i)
        if (i != skip)
          f.push_back(m.Cell(c)[i]);
      std::sort(f.begin(), f.end());
      ++count[f];
    }
  manifold = true;
  std::vector<std::vector<std::int32_t>> boundary;
  for (const auto& [f, n] : count)
  {
    if (n == 1)
      boundary.push_back(f);
    manifold = manifold && n <= 2;
  }
  return boundary;
}

std::size_t NumInverted(const av::SimplexMesh& m)
{
  std::size_t n = 0;
  for (std::size_t c = 0; c < m.NumCells(); ++c)
    n += av::CellMeasure(m, c) <= 0.0 ? 1 : 0;
  return n;
}

void TestFlips()
{
  av::MeshImprovementOptions flipsOnly;
  flipsOnly.Smoothing = false;
  flipsOnly.KeepEdgeLengths = false; // the configurations' edges are far from unit length
  { // 2-3: two flat tets (apexes at +-0.2) become three around the apex edge
    av::SimplexMesh m = RingConfiguration(3, 0.2, false);
    const double before = WorstQuality(m);
    const av::MeshImprovementResult r = av::ImproveMesh(m, IsotropicMetric(5), nullptr, flipsOnly);
    AV_CHECK(r.NumFlips23 == 1);
    AV_CHECK(m.NumCells() == 3);
    AV_CHECK_MSG(WorstQuality(m) > before + 0.2, before << " -> " << WorstQuality(m));
    AV_CHECK_NEAR(Volume(m), Volume(RingConfiguration(3, 0.2, false)), 1e-14);
  }
  // 3-2 flip and edge removal: n tall tets around a long edge become 2(n-2).
  for (int n = 3; n <= 5; ++n)
  {
    av::SimplexMesh m = RingConfiguration(n, 3.0, true);
    const double before = WorstQuality(m);
    const double volume = Volume(m);
    const av::MeshImprovementResult r =
      av::ImproveMesh(m, IsotropicMetric(n + 2), nullptr, flipsOnly);
    AV_CHECK_MSG(r.NumEdgeRemovals >= 1, "ring " << n);
    AV_CHECK_MSG(
      WorstQuality(m) > before, "ring " << n << ": " << before << " -> " << WorstQuality(m));
    AV_CHECK_NEAR(Volume(m), volume, 1e-14);
    AV_CHECK(NumInverted(m) == 0);
    // The apex edge is gone.
    bool hasEdge = false;
    for (std::size_t c = 0; c < m.NumCells(); ++c)
      hasEdge = hasEdge ||
        (std::count(m.Cell(c), m.Cell(c) + 4, n) && std::count(m.Cell(c), m.Cell(c) + 4, n + 1));
    AV_CHECK(!hasEdge);
  }
  { // Keeping edge lengths: the 2-3 flip's new edge (0.4 against a median of 1) is refused
    // for tets of 21.8 degrees (above EdgeLengthRuleMinAngle).
    av::SimplexMesh m = RingConfiguration(3, 0.2, false);
    av::MeshImprovementOptions keep = flipsOnly;
    keep.KeepEdgeLengths = true;
    AV_CHECK(av::ImproveMesh(m, IsotropicMetric(5), nullptr, keep).NumFlips23 == 0);
    AV_CHECK(m.NumCells() == 2);
    // Slivers of 5.7 degrees (apexes at +-0.05) are flipped anyway (new edge 0.1), unless the
    // rule binds at every angle.
    av::SimplexMesh flat = RingConfiguration(3, 0.05, false);
    AV_CHECK(av::ImproveMesh(flat, IsotropicMetric(5), nullptr, keep).NumFlips23 == 1);
    av::MeshImprovementOptions always = keep;
    always.EdgeLengthRuleMinAngle = 0.0;
    av::SimplexMesh strict = RingConfiguration(3, 0.05, false);
    AV_CHECK(av::ImproveMesh(strict, IsotropicMetric(5), nullptr, always).NumFlips23 == 0);
  }
  { // With flips off nothing changes.
    av::SimplexMesh m = RingConfiguration(3, 1.5, true);
    av::MeshImprovementOptions none = flipsOnly;
    none.Flips = false;
    const av::MeshImprovementResult r = av::ImproveMesh(m, IsotropicMetric(5), nullptr, none);
    AV_CHECK(r.NumEdgeRemovals == 0 && m.NumCells() == 3);
  }
  { // An anisotropic metric decides: stretched 4x along z, the h = 0.2 pair is already good
    // in the metric (apex height 0.8 there) and stays.
    av::SimplexMesh m = RingConfiguration(3, 0.2, false);
    av::MetricField metric = IsotropicMetric(5);
    for (int i = 0; i < 5; ++i)
      metric.Values[6 * i + 2] = 16.0;
    const av::MeshImprovementResult r = av::ImproveMesh(m, metric, nullptr, flipsOnly);
    AV_CHECK(r.NumFlips23 == 0 && m.NumCells() == 2);
  }
}

void TestSmoothing()
{
  // Regular octahedron with its center pulled towards a face: the 8 tets around the center.
  av::SimplexMesh m;
  m.Points = { 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0.35, 0.3, 0.3 };
  const std::int32_t c = 6;
  for (int sx = 0; sx < 2; ++sx)
    for (int sy = 0; sy < 2; ++sy)
      for (int sz = 0; sz < 2; ++sz)
      {
        std::array<std::int32_t, 4> t = { c, sx, 2 + sy, 4 + sz };
        if ((sx + sy + sz) % 2 == 0)
          std::swap(t[2], t[3]);
        m.Cells.insert(m.Cells.end(), t.begin(), t.end());
      }
  for (std::size_t k = 0; k < m.NumCells(); ++k)
    if (av::CellMeasure(m, k) < 0)
      std::swap(m.Cells[4 * k + 2], m.Cells[4 * k + 3]);
  const double before = WorstQuality(m);
  const double volume = Volume(m);
  av::MeshImprovementOptions smoothOnly;
  smoothOnly.Flips = false;
  smoothOnly.Insertions = false;
  smoothOnly.KeepEdgeLengths = false;
  av::SimplexMesh moved = m;
  const av::MeshImprovementResult r =
    av::ImproveMesh(moved, IsotropicMetric(7), nullptr, smoothOnly);
  AV_CHECK(r.NumSmoothed >= 1 && r.Moved[c] == 1);
  AV_CHECK_MSG(WorstQuality(moved) > before + 0.2, before << " -> " << WorstQuality(moved));
  AV_CHECK_NEAR(Volume(moved), volume, 1e-14);
  for (int i = 0; i < 6; ++i) // boundary vertices stay
    for (int d = 0; d < 3; ++d)
      AV_CHECK(moved.Points[3 * i + d] == m.Points[3 * i + d]);
  // Fixed: the center stays.
  std::vector<std::uint8_t> fixed(7, 0);
  fixed[c] = 1;
  av::SimplexMesh kept = m;
  av::ImproveMesh(kept, IsotropicMetric(7), &fixed, smoothOnly);
  AV_CHECK(kept.Points == m.Points);
  // A refusing AcceptMove keeps every point.
  smoothOnly.AcceptMove = [](std::int32_t, const double*) { return false; };
  av::SimplexMesh refused = m;
  AV_CHECK(av::ImproveMesh(refused, IsotropicMetric(7), nullptr, smoothOnly).NumSmoothed == 0);
  AV_CHECK(refused.Points == m.Points);
}

// Makes every tet of m positive (swaps two vertices of a negative one).
void Orient(av::SimplexMesh& m)
{
  for (std::size_t k = 0; k < m.NumCells(); ++k)
    if (av::CellMeasure(m, k) < 0)
      std::swap(m.Cells[4 * k + 2], m.Cells[4 * k + 3]);
}

void TestPlanarBoundary()
{
  av::MeshImprovementOptions flipsOnly;
  flipsOnly.Smoothing = false;
  flipsOnly.KeepEdgeLengths = false;
  // Boundary 2-2 flip: the long edge a b of the flat base quad (a, r0, b, r2) in z = 0, under
  // the apex r1, is replaced by the short diagonal r0 r2.
  auto pyramid = [](double baseZ)
  {
    av::SimplexMesh m;
    m.Points = { -1, 0, 0, 1, 0, 0, 0, -0.3, 0, 0, 0, 0.6, 0, 0.3, baseZ };
    m.Cells = { 0, 1, 2, 3, 0, 1, 3, 4 };
    Orient(m);
    return m;
  };
  {
    av::SimplexMesh m = pyramid(0.0);
    const double before = WorstQuality(m);
    const double volume = Volume(m);
    const av::MeshImprovementResult r = av::ImproveMesh(m, IsotropicMetric(5), nullptr, flipsOnly);
    AV_CHECK(r.NumBoundaryEdgeRemovals == 1 && m.NumCells() == 2);
    AV_CHECK_MSG(WorstQuality(m) > before + 0.1, before << " -> " << WorstQuality(m));
    AV_CHECK_NEAR(Volume(m), volume, 1e-15);
    AV_CHECK(NumInverted(m) == 0);
    bool manifold = false;
    const auto faces = BoundaryFaces(m, manifold);
    AV_CHECK(faces.size() == 6 && manifold);
    const std::vector<std::int32_t> newBase = { 0, 2, 4 }; // (a, r0, r2): on the plane z = 0
    AV_CHECK(std::find(faces.begin(), faces.end(), newBase) != faces.end());
    // Off: unchanged.
    av::SimplexMesh k = pyramid(0.0);
    av::MeshImprovementOptions off = flipsOnly;
    off.PlanarBoundary = false;
    AV_CHECK(av::ImproveMesh(k, IsotropicMetric(5), nullptr, off).NumEdgeRemovals == 0);
    AV_CHECK(k.Cells == pyramid(0.0).Cells);
  }
  { // A crease (r2 lifted by 0.2: the base folds by 34 degrees): the edge a b stays.
    av::SimplexMesh m = pyramid(0.2);
    av::MeshImprovementOptions any = flipsOnly;
    any.BoundaryFlipVolumeBudget = 1.0;
    const av::MeshImprovementResult r = av::ImproveMesh(m, IsotropicMetric(5), nullptr, any);
    AV_CHECK(r.NumEdgeRemovals == 0 && m.Cells == pyramid(0.2).Cells);
  }
  { // A curved base (r2 lifted by 0.02, 3.8 degrees): flipped when the volume budget allows,
    // and the volume changes by exactly the thin tet (a, b, r0, r2) between the two bases.
    const av::SimplexMesh start = pyramid(0.02);
    const double thin = 0.02 * 2.0 * 0.3 / 6.0; // |det(b - a, r0 - a, r2 - a)| / 6
    av::SimplexMesh kept = start;
    AV_CHECK(av::ImproveMesh(kept, IsotropicMetric(5), nullptr, flipsOnly).NumEdgeRemovals == 0);
    av::MeshImprovementOptions budget = flipsOnly;
    budget.BoundaryFlipVolumeBudget = 1.0;
    av::SimplexMesh m = start;
    const av::MeshImprovementResult r = av::ImproveMesh(m, IsotropicMetric(5), nullptr, budget);
    AV_CHECK(r.NumBoundaryEdgeRemovals == 1 && NumInverted(m) == 0);
    AV_CHECK_NEAR(r.BoundaryVolumeChange, thin / Volume(start), 1e-14);
    AV_CHECK_NEAR(std::abs(Volume(m) - Volume(start)), thin, 1e-15);
    av::MeshImprovementOptions planarOnly = budget;
    planarOnly.BoundaryFlipMaxDihedral = 0.0;
    av::SimplexMesh p = start;
    AV_CHECK(av::ImproveMesh(p, IsotropicMetric(5), nullptr, planarOnly).NumEdgeRemovals == 0);
  }
  // In-plane move: the center c of a square base in z = 0 under an apex, pulled towards a side;
  // it moves back in the plane, exactly (z stays 0), the volume stays.
  auto halfOctahedron = [](double centerZ)
  {
    av::SimplexMesh m;
    m.Points = { 1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0, 0, 0, 1, 0.6, 0.1, centerZ };
    for (std::int32_t i = 0; i < 4; ++i)
      m.Cells.insert(m.Cells.end(), { 5, i, (i + 1) % 4, 4 });
    Orient(m);
    return m;
  };
  av::MeshImprovementOptions smoothOnly;
  smoothOnly.Flips = false;
  smoothOnly.Insertions = false;
  smoothOnly.KeepEdgeLengths = false;
  {
    av::SimplexMesh m = halfOctahedron(0.0);
    const double before = WorstQuality(m);
    const double volume = Volume(m);
    const av::MeshImprovementResult r = av::ImproveMesh(m, IsotropicMetric(6), nullptr, smoothOnly);
    AV_CHECK(r.NumBoundarySmoothed >= 1 && r.NumBoundarySmoothed == r.NumSmoothed && r.Moved[5]);
    AV_CHECK_MSG(WorstQuality(m) > before + 0.2, before << " -> " << WorstQuality(m));
    AV_CHECK(m.Points[17] == 0.0);
    AV_CHECK(std::abs(m.Points[15]) < 0.3 && std::abs(m.Points[16]) < 0.3);
    AV_CHECK_NEAR(Volume(m), volume, 1e-15);
    for (int i = 0; i < 15; ++i) // the square's corners and the apex stay
      AV_CHECK(m.Points[i] == halfOctahedron(0.0).Points[i]);
    std::vector<std::uint8_t> fixed(6, 0);
    fixed[5] = 1; // a feature vertex stays
    av::SimplexMesh k = halfOctahedron(0.0);
    AV_CHECK(av::ImproveMesh(k, IsotropicMetric(6), &fixed, smoothOnly).NumSmoothed == 0);
  }
  { // On a curved boundary (a cap of the sphere |x - (0, 0, -20)| = 20) the center moves only
    // with ProjectToBoundary, and then stays on the sphere, within the volume budget.
    const double radius = 20.0;
    const Eigen::Vector3d center(0, 0, -radius);
    auto onSphere = [&](double x, double y)
    { return Eigen::Vector3d(x, y, std::sqrt(radius * radius - x * x - y * y) - radius); };
    av::SimplexMesh m = halfOctahedron(0.0);
    for (int i = 0; i < 6; ++i)
      if (i != 4)
      {
        const Eigen::Vector3d q = onSphere(m.Points[3 * i], m.Points[3 * i + 1]);
        m.Points[3 * i + 2] = q.z();
      }
    Orient(m);
    const av::SimplexMesh start = m;
    av::MeshImprovementOptions curved = smoothOnly;
    curved.BoundaryFlipVolumeBudget = 1.0;
    // The projection below knows the cap only, not the sides: no classification by it.
    curved.SnapToBoundary = false;
    curved.InputBoundaryMoves = false;
    av::SimplexMesh fixedCap = start;
    AV_CHECK(av::ImproveMesh(fixedCap, IsotropicMetric(6), nullptr, curved).NumSmoothed == 0);
    int calls = 0;
    curved.ProjectToBoundary =
      [&](std::int32_t v, const double* x, const double*, double* placed, double*)
    {
      ++calls;
      AV_CHECK(v == 5);
      const Eigen::Vector3d p = Eigen::Map<const Eigen::Vector3d>(x) - center;
      Eigen::Map<Eigen::Vector3d> out(placed);
      out = center + radius * p.normalized();
      return true;
    };
    const double before = WorstQuality(start);
    const av::MeshImprovementResult r = av::ImproveMesh(m, IsotropicMetric(6), nullptr, curved);
    AV_CHECK(calls > 0 && r.NumBoundarySmoothed >= 1 && r.Moved[5]);
    AV_CHECK_MSG(WorstQuality(m) > before + 0.2, before << " -> " << WorstQuality(m));
    const Eigen::Vector3d c(m.Points[15], m.Points[16], m.Points[17]);
    AV_CHECK_NEAR((c - center).norm(), radius, 1e-12);
    AV_CHECK(NumInverted(m) == 0);
    AV_CHECK_NEAR(r.BoundaryVolumeChange, std::abs(Volume(m) - Volume(start)) / Volume(start), 1e-12);
    // A budget of 0.1 % of the volume is far below this move's change: refused.
    av::MeshImprovementOptions small = curved;
    small.BoundaryFlipVolumeBudget = 1e-3;
    AV_CHECK(r.BoundaryVolumeChange > 1e-3);
    av::SimplexMesh k = start;
    AV_CHECK(av::ImproveMesh(k, IsotropicMetric(6), nullptr, small).NumSmoothed == 0);
    AV_CHECK(k.Points == start.Points);
  }
  { // Lifted off the plane of its neighbours the center is a crease vertex: it stays.
    av::SimplexMesh m = halfOctahedron(0.05);
    AV_CHECK(av::ImproveMesh(m, IsotropicMetric(6), nullptr, smoothOnly).NumSmoothed == 0);
    AV_CHECK(m.Points == halfOctahedron(0.05).Points);
  }
  { // The same center, 0.05 inside a domain whose boundary is the plane z = 0 (a site just
    // inside the boundary, its faces folded in): with SnapToBoundary it goes onto the plane,
    // which raises the worst tet, and the mesh then covers the domain's volume exactly.
    av::MeshImprovementOptions snap = smoothOnly;
    snap.BoundaryFlipVolumeBudget = 0.0; // the snap is not charged to the budget
    snap.InputBoundaryMoves = false;     // the corners are on the boundary (tested below)
    int calls = 0;
    Eigen::Vector3d target(0.0, 0.0, 0.0);
    bool toTarget = false;
    snap.ProjectToBoundary =
      [&](std::int32_t v, const double* x, const double*, double* placed, double* normal)
    {
      // The other vertices are corners of the domain: already on its boundary.
      const Eigen::Map<const Eigen::Vector3d> at(x);
      calls += v == 5 ? 1 : 0;
      const Eigen::Vector3d p = v != 5 ? Eigen::Vector3d(at)
        : toTarget                     ? target
                                       : Eigen::Vector3d(x[0], x[1], 0.0);
      Eigen::Map<Eigen::Vector3d>{ placed } = p;
      if (normal)
        Eigen::Map<Eigen::Vector3d>{ normal } = Eigen::Vector3d::UnitZ();
      return true;
    };
    const av::SimplexMesh start = halfOctahedron(0.05);
    av::SimplexMesh m = start;
    const double before = WorstQuality(m);
    const av::MeshImprovementResult r = av::ImproveMesh(m, IsotropicMetric(6), nullptr, snap);
    AV_CHECK(calls > 0 && r.NumBoundarySnaps == 1 && r.Moved[5]);
    AV_CHECK(m.Points[17] == 0.0);
    AV_CHECK_MSG(WorstQuality(m) > before, before << " -> " << WorstQuality(m));
    AV_CHECK_NEAR(Volume(m), 2.0 / 3.0, 1e-15); // the pyramid, base on the plane
    AV_CHECK(NumInverted(m) == 0);
    for (int i = 0; i < 15; ++i)
      AV_CHECK(m.Points[i] == start.Points[i]);
    // Off: the vertex stays.
    av::MeshImprovementOptions off = snap;
    off.SnapToBoundary = false;
    av::SimplexMesh k = start;
    AV_CHECK(av::ImproveMesh(k, IsotropicMetric(6), nullptr, off).NumBoundarySnaps == 0);
    AV_CHECK(k.Points == start.Points);
    // A boundary point that makes the star worse (next to a corner): refused.
    toTarget = true;
    target = Eigen::Vector3d(0.97, 0.0, 0.0);
    av::SimplexMesh w = start;
    AV_CHECK(av::ImproveMesh(w, IsotropicMetric(6), nullptr, snap).NumBoundarySnaps == 0);
    AV_CHECK(w.Points == start.Points);
  }
  { // InputBoundaryMoves: the center on the domain's boundary plane z = 0, one corner of the
    // square 0.3 inside the domain, so that the center's faces are folded (17 deg from their
    // mean plane: neither planar nor smooth). It moves only with the option, and then in the
    // domain's plane; the corners (feature sites) stay.
    av::SimplexMesh start = halfOctahedron(0.0);
    start.Points[2] = 0.3;
    Orient(start);
    std::vector<std::uint8_t> corners(6, 1);
    corners[5] = 0;
    av::MeshImprovementOptions onPlane = smoothOnly;
    onPlane.BoundaryFlipVolumeBudget = 1.0;
    onPlane.ProjectToBoundary =
      [&](std::int32_t v, const double* x, const double*, double* placed, double* normal)
    {
      const Eigen::Map<const Eigen::Vector3d> at(x);
      Eigen::Map<Eigen::Vector3d>{ placed } = v == 5 ? Eigen::Vector3d(x[0], x[1], 0.0) : Eigen::Vector3d(at);
      if (normal)
        Eigen::Map<Eigen::Vector3d>{ normal } = Eigen::Vector3d::UnitZ();
      return true;
    };
    av::MeshImprovementOptions off = onPlane;
    off.InputBoundaryMoves = false;
    av::SimplexMesh k = start;
    AV_CHECK(av::ImproveMesh(k, IsotropicMetric(6), &corners, off).NumSmoothed == 0);
    AV_CHECK(k.Points == start.Points);
    av::SimplexMesh m = start;
    const double before = WorstQuality(m);
    const av::MeshImprovementResult r = av::ImproveMesh(m, IsotropicMetric(6), &corners, onPlane);
    AV_CHECK(r.NumBoundarySmoothed >= 1 && r.Moved[5] && r.NumBoundarySnaps == 0);
    AV_CHECK(m.Points[17] == 0.0);
    AV_CHECK_MSG(WorstQuality(m) > before, before << " -> " << WorstQuality(m));
    AV_CHECK(NumInverted(m) == 0);
    for (int i = 0; i < 15; ++i)
      AV_CHECK(m.Points[i] == start.Points[i]);
  }
}

void TestTriangles()
{
  { // A quad split along its long diagonal: the flip takes the short one.
    av::SimplexMesh m;
    m.AmbientDim = m.SimplexDim = 2;
    m.Points = { 0, 0, 1, 0, 0.5, 0.3, 0.5, -0.3 };
    m.Cells = { 0, 1, 2, 1, 0, 3 };
    const double before = WorstQuality(m);
    av::MeshImprovementOptions o;
    o.Smoothing = false;
    const av::MeshImprovementResult r = av::ImproveMesh(m, IsotropicMetric(4), nullptr, o);
    AV_CHECK(r.NumFlips22 == 1);
    AV_CHECK(WorstQuality(m) > before + 0.3);
  }
  { // Hexagon with its center off: smoothing re-centers it.
    av::SimplexMesh m;
    m.AmbientDim = m.SimplexDim = 2;
    for (int i = 0; i < 6; ++i)
      m.Points.insert(m.Points.end(), { std::cos(Pi * i / 3), std::sin(Pi * i / 3) });
    m.Points.insert(m.Points.end(), { 0.6, 0.1 });
    for (int i = 0; i < 6; ++i)
      m.Cells.insert(m.Cells.end(), { 6, i, (i + 1) % 6 });
    const double before = WorstQuality(m);
    const double area = Volume(m);
    av::MeshImprovementOptions o;
    o.Flips = false;
    av::ImproveMesh(m, IsotropicMetric(7), nullptr, o);
    AV_CHECK_MSG(WorstQuality(m) > before + 0.3, before << " -> " << WorstQuality(m));
    AV_CHECK_NEAR(Volume(m), area, 1e-14);
  }
}

// A Kuhn grid with its interior vertices jittered (still valid), measured in a metric
// stretched along x.
av::SimplexMesh JitteredGrid(int n, unsigned seed)
{
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
  av::SimplexMesh m = av::MakeKuhnTetGrid(n, n, n, lo, hi);
  const std::vector<char> boundary = av::BoundaryVertexMask(m);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.3 / n, 0.3 / n);
  for (std::size_t i = 0; i < m.NumPoints(); ++i)
    if (!boundary[i])
      for (int d = 0; d < 3; ++d)
      {
        const double old = m.Points[3 * i + d];
        m.Points[3 * i + d] += u(rng);
        for (std::size_t c = 0; c < m.NumCells(); ++c) // undo a move that inverts
          if (std::count(m.Cell(c), m.Cell(c) + 4, static_cast<std::int32_t>(i)) &&
            av::CellMeasure(m, c) <= 0)
          {
            m.Points[3 * i + d] = old;
            break;
          }
      }
  return m;
}

// Coordinates of a point of the unit cube's surface that are 0 or 1 (bit d: x_d is 0 or 1).
int CubeFaceBits(const double* x)
{
  int bits = 0;
  for (int d = 0; d < 3; ++d)
    bits |= (x[d] == 0.0 || x[d] == 1.0) ? 1 << d : 0;
  return bits;
}

// The properties every run must keep; returns them instead of failing, so the mutation test
// can show they catch a worsening run. `unitCube`: the tets fill [0,1]^3 and boundary vertices
// of its faces may move in them (PlanarBoundary) and those of its edges along them
// (StraightCreases), so the boundary is checked as a surface: every boundary face lies in a face
// of the cube, the boundary area is kept, the cube's corners stay, the other boundary vertices
// stay on their face or edge.
Checks CheckRun(const av::SimplexMesh& before,
  const av::SimplexMesh& after,
  const std::vector<std::uint8_t>& fixed,
  const av::MeshImprovementResult& r,
  bool unitCube = false)
{
  Checks c;
  bool manifoldBefore = false, manifoldAfter = false;
  const auto facesBefore = BoundaryFaces(before, manifoldBefore);
  const auto facesAfter = BoundaryFaces(after, manifoldAfter);
  if (!unitCube)
    c.Expect(facesBefore == facesAfter, "same boundary faces");
  else
  {
    auto area = [](const av::SimplexMesh& m, const std::vector<std::vector<std::int32_t>>& fs)
    {
      double a = 0.0;
      for (const auto& f : fs)
      {
        double e[2][3];
        for (int k = 0; k < 2; ++k)
          for (int d = 0; d < 3; ++d)
            e[k][d] = m.Point(f[k + 1])[d] - m.Point(f[0])[d];
        const double n[3] = { e[0][1] * e[1][2] - e[0][2] * e[1][1],
          e[0][2] * e[1][0] - e[0][0] * e[1][2], e[0][0] * e[1][1] - e[0][1] * e[1][0] };
        a += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      }
      return a;
    };
    for (const auto& f : facesAfter)
    {
      // The three vertices share a coordinate that is 0 or 1 with the same value.
      bool inFace = false;
      for (int d = 0; d < 3; ++d)
      {
        const double v = after.Point(f[0])[d];
        inFace = inFace ||
          ((v == 0.0 || v == 1.0) && after.Point(f[1])[d] == v && after.Point(f[2])[d] == v);
      }
      c.Expect(inFace, "every boundary face in a face of the cube");
    }
    c.Expect(std::abs(area(after, facesAfter) - area(before, facesBefore)) < 1e-12,
      "boundary area kept");
  }
  c.Expect(manifoldAfter, "every interior face shared by exactly two cells");
  c.Expect(NumInverted(after) == 0, "no inverted cell");
  c.Expect(std::abs(Volume(after) - Volume(before)) < 1e-12, "volume kept");
  const std::vector<char> boundary = av::BoundaryVertexMask(before);
  for (std::size_t i = 0; i < before.NumPoints(); ++i)
  {
    const double* x0 = before.Point(i);
    const double* x1 = after.Point(i);
    const int bits = unitCube && boundary[i] ? CubeFaceBits(x0) : 0;
    const bool onCubeFaceOrEdge = bits != 0 && bits != 7;
    if ((boundary[i] && !onCubeFaceOrEdge) || fixed[i])
      for (int d = 0; d < before.AmbientDim; ++d)
        c.Expect(x1[d] == x0[d], "boundary and fixed points stay");
    else if (onCubeFaceOrEdge)
    {
      bool inside = true, kept = true;
      for (int k = 0; k < 3; ++k)
      {
        inside = inside && x1[k] >= 0.0 && x1[k] <= 1.0;
        kept = kept && (!(bits & (1 << k)) || x1[k] == x0[k]); // the coordinates that are 0 or 1
      }
      c.Expect(CubeFaceBits(x1) == bits && kept && inside,
        "face and edge points stay on their face or edge");
    }
  }
  c.Expect(r.WorstAfter >= r.WorstBefore, "the worst quality never drops");
  return c;
}

// Straight creases: a vertex of an edge of the cube, pulled towards a corner, slides back along
// the edge (both faces of the cube kept exactly), as a free vertex or a FeatureLinePoint; pinned,
// with StraightCreases off, or with a bent crease it stays, and the corner never moves.
void TestStraightCrease()
{
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
  const av::SimplexMesh grid = av::MakeKuhnTetGrid(4, 4, 4, lo, hi); // 3 x 3 x 3 cubes
  auto find = [&](double x, double y, double z)
  {
    for (std::size_t i = 0; i < grid.NumPoints(); ++i)
      if (std::abs(grid.Point(i)[0] - x) + std::abs(grid.Point(i)[1] - y) +
          std::abs(grid.Point(i)[2] - z) < 1e-12)
        return i;
    return grid.NumPoints();
  };
  const std::size_t v = find(1.0 / 3.0, 0, 0), next = find(2.0 / 3.0, 0, 0), corner = find(0, 0, 0);
  if (!(v < grid.NumPoints() && next < grid.NumPoints() && corner < grid.NumPoints()))
  {
    AV_CHECK_MSG(false, "grid vertices not found");
    return;
  }
  av::SimplexMesh start = grid;
  start.Points[3 * v] = 0.04;
  AV_CHECK(NumInverted(start) == 0);
  const double before = WorstQuality(start);
  av::MeshImprovementOptions smoothOnly;
  smoothOnly.Flips = false;
  smoothOnly.Insertions = false;
  smoothOnly.KeepEdgeLengths = false;
  const av::MetricField metric = IsotropicMetric(grid.NumPoints());
  for (const std::uint8_t flag : { std::uint8_t(0), av::FeatureLinePoint })
  {
    std::vector<std::uint8_t> flags(grid.NumPoints(), 0);
    flags[v] = flag;
    av::SimplexMesh m = start;
    const av::MeshImprovementResult r = av::ImproveMesh(m, metric, &flags, smoothOnly);
    AV_CHECK_MSG(r.NumCreaseSmoothed >= 1 && r.Moved[v], r.NumCreaseSmoothed << " crease moves");
    AV_CHECK(m.Points[3 * v + 1] == 0.0 && m.Points[3 * v + 2] == 0.0);
    AV_CHECK_MSG(m.Points[3 * v] > 0.15 && m.Points[3 * v] < 0.5, "x = " << m.Points[3 * v]);
    AV_CHECK_MSG(WorstQuality(m) > before + 0.1, before << " -> " << WorstQuality(m));
    for (int d = 0; d < 3; ++d)
      AV_CHECK(m.Points[3 * corner + d] == 0.0);
    const Checks c = CheckRun(start, m, std::vector<std::uint8_t>(grid.NumPoints(), 0), r, true);
    AV_CHECK(c.Ok);
  }
  { // Pinned (a corner site of the sampler, or the user's), or StraightCreases off: it stays.
    std::vector<std::uint8_t> pinned(grid.NumPoints(), 0);
    pinned[v] = 1;
    av::SimplexMesh m = start;
    const av::MeshImprovementResult r = av::ImproveMesh(m, metric, &pinned, smoothOnly);
    AV_CHECK(!r.Moved[v] && m.Points[3 * v] == 0.04);
    av::MeshImprovementOptions off = smoothOnly;
    off.StraightCreases = false;
    av::SimplexMesh k = start;
    AV_CHECK(av::ImproveMesh(k, metric, nullptr, off).NumCreaseSmoothed == 0);
    AV_CHECK(k.Points[3 * v] == 0.04);
  }
  { // A bent crease: its next vertex pushed into the cube, off both planes.
    av::SimplexMesh bent = start;
    bent.Points[3 * next + 1] = bent.Points[3 * next + 2] = 0.05;
    AV_CHECK(NumInverted(bent) == 0);
    av::SimplexMesh m = bent;
    const av::MeshImprovementResult r = av::ImproveMesh(m, metric, nullptr, smoothOnly);
    AV_CHECK(!r.Moved[v] && m.Points[3 * v] == 0.04);
  }
}

av::MetricField StretchedMetric(std::size_t n, int dim)
{
  av::MetricField m;
  m.Values.assign(6 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
  {
    m.Values[6 * i] = 9.0;
    m.Values[6 * i + 1] = 1.0;
    m.Values[6 * i + 2] = dim == 3 ? 1.0 : 0.0;
    m.Values[6 * i + 3] = 0.5;
  }
  return m;
}

void TestGrids()
{
  const av::SimplexMesh start = JitteredGrid(5, 3);
  const av::MetricField metric = StretchedMetric(start.NumPoints(), 3);
  std::vector<std::uint8_t> fixed(start.NumPoints(), 0);
  fixed[start.NumPoints() / 2] = 1; // an interior "feature" vertex
  av::SimplexMesh m = start;
  const av::MeshImprovementResult r =
    av::ImproveMesh(m, metric, &fixed, av::MeshImprovementOptions());
  const Checks c = CheckRun(start, m, fixed, r, true);
  AV_CHECK(c.Ok);
  AV_CHECK_MSG(r.WorstAfter > r.WorstBefore + 1.0, r.WorstBefore << " -> " << r.WorstAfter);
  AV_CHECK(r.NumSmoothed > 0 && r.NumEdgeRemovals + r.NumFlips23 > 0);
  AV_CHECK_MSG(r.NumBoundarySmoothed > 0 && r.NumBoundaryEdgeRemovals > 0,
    r.NumBoundarySmoothed << " boundary moves, " << r.NumBoundaryEdgeRemovals
                          << " boundary edge removals");
  AV_CHECK(m.NumPoints() == start.NumPoints() + r.NumInsertions);
  { // Without PlanarBoundary the boundary stays face for face.
    av::MeshImprovementOptions interior;
    interior.PlanarBoundary = false;
    av::SimplexMesh k = start;
    const av::MeshImprovementResult kr = av::ImproveMesh(k, metric, &fixed, interior);
    AV_CHECK(CheckRun(start, k, fixed, kr).Ok);
    AV_CHECK(kr.NumBoundarySmoothed == 0 && kr.NumBoundaryEdgeRemovals == 0);
  }

  // Triangles on a jittered grid in the same metric.
  const double lo[2] = { 0, 0 }, hi[2] = { 1, 1 };
  av::SimplexMesh t0 = av::MakeTriangleGrid(8, 8, lo, hi);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.03, 0.03);
  const std::vector<char> tb = av::BoundaryVertexMask(t0);
  for (std::size_t i = 0; i < t0.NumPoints(); ++i)
    if (!tb[i])
      for (int d = 0; d < 2; ++d)
        t0.Points[2 * i + d] += u(rng);
  av::SimplexMesh t = t0;
  const av::MetricField tm = StretchedMetric(t0.NumPoints(), 2);
  const std::vector<std::uint8_t> none(t0.NumPoints(), 0);
  av::MeshImprovementOptions noSplits; // boundary splits: TestTriangleMeshImprovement
  noSplits.Splits = false;
  const av::MeshImprovementResult tr = av::ImproveMesh(t, tm, nullptr, noSplits);
  AV_CHECK(CheckRun(t0, t, none, tr).Ok);
  AV_CHECK_MSG(tr.WorstAfter > tr.WorstBefore + 1.0, tr.WorstBefore << " -> " << tr.WorstAfter);

  // Mutation: accepting operations that lower the worst quality they touch must be caught.
  av::MeshImprovementOptions worsening;
  worsening.AcceptWorsening = true;
  worsening.TargetAngle = 80.0;
  av::SimplexMesh w = start;
  const av::MeshImprovementResult wr = av::ImproveMesh(w, metric, &fixed, worsening);
  std::cerr << "(expected) worsening run: " << wr.WorstBefore << " -> " << wr.WorstAfter
            << std::endl;
  AV_CHECK_MSG(!CheckRun(start, w, fixed, wr, true).Ok, "the checks miss a worsening run");
}

/// Mean §5.2 G and smallest angle (degrees) of m in the constant StretchedMetric (inserted
/// points included), from the Quality kernel's evaluator (not the improver's own measure).
void MeanAndWorst(const av::SimplexMesh& m, double& g, double& worst)
{
  const av::MeshQualityResult q = av::EvaluateMeshQuality(m, StretchedMetric(m.NumPoints(), 3));
  g = q.Summary.GAvg;
  worst = q.Summary.ThetaMin;
}

// The mean-quality sweeps after the worst-first passes: the mean G rises, the worst element
// stays at least where the passes left it (or at the target angle), the mesh stays valid with
// its boundary; without the floor (the AcceptWorsening hook) the worst falls and the check
// sees it.
void TestMeanSmoothing()
{
  const av::SimplexMesh start = JitteredGrid(5, 3);
  const av::MetricField metric = StretchedMetric(start.NumPoints(), 3);
  std::vector<std::uint8_t> fixed(start.NumPoints(), 0);
  fixed[start.NumPoints() / 2] = 1;
  av::MeshImprovementOptions passesOnly;
  passesOnly.MeanSmoothingSweeps = 0;
  av::SimplexMesh m0 = start, m2 = start;
  const av::MeshImprovementResult r0 = av::ImproveMesh(m0, metric, &fixed, passesOnly);
  const av::MeshImprovementResult r2 =
    av::ImproveMesh(m2, metric, &fixed, av::MeshImprovementOptions());
  AV_CHECK(r0.NumMeanSmoothed == 0 && r2.NumMeanSmoothed > 0);
  AV_CHECK(CheckRun(start, m2, fixed, r2, true).Ok);
  double g0 = 0, w0 = 0, g2 = 0, w2 = 0;
  MeanAndWorst(m0, g0, w0);
  MeanAndWorst(m2, g2, w2);
  std::cerr << "mean smoothing (tets): G_avg " << g0 << " -> " << g2 << ", theta_min " << w0
            << " -> " << w2 << ", " << r2.NumMeanSmoothed << " moves" << std::endl;
  AV_CHECK_MSG(g2 > g0 + 0.005, "G_avg " << g0 << " -> " << g2);
  AV_CHECK_MSG(r2.WorstAfter >= std::min(r0.WorstAfter, 35.0) - 1e-9,
    r0.WorstAfter << " -> " << r2.WorstAfter);

  // The floor is what keeps the worst: without it (and without the passes, so that the sweeps
  // start from the jittered grid) the worst element falls below where it started.
  av::MeshImprovementOptions noFloor;
  noFloor.MaxPasses = 0;
  noFloor.AcceptWorsening = true;
  av::MeshImprovementOptions floor = noFloor;
  floor.AcceptWorsening = false;
  av::SimplexMesh a = start, b = start;
  const av::MeshImprovementResult ra = av::ImproveMesh(a, metric, &fixed, floor);
  const av::MeshImprovementResult rb = av::ImproveMesh(b, metric, &fixed, noFloor);
  std::cerr << "(expected) sweeps without the floor: worst " << rb.WorstBefore << " -> "
            << rb.WorstAfter << " (with it: " << ra.WorstAfter << ")" << std::endl;
  AV_CHECK(ra.NumMeanSmoothed > 0 && ra.WorstAfter >= ra.WorstBefore - 1e-9);
  AV_CHECK_MSG(rb.WorstAfter < rb.WorstBefore, "the floor check misses a worsening sweep");
}

void TestBadInput()
{
  av::SimplexMesh m = RingConfiguration(3, 1.0, true);
  AV_CHECK_THROWS(av::ImproveMesh(m, IsotropicMetric(3), nullptr));
  std::vector<std::uint8_t> fixed(2, 0);
  AV_CHECK_THROWS(av::ImproveMesh(m, IsotropicMetric(5), &fixed));
  m.Cells[0] = 99;
  AV_CHECK_THROWS(av::ImproveMesh(m, IsotropicMetric(5), nullptr));
  av::SimplexMesh s = RingConfiguration(3, 1.0, true);
  s.Points[0] = std::nan("");
  AV_CHECK_THROWS(av::ImproveMesh(s, IsotropicMetric(5), nullptr));
  // Surface triangles without PlacePoint: unsupported, unchanged.
  av::SimplexMesh surf;
  surf.SimplexDim = 2;
  surf.Points = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
  surf.Cells = { 0, 1, 2 };
  const av::MeshImprovementResult r = av::ImproveMesh(surf, IsotropicMetric(3), nullptr);
  AV_CHECK(!r.Supported && surf.Cells.size() == 3);
}

// A sliver whose four vertices are fixed (feature vertices), inside a cube: the Delaunay
// tetrahedralization of the cube's corners and the sliver. With flips off and every vertex
// fixed or on the boundary, nothing but an inserted vertex can raise its worst tet. The new vertex
// is interior, the boundary, the volume and the fixed vertices stay exactly, and refusals
// (AddPoint, a tet above the insertion bar, Insertions off) leave the mesh as it was.
av::SimplexMesh SliverInCube()
{
  const double h = 0.12;
  std::vector<double> p = { 1, 0, 0, -1, 0, 0, 0, 1, h, 0, -1, h };
  for (int i = 0; i < 8; ++i)
    p.insert(p.end(), { i & 1 ? 2.0 : -2.0, i & 2 ? 2.0 : -2.0, i & 4 ? 2.0 : -2.0 });
  av::SimplexMesh m = av::DelaunayOfPoints(p);
  Orient(m);
  return m;
}

void TestInsertion()
{
  const av::SimplexMesh start = SliverInCube();
  AV_CHECK(start.NumPoints() == 12 && start.NumCells() > 10);
  const double before = WorstQuality(start);
  std::vector<std::uint8_t> fixed(12, 0);
  std::fill(fixed.begin(), fixed.begin() + 4, 1);
  av::MeshImprovementOptions o;
  // The edge-length rule waived below 15° (the default is 20°: then the new vertex's star, whose
  // worst tet is 17.6°, has more tets below the bar than the cavity and is refused).
  o.EdgeLengthRuleMinAngle = 15.0;
  o.Flips = false;
  {
    av::MeshImprovementOptions off = o;
    off.Insertions = false;
    av::SimplexMesh m = start;
    const av::MeshImprovementResult r = av::ImproveMesh(m, IsotropicMetric(12), &fixed, off);
    AV_CHECK_MSG(r.NumInsertions == 0 && WorstQuality(m) <= before + 1e-12,
      "without insertion " << before << " -> " << WorstQuality(m));
  }
  int placed = 0, added = 0;
  o.PlacePoint = [&](std::int32_t, const double* x, double* at, double* normal, double* metric)
  {
    ++placed;
    for (int d = 0; d < 3; ++d)
    {
      at[d] = x[d];
      normal[d] = 0.0;
    }
    const double iso[6] = { 1, 1, 1, 0, 0, 0 };
    std::copy(iso, iso + 6, metric);
    return true;
  };
  o.AddPoint = [&](std::int32_t id, std::int32_t near, const double*)
  {
    ++added;
    AV_CHECK(id == 12 + added - 1 && near >= 0 && near < 12);
    return true;
  };
  av::SimplexMesh m = start;
  const av::MeshImprovementResult r = av::ImproveMesh(m, IsotropicMetric(12), &fixed, o);
  std::cout << "sliver in a cube: worst sine " << before << " -> " << WorstQuality(m) << ", "
            << r.NumInsertions << " insertion(s), " << r.NumFlips23 + r.NumEdgeRemovals
            << " flips, " << m.NumCells() << " tets" << std::endl;
  AV_CHECK(
    r.NumInsertions >= 1 && static_cast<std::size_t>(added) == r.NumInsertions && placed >= 1);
  AV_CHECK(m.NumPoints() == start.NumPoints() + r.NumInsertions);
  AV_CHECK_MSG(WorstQuality(m) > before + 0.1, before << " -> " << WorstQuality(m));
  const Checks c = CheckRun(start, m, fixed, r);
  AV_CHECK(c.Ok);
  for (std::size_t v = 12; v < m.NumPoints(); ++v) // new vertices lie inside the cube
    for (int d = 0; d < 3; ++d)
      AV_CHECK(r.Moved[v] == 1 && std::abs(m.Point(v)[d]) < 2.0);
  { // A refusing AddPoint: no vertex, the mesh as it was.
    av::MeshImprovementOptions refuse = o;
    refuse.AddPoint = [](std::int32_t, std::int32_t, const double*) { return false; };
    av::SimplexMesh k = start;
    const av::MeshImprovementResult rk = av::ImproveMesh(k, IsotropicMetric(12), &fixed, refuse);
    AV_CHECK(rk.NumInsertions == 0 && k.NumPoints() == start.NumPoints());
    AV_CHECK(WorstQuality(k) <= before + 1e-12);
  }
  { // Above the insertion bar (the edge-length rule binds): no insertion.
    av::MeshImprovementOptions bar = o;
    bar.EdgeLengthRuleMinAngle = 0.5;
    av::SimplexMesh k = start;
    AV_CHECK(av::ImproveMesh(k, IsotropicMetric(12), &fixed, bar).NumInsertions == 0);
  }
}

// A flat sliver lying in a shallow valley on top of a cube (the top's diagonal 4-7 lowered by
// 0.02): two of its faces are boundary faces meeting along the other diagonal 5-6, no other
// tet has that edge, and no flip or move can raise it. The peel removes it: the valley is the
// boundary again, the volume changes by the sliver's exactly, and without the option or with a
// budget below the sliver's volume it stays.
void TestBoundaryPeel()
{
  av::SimplexMesh start;
  for (int i = 0; i < 8; ++i)
    start.Points.insert(start.Points.end(),
      { double(i & 1), double((i >> 1) & 1), (i & 4) ? ((i == 4 || i == 7) ? 0.98 : 1.0) : 0.0 });
  start.Cells = {
    0, 1, 3, 7, 0, 3, 2, 7, 0, 2, 6, 7, 0, 6, 4, 7, 0, 4, 5, 7, 0, 5, 1, 7, 4, 5, 6, 7
  };
  Orient(start);
  const double sliver = [&]
  {
    av::SimplexMesh one = start;
    one.Cells.assign(start.Cells.end() - 4, start.Cells.end());
    return Volume(one);
  }();
  const double before = WorstQuality(start);
  av::MeshImprovementOptions o;
  o.Flips = false;
  o.Insertions = false;              // a vertex inside would split it as well
  o.BoundaryPeelVolumeBudget = 0.01; // the sliver is 0.7 % of this small mesh
  {
    av::MeshImprovementOptions off = o;
    off.PeelBoundaryTets = false;
    av::SimplexMesh m = start;
    const av::MeshImprovementResult r = av::ImproveMesh(m, IsotropicMetric(8), nullptr, off);
    AV_CHECK(r.NumBoundaryPeels == 0 && m.NumCells() == 7 && WorstQuality(m) <= before + 1e-12);
  }
  av::SimplexMesh m = start;
  const av::MeshImprovementResult r = av::ImproveMesh(m, IsotropicMetric(8), nullptr, o);
  std::cout << "valley sliver: worst sine " << before << " -> " << WorstQuality(m) << ", "
            << r.NumBoundaryPeels << " peel(s), volume change " << r.BoundaryVolumeChange
            << std::endl;
  AV_CHECK(r.NumBoundaryPeels == 1 && m.NumCells() == 6);
  AV_CHECK_MSG(WorstQuality(m) > before + 0.3, before << " -> " << WorstQuality(m));
  AV_CHECK_NEAR(Volume(start) - Volume(m), sliver, 1e-14);
  AV_CHECK_NEAR(r.BoundaryVolumeChange, sliver / Volume(start), 1e-12);
  AV_CHECK(NumInverted(m) == 0 && m.NumPoints() == 8);
  {
    av::MeshImprovementOptions small = o;
    small.BoundaryPeelVolumeBudget = 0.5 * sliver / Volume(start);
    av::SimplexMesh k = start;
    AV_CHECK(av::ImproveMesh(k, IsotropicMetric(8), nullptr, small).NumBoundaryPeels == 0);
    AV_CHECK(k.NumCells() == 7);
  }
}
// An interior vertex squeezed towards a corner of an octahedron (its 8 tets: 4 flat ones on the
// corner, 4 long ones): with flips, smoothing and insertion off, only the edge contraction can
// help. It merges the vertex into that corner: 4 tets around the axis, the worst tet far better,
// the volume and the boundary faces exactly kept, the vertex unreferenced. Without the option,
// or with the vertex fixed, nothing changes.
void TestContraction()
{
  av::SimplexMesh start;
  start.Points = { 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0.9, 0.04, 0.03 };
  for (std::int32_t x : { 0, 1 })
    for (std::int32_t y : { 2, 3 })
      for (std::int32_t z : { 4, 5 })
        start.Cells.insert(start.Cells.end(), { 6, x, y, z });
  Orient(start);
  const double before = WorstQuality(start);
  std::vector<std::uint8_t> fixed(7, 0);
  av::MeshImprovementOptions o;
  o.Flips = false;
  o.Smoothing = false;
  o.Insertions = false;
  {
    av::MeshImprovementOptions off = o;
    off.Collapses = false;
    av::SimplexMesh m = start;
    const av::MeshImprovementResult r = av::ImproveMesh(m, IsotropicMetric(7), &fixed, off);
    AV_CHECK(r.NumCollapses == 0 && m.Cells == start.Cells);
    std::vector<std::uint8_t> pinned(7, 0);
    pinned[6] = 1;
    av::SimplexMesh k = start;
    AV_CHECK(av::ImproveMesh(k, IsotropicMetric(7), &pinned, o).NumCollapses == 0);
    AV_CHECK(k.Cells == start.Cells);
  }
  av::SimplexMesh m = start;
  const av::MeshImprovementResult r = av::ImproveMesh(m, IsotropicMetric(7), &fixed, o);
  std::cout << "squeezed vertex in an octahedron: worst sine " << before << " -> "
            << WorstQuality(m) << ", " << r.NumCollapses << " contraction(s), " << m.NumCells()
            << " tets" << std::endl;
  AV_CHECK(r.NumCollapses == 1 && m.NumCells() == 4 && m.NumPoints() == 7);
  AV_CHECK_MSG(WorstQuality(m) > before + 0.3, before << " -> " << WorstQuality(m));
  for (std::size_t c = 0; c < m.NumCells(); ++c)
    for (int i = 0; i < 4; ++i)
      AV_CHECK(m.Cell(c)[i] != 6);
  AV_CHECK(CheckRun(start, m, fixed, r).Ok);
}

// An ear: a flat tet on a good one, its three other faces on the boundary, its apex also a
// vertex of a third tet that shares no face with it (a pinched boundary, as the real volumes'
// duals have at creases). No flip, move or insertion reaches it; the peel removes it, the
// volume changes by exactly the ear's, its apex stays in the third tet. With a budget below the
// ear's volume, or without the option, it stays.
void TestEarPeel()
{
  av::SimplexMesh start;
  start.Points = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.3, 0.3, -0.8, 0.3, 0.3, 0.03, -0.2, 0.3, 1.0,
    0.8, 0.3, 1.0, 0.3, 1.0, 1.0 };
  start.Cells = { 0, 1, 2, 4, 0, 1, 2, 3, 4, 5, 6, 7 };
  Orient(start);
  const double ear = [&]
  {
    av::SimplexMesh one = start;
    one.Cells.resize(4);
    return Volume(one);
  }();
  const double before = WorstQuality(start);
  std::vector<std::uint8_t> fixed(8, 1);
  av::MeshImprovementOptions o;
  o.Flips = false;
  o.Insertions = false;
  o.BoundaryPeelVolumeBudget = 0.05;
  {
    av::MeshImprovementOptions off = o;
    off.PeelBoundaryTets = false;
    av::SimplexMesh m = start;
    AV_CHECK(av::ImproveMesh(m, IsotropicMetric(8), &fixed, off).NumBoundaryPeels == 0);
    AV_CHECK(m.NumCells() == 3);
    av::MeshImprovementOptions small = o;
    small.BoundaryPeelVolumeBudget = 0.5 * ear / Volume(start);
    av::SimplexMesh k = start;
    AV_CHECK(av::ImproveMesh(k, IsotropicMetric(8), &fixed, small).NumBoundaryPeels == 0);
    AV_CHECK(k.NumCells() == 3);
  }
  av::SimplexMesh m = start;
  const av::MeshImprovementResult r = av::ImproveMesh(m, IsotropicMetric(8), &fixed, o);
  std::cout << "pinched ear: worst sine " << before << " -> " << WorstQuality(m) << ", "
            << r.NumBoundaryPeels << " peel(s)" << std::endl;
  AV_CHECK(r.NumBoundaryPeels == 1 && m.NumCells() == 2);
  AV_CHECK_MSG(WorstQuality(m) > before + 0.3, before << " -> " << WorstQuality(m));
  AV_CHECK_NEAR(Volume(start) - Volume(m), ear, 1e-14);
  AV_CHECK_NEAR(r.BoundaryVolumeChange, ear / Volume(start), 1e-12);
  bool apexUsed = false;
  for (std::size_t c = 0; c < m.NumCells(); ++c)
    for (int i = 0; i < 4; ++i)
      apexUsed = apexUsed || m.Cell(c)[i] == 4;
  AV_CHECK(apexUsed && NumInverted(m) == 0);
}
} // namespace

int TestMeshImprovement(int, char*[])
{
  TestMeanSmoothing();
  TestFlips();
  TestSmoothing();
  TestPlanarBoundary();
  TestStraightCrease();
  TestTriangles();
  TestInsertion();
  TestBoundaryPeel();
  TestContraction();
  TestEarPeel();
  TestGrids();
  TestBadInput();
  return AV_TEST_RESULT();
}
