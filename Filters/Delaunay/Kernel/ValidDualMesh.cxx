// SPDX-License-Identifier: BSD-3-Clause
#include "ValidDualMesh.h"

#include "ElementLocator.h"
#include "InputError.h"
#include "MeshImprovement.h"
#include "MeshTopology.h"
#include "MetricAlgebra.h"
#include "SurfaceFidelity.h"
#include "TetMesher.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>

namespace av
{
namespace
{
// Relative volume below which a simplex counts as flat (the value of ComputeRestrictedDelaunay).
constexpr double kFlatTolerance = 1e-7;
// Boundary tets flatter than this (a regular tet: 0.048) are peeled: four nearly coplanar sites
// on a boundary face give a sliver the mesh improvement cannot remove (boundary faces are
// never flipped), and peeling it loses almost no volume.
constexpr double kPeelTolerance = 1e-3;

/// Whether k! times the signed measure of cell c is below `tolerance` times the bound of its
/// edges, (sum of squared edge lengths)^(k/2).
bool IsFlatOrInverted(const SimplexMesh& m, std::size_t c, double tolerance = kFlatTolerance)
{
  const int k = m.SimplexDim;
  const std::int32_t* v = m.Cell(c);
  double l2 = 0.0;
  for (int i = 0; i <= k; ++i)
    for (int j = i + 1; j <= k; ++j)
      for (int d = 0; d < m.AmbientDim; ++d)
      {
        const double e = m.Point(v[i])[d] - m.Point(v[j])[d];
        l2 += e * e;
      }
  const double measure = (k == 3 ? 6.0 : 2.0) * CellMeasure(m, c);
  return !(measure > tolerance * std::pow(l2, 0.5 * k));
}

/// Surfaces: triangle v of `dual` against the sum of the normals of the input triangles that
/// hold its sites (a flip across a strongly curved region).
bool FlippedOnSurface(const SimplexMesh& input, const SimplexMesh& dual, const SiteSet& sites,
  const std::int32_t* v)
{
  auto at = [](const SimplexMesh& m, std::int32_t p)
  { return Eigen::Map<const Eigen::Vector3d>(m.Point(static_cast<std::size_t>(p))); };
  Eigen::Vector3d ref = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i)
  {
    const std::int32_t* e = input.Cell(static_cast<std::size_t>(sites.CellIds[v[i]]));
    ref += (at(input, e[1]) - at(input, e[0])).cross(at(input, e[2]) - at(input, e[0])).normalized();
  }
  const Eigen::Vector3d n = (at(dual, v[1]) - at(dual, v[0])).cross(at(dual, v[2]) - at(dual, v[0]));
  return !(n.dot(ref) > 0.0);
}

SimplexMesh AsMesh(const RestrictedDelaunayMesh& rdt)
{
  SimplexMesh m;
  m.AmbientDim = rdt.AmbientDim;
  m.SimplexDim = rdt.SimplexDim;
  m.Points = rdt.Points;
  m.Cells = rdt.Cells;
  return m;
}

/// Whether the centroid of tet c of `dt` (whose points are the sites) lies in the input domain.
bool CentroidInDomain(const SimplexMesh& mesh, const std::vector<std::int32_t>& adjacency,
  const SiteSet& sites, const SimplexMesh& dt, std::size_t c)
{
  const std::int32_t* v = dt.Cell(c);
  double x[3] = { 0, 0, 0 };
  for (int a = 0; a < 4; ++a)
    for (int d = 0; d < 3; ++d)
      x[d] += 0.25 * dt.Point(v[a])[d];
  double lambda[4];
  // From each site's element in turn: a walk may stop at a concave part of the boundary that
  // lies between one site and the centroid but not another.
  for (int a = 0; a < 4; ++a)
  {
    std::int32_t cell = sites.CellIds[static_cast<std::size_t>(v[a])];
    if (LocateInMesh(mesh, adjacency, cell, x, lambda))
      return true;
  }
  return false;
}

/// Cells of `dt` flagged in `keep` with a face that no other kept cell has.
std::vector<std::uint8_t> OnBoundary(const SimplexMesh& dt, const std::vector<std::uint8_t>& keep)
{
  SimplexMesh kept;
  kept.AmbientDim = dt.AmbientDim;
  kept.SimplexDim = dt.SimplexDim;
  std::vector<std::int32_t> id;
  for (std::size_t c = 0; c < dt.NumCells(); ++c)
    if (keep[c])
    {
      kept.Cells.insert(kept.Cells.end(), dt.Cell(c), dt.Cell(c) + 4);
      id.push_back(static_cast<std::int32_t>(c));
    }
  const std::vector<CellFacet> facets = SortedCellFacets(kept);
  std::vector<std::uint8_t> boundary(dt.NumCells(), 0);
  for (std::size_t i = 0; i < facets.size();)
  {
    std::size_t j = i + 1;
    while (j < facets.size() && facets[j].Vertices == facets[i].Vertices)
      ++j;
    if (j - i == 1)
      boundary[static_cast<std::size_t>(id[static_cast<std::size_t>(facets[i].Cell)])] = 1;
    i = j;
  }
  return boundary;
}

/**
 * Removes the tets on the boundary of `dt` whose metric quality is below sin(kSliverAngle) and
 * whose four vertices are all on the boundary and in another tet, worst first, round after
 * round, while the volume removed stays below kVolumeBudget of the mesh's: the carved
 * boundary's slivers, which the mesh improvement cannot reach (it never flips boundary faces
 * nor moves boundary vertices). Removing one moves the boundary by its small height; the
 * budget keeps the domain (without it, hueeber1 lost 10 % of its volume at 10 deg). Returns
 * the count.
 */
std::size_t PeelBoundarySlivers(
  SimplexMesh& dt, const MetricField& siteMetric, double& totalVolume, double& peeledVolume)
{
  constexpr double kSliverAngle = 10.0; // degrees
  constexpr double kVolumeBudget = 2e-3;
  const double threshold = std::sin(kSliverAngle * 3.14159265358979323846 / 180.0);
  std::vector<Eigen::Matrix3d> roots(dt.NumPoints());
  for (std::size_t i = 0; i < dt.NumPoints(); ++i)
    roots[i] = SymmetricSqrt(UnpackSymmetric(siteMetric.At(i)));
  double total = 0.0;
  for (std::size_t c = 0; c < dt.NumCells(); ++c)
    total += CellMeasure(dt, c);
  double budget = kVolumeBudget * total;
  totalVolume = total;
  peeledVolume = 0.0;
  std::size_t removed = 0;
  for (int round = 0; round < 10 && budget > 0.0; ++round)
  {
    // Boundary faces (of one tet): their tets and their vertices.
    std::vector<std::uint8_t> boundary(dt.NumCells(), 0);
    std::vector<char> onBoundary(dt.NumPoints(), 0);
    const std::vector<CellFacet> facets = SortedCellFacets(dt);
    for (std::size_t i = 0; i < facets.size();)
    {
      std::size_t j = i + 1;
      while (j < facets.size() && facets[j].Vertices == facets[i].Vertices)
        ++j;
      if (j - i == 1)
      {
        boundary[static_cast<std::size_t>(facets[i].Cell)] = 1;
        for (const std::int32_t v : facets[i].Vertices)
          onBoundary[static_cast<std::size_t>(v)] = 1;
      }
      i = j;
    }
    std::vector<int> uses(dt.NumPoints(), 0);
    for (std::size_t c = 0; c < dt.NumCells(); ++c)
      for (int a = 0; a < 4; ++a)
        ++uses[static_cast<std::size_t>(dt.Cell(c)[a])];
    std::vector<std::pair<double, std::size_t>> slivers; // (quality, tet)
    for (std::size_t c = 0; c < dt.NumCells(); ++c)
    {
      const std::int32_t* v = dt.Cell(c);
      bool candidate = boundary[c] != 0;
      for (int a = 0; a < 4 && candidate; ++a)
        candidate = onBoundary[static_cast<std::size_t>(v[a])] != 0;
      if (!candidate)
        continue;
      const double* pts[4];
      const double* sq[4];
      for (int a = 0; a < 4; ++a)
      {
        pts[a] = dt.Point(v[a]);
        sq[a] = roots[static_cast<std::size_t>(v[a])].data();
      }
      const double q = MetricSimplexQuality(3, pts, sq);
      if (q < threshold)
        slivers.push_back({ q, c });
    }
    std::sort(slivers.begin(), slivers.end());
    std::vector<std::uint8_t> drop(dt.NumCells(), 0);
    std::size_t now = 0;
    for (const auto& [q, c] : slivers)
    {
      const std::int32_t* v = dt.Cell(c);
      bool shared = true;
      for (int a = 0; a < 4; ++a)
        shared = shared && uses[static_cast<std::size_t>(v[a])] > 1;
      const double vol = CellMeasure(dt, c);
      if (!shared || vol > budget)
        continue;
      drop[c] = 1;
      budget -= vol;
      peeledVolume += vol;
      ++now;
      for (int a = 0; a < 4; ++a)
        --uses[static_cast<std::size_t>(v[a])];
    }
    if (now == 0)
      break;
    std::vector<std::int32_t> kept;
    for (std::size_t c = 0; c < dt.NumCells(); ++c)
      if (!drop[c])
        kept.insert(kept.end(), dt.Cell(c), dt.Cell(c) + 4);
    dt.Cells = std::move(kept);
    removed += now;
  }
  return removed;
}

using Quad = std::array<std::int32_t, 4>;

Quad SortedQuad(const std::int32_t* v)
{
  Quad q{ v[0], v[1], v[2], v[3] };
  std::sort(q.begin(), q.end());
  return q;
}

/// The face of sorted quadruple `q` opposite its vertex `skip` (sorted too).
std::array<std::int32_t, 3> FaceOf(const Quad& q, int skip)
{
  std::array<std::int32_t, 3> f;
  for (int a = 0, n = 0; a < 4; ++a)
    if (a != skip)
      f[n++] = q[a];
  return f;
}

/// The distinct faces of `cells` (sorted quadruples), 3 ids each.
std::vector<std::int32_t> FacesOf(const std::vector<Quad>& cells)
{
  std::vector<std::array<std::int32_t, 3>> faces;
  faces.reserve(4 * cells.size());
  for (const Quad& q : cells)
    for (int skip = 0; skip < 4; ++skip)
      faces.push_back(FaceOf(q, skip));
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  std::vector<std::int32_t> out;
  out.reserve(3 * faces.size());
  for (const auto& f : faces)
    out.insert(out.end(), f.begin(), f.end());
  return out;
}

/**
 * The cells of the dual kept in the replacement: not inverted or flat, every face in at most
 * two cells and, if in two, with their apexes on either side; no vertex on a cell that fails
 * those (the overlapping cells of a fold are positive too, so the bad cells' vertices mark the
 * fold); the centroid in the domain (a cell across a concave part of the boundary is carved
 * anyway); and no face that crosses a face of another kept cell with which it shares no vertex
 * (overlapping layers that the rules before miss; TetGen would fail on them). Sorted.
 */
std::vector<Quad> ValidDualCells(const SimplexMesh& mesh,
  const std::vector<std::int32_t>& adjacency,
  const SiteSet& sites,
  const RestrictedDelaunayMesh& rdt)
{
  const SimplexMesh dual = AsMesh(rdt);
  const std::size_t n = dual.NumCells();
  std::vector<std::uint8_t> bad(n, 0);
  std::vector<std::uint8_t> badVertex(dual.NumPoints(), 0);
  for (std::size_t c = 0; c < n; ++c)
    bad[c] = IsFlatOrInverted(dual, c) || (c < rdt.Inverted.size() && rdt.Inverted[c]);
  const std::vector<CellFacet> facets = SortedCellFacets(dual);
  auto apexSide = [&](const std::array<std::int32_t, 3>& f, std::size_t c)
  {
    std::int32_t apex = -1;
    for (int a = 0; a < 4; ++a)
      if (std::find(f.begin(), f.end(), dual.Cell(c)[a]) == f.end())
        apex = dual.Cell(c)[a];
    const Eigen::Map<const Eigen::Vector3d> p0(dual.Point(f[0])), p1(dual.Point(f[1])),
      p2(dual.Point(f[2])), q(dual.Point(apex));
    return (p1 - p0).cross(p2 - p0).dot(q - p0) > 0.0;
  };
  for (std::size_t i = 0; i < facets.size();)
  {
    std::size_t j = i + 1;
    while (j < facets.size() && facets[j].Vertices == facets[i].Vertices)
      ++j;
    // A face of more than two cells, or of two cells on the same side of it (they overlap:
    // a fold whose cells are all positive).
    const bool overlap = j - i == 2 &&
      apexSide(facets[i].Vertices, static_cast<std::size_t>(facets[i].Cell)) ==
        apexSide(facets[i].Vertices, static_cast<std::size_t>(facets[i + 1].Cell));
    if (j - i > 2 || overlap)
      for (std::size_t k = i; k < j; ++k)
        bad[static_cast<std::size_t>(facets[k].Cell)] = 1;
    i = j;
  }
  for (std::size_t c = 0; c < n; ++c)
    if (bad[c])
      for (int a = 0; a < 4; ++a)
        badVertex[static_cast<std::size_t>(dual.Cell(c)[a])] = 1;
  std::vector<Quad> out;
  for (std::size_t c = 0; c < n; ++c)
  {
    const std::int32_t* v = dual.Cell(c);
    if (!bad[c] && !badVertex[v[0]] && !badVertex[v[1]] && !badVertex[v[2]] && !badVertex[v[3]] &&
      CentroidInDomain(mesh, adjacency, sites, dual, c))
      out.push_back(SortedQuad(v));
  }
  std::sort(out.begin(), out.end());
  if (out.empty())
    return out;
  SimplexMesh faces;
  faces.AmbientDim = 3;
  faces.SimplexDim = 2;
  faces.Points = dual.Points;
  faces.Cells = FacesOf(out);
  const std::vector<std::uint8_t> crossing = SelfIntersectingTriangles(faces);
  std::vector<std::array<std::int32_t, 3>> crossed;
  for (std::size_t f = 0; f < crossing.size(); ++f)
    if (crossing[f])
      crossed.push_back({ faces.Cells[3 * f], faces.Cells[3 * f + 1], faces.Cells[3 * f + 2] });
  if (crossed.empty())
    return out; // sorted already: crossed stays sorted as FacesOf's faces are
  std::vector<Quad> kept;
  for (const Quad& q : out)
  {
    bool ok = true;
    for (int skip = 0; skip < 4 && ok; ++skip)
      ok = !std::binary_search(crossed.begin(), crossed.end(), FaceOf(q, skip));
    if (ok)
      kept.push_back(q);
  }
  return kept;
}

/// The constrained Delaunay tetrahedralization of `points` with `faces`, or the plain one where
/// TetGen cannot recover them (intersecting faces: a fold the targets missed).
SimplexMesh DelaunayKeeping(const std::vector<double>& points,
  const std::vector<std::int32_t>& faces,
  bool& constrained)
{
  constrained = false;
  if (!faces.empty())
  {
    try
    {
      SimplexMesh m = ConstrainedDelaunayOfPoints(points, faces);
      constrained = true;
      return m;
    }
    catch (const InputError&)
    {
    }
  }
  return DelaunayOfPoints(points);
}

} // namespace

void RecountFinalDual(const SimplexMesh& input, RestrictedDelaunayMesh& rdt, const SiteSet& sites)
{
  const SimplexMesh dual = AsMesh(rdt);
  rdt.Inverted.assign(dual.NumCells(), 0);
  rdt.CellElement.assign(dual.NumCells(), 0);
  rdt.NumInverted = 0;
  std::vector<std::uint8_t> used(dual.NumPoints(), 0);
  for (std::size_t c = 0; c < dual.NumCells(); ++c)
  {
    const std::int32_t* v = dual.Cell(c);
    rdt.Inverted[c] = IsFlatOrInverted(dual, c) ? 1 : 0;
    if (dual.AmbientDim == 3 && dual.SimplexDim == 2 && !rdt.Inverted[c])
      rdt.Inverted[c] = FlippedOnSurface(input, dual, sites, v) ? 1 : 0;
    rdt.NumInverted += rdt.Inverted[c];
    rdt.CellElement[c] = sites.CellIds[static_cast<std::size_t>(v[0])];
    for (int a = 0; a <= dual.SimplexDim; ++a)
      used[static_cast<std::size_t>(v[a])] = 1;
  }
  // Faces shared by more than two cells.
  const std::vector<CellFacet> facets = SortedCellFacets(dual);
  rdt.NumNonManifoldFaces = 0;
  for (std::size_t i = 0; i < facets.size();)
  {
    std::size_t j = i + 1;
    while (j < facets.size() && facets[j].Vertices == facets[i].Vertices)
      ++j;
    rdt.NumNonManifoldFaces += j - i > 2;
    i = j;
  }
  rdt.NumUnusedSites = static_cast<std::size_t>(std::count(used.begin(), used.end(), 0));
}

bool DualNeedsReplacement(const RestrictedDelaunayMesh& rdt)
{
  const double sites = static_cast<double>(rdt.Points.size() / 3);
  return rdt.NumInverted > 0 || rdt.NumNonManifoldFaces > 0 ||
    static_cast<double>(rdt.NumUnusedSites) > kMaxUnusedSiteFraction * sites;
}

ValidDualResult MakeDualValid(const SimplexMesh& mesh, const std::vector<std::int32_t>& adjacency,
  const SiteSet& sites, const MetricField* siteMetric, RestrictedDelaunayMesh& rdt)
{
  ValidDualResult r;
  r.InvalidCells = rdt.NumInverted;
  r.NonManifoldFaces = rdt.NumNonManifoldFaces;
  r.UnusedSites = rdt.NumUnusedSites;
  if (mesh.SimplexDim != 3 || mesh.AmbientDim != 3 || rdt.SimplexDim != 3 ||
    !DualNeedsReplacement(rdt) || rdt.Points.size() < 12)
    return r;

  const std::vector<Quad> targets = ValidDualCells(mesh, adjacency, sites, rdt);
  r.TargetCells = targets.size();
  SimplexMesh dt;
  try
  {
    // Delaunay in the mean metric (a linear map of positive determinant keeps orientations):
    // nearer the metric Delaunay mesh than the Euclidean one when the metric's directions
    // agree over the domain (a boundary layer), so the flips below have less to do.
    std::vector<double> mapped = rdt.Points;
    if (siteMetric && siteMetric->NumPoints() == rdt.Points.size() / 3)
    {
      Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
      for (std::size_t i = 0; i < siteMetric->NumPoints(); ++i)
      {
        const Eigen::Matrix3d root = SymmetricSqrt(UnpackSymmetric(siteMetric->At(i)));
        s += root / std::cbrt(root.determinant()); // shape only: each site counts alike
      }
      for (std::size_t i = 0; i < mapped.size() / 3; ++i)
      {
        Eigen::Map<Eigen::Vector3d> x(mapped.data() + 3 * i);
        x = (s * Eigen::Vector3d(x)).eval();
      }
    }
    // One tetrahedralization per body of the input (parts with no shared point, as in a
    // contact assembly): a tet across the contact would join two domains.
    std::vector<std::int32_t> pointBody;
    const std::size_t numBodies = LabelBodies(mesh, pointBody);
    if (numBodies < 2)
    {
      bool constrained = false;
      dt = DelaunayKeeping(mapped, FacesOf(targets), constrained);
      r.Constrained = constrained;
    }
    else
    {
      std::vector<std::vector<std::int32_t>> members(numBodies);
      for (std::size_t i = 0; i < mapped.size() / 3; ++i)
      {
        const std::int32_t cell = sites.CellIds[i];
        members[static_cast<std::size_t>(pointBody[static_cast<std::size_t>(mesh.Cell(cell)[0])])]
          .push_back(static_cast<std::int32_t>(i));
      }
      for (const std::vector<std::int32_t>& ids : members)
      {
        if (ids.size() < 4)
          continue; // too few sites for a tet: the body's sites stay unused
        std::vector<double> sub(3 * ids.size());
        for (std::size_t k = 0; k < ids.size(); ++k)
          for (int d = 0; d < 3; ++d)
            sub[3 * k + d] = mapped[3 * static_cast<std::size_t>(ids[k]) + d];
        // The body's target cells, in its own numbering.
        std::vector<std::int32_t> local(mapped.size() / 3, -1);
        for (std::size_t k = 0; k < ids.size(); ++k)
          local[static_cast<std::size_t>(ids[k])] = static_cast<std::int32_t>(k);
        std::vector<Quad> own;
        for (const Quad& q : targets)
        {
          Quad l{ local[q[0]], local[q[1]], local[q[2]], local[q[3]] };
          if (l[0] >= 0 && l[1] >= 0 && l[2] >= 0 && l[3] >= 0)
          {
            std::sort(l.begin(), l.end());
            own.push_back(l);
          }
        }
        try
        {
          bool constrained = false;
          const SimplexMesh part = DelaunayKeeping(sub, FacesOf(own), constrained);
          r.Constrained = r.Constrained || constrained;
          for (std::int32_t v : part.Cells)
            dt.Cells.push_back(ids[static_cast<std::size_t>(v)]);
        }
        catch (const InputError&)
        {
          // coplanar sites of one body: that body stays uncovered, the others are meshed
        }
      }
      if (dt.Cells.empty())
        return r;
    }
    dt.Points = rdt.Points;
  }
  catch (const InputError&)
  {
    return r; // coplanar sites, say: keep the dual (its counts say what is wrong with it)
  }
  r.DelaunayCells = dt.NumCells();
  std::vector<std::uint8_t> keep(dt.NumCells(), 0);
  for (std::size_t c = 0; c < dt.NumCells(); ++c)
  {
    keep[c] = CentroidInDomain(mesh, adjacency, sites, dt, c) ? 1 : 0;
    r.OutsideCells += !keep[c];
  }
  for (bool changed = true; changed;)
  {
    changed = false;
    const std::vector<std::uint8_t> boundary = OnBoundary(dt, keep);
    for (std::size_t c = 0; c < dt.NumCells(); ++c)
      if (keep[c] && boundary[c] && IsFlatOrInverted(dt, c, kPeelTolerance))
      {
        keep[c] = 0;
        ++r.FlatBoundaryCells;
        changed = true;
      }
  }
  std::vector<std::int32_t> kept;
  for (std::size_t c = 0; c < dt.NumCells(); ++c)
    if (keep[c])
      kept.insert(kept.end(), dt.Cell(c), dt.Cell(c) + 4);
  dt.Cells = std::move(kept);
  if (siteMetric && siteMetric->NumPoints() == dt.NumPoints())
  {
    r.Flips = FlipTowardsMetricDelaunay(dt, *siteMetric, targets);
    r.BoundarySlivers = PeelBoundarySlivers(dt, *siteMetric, r.VolumeBeforePeel, r.PeeledVolume);
  }
  for (std::size_t c = 0; c < dt.NumCells(); ++c)
    r.KeptCells += std::binary_search(targets.begin(), targets.end(), SortedQuad(dt.Cell(c)));
  rdt.Cells = std::move(dt.Cells);
  r.Replaced = true;
  RecountFinalDual(mesh, rdt, sites);
  rdt.NumOpenInteriorFaces = 0; // not dual to the RVD: no Voronoi face to compare with
  return r;
}

} // namespace av
