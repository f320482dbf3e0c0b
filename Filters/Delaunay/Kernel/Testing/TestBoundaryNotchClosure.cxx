// SPDX-License-Identifier: BSD-3-Clause
// Tests of SitesOnOpenBoundary and CloseBoundaryNotches on a flat open strip: a dual whose
// boundary passes through a site just inside the strip's edge gets the one triangle that
// closes the notch, after which the dual covers its polygon exactly and every boundary vertex
// is on the input's boundary; boundary vertices at convex corners get no ear (it would fold
// over their triangles); a closed surface is left alone.
#include "BoundaryNotchClosure.h"
#include "MeshTopology.h"
#include "AnisoTestChecks.h"
#include "HeightFieldSites.h"

#include <Eigen/Dense>

#include <cmath>
#include <vector>

namespace
{
/// The strip [0, 4] x [0, h] in the plane z = 0 (a 5 x 2 grid of points, +z normals).
av::SimplexMesh MakeStrip(double h)
{
  av::SimplexMesh m;
  m.AmbientDim = 3;
  m.SimplexDim = 2;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 5; ++i)
      m.Points.insert(m.Points.end(), { double(i), h * j, 0.0 });
  for (int i = 0; i < 4; ++i)
  {
    m.Cells.insert(m.Cells.end(), { i, i + 1, i + 6 });
    m.Cells.insert(m.Cells.end(), { i, i + 6, i + 5 });
  }
  return m;
}

/// Appends a site at (x, y) of the strip.
void AddSite(const av::SimplexMesh& m, double x, double y, av::SiteSet& sites)
{
  av_test::AddSiteOverXY(m, x, y, 0.0, sites);
}

/// Total area of the dual (signed by +z), and whether every triangle faces +z.
double Area(const av::RestrictedDelaunayMesh& rdt, bool& upwards)
{
  auto at = [&](std::size_t t, int i)
  { return Eigen::Map<const Eigen::Vector3d>(rdt.Points.data() + 3 * rdt.Cells[3 * t + i]); };
  double area = 0.0;
  upwards = true;
  for (std::size_t t = 0; t < rdt.NumCells(); ++t)
  {
    const double z = (at(t, 1) - at(t, 0)).cross(at(t, 2) - at(t, 0)).z() / 2.0;
    area += z;
    upwards = upwards && z > 0.0;
  }
  return area;
}
} // namespace

int TestBoundaryNotchClosure(int, char*[])
{
  // Sites A, C on the bottom edge, D, E on the top edge (h = 1), B just inside the bottom edge.
  // The dual (A, B, D), (B, E, D), (B, C, E) has the boundary A -> B -> C -> E -> D -> A: the
  // strip between A-C and B is uncovered.
  const av::SimplexMesh strip = MakeStrip(1.0);
  av::SiteSet sites;
  sites.Dim = 3;
  AddSite(strip, 1.0, 0.0, sites); // A = 0
  AddSite(strip, 2.0, 0.3, sites); // B = 1
  AddSite(strip, 3.0, 0.0, sites); // C = 2
  AddSite(strip, 1.0, 1.0, sites); // D = 3
  AddSite(strip, 3.0, 1.0, sites); // E = 4
  AV_CHECK(sites.NumSites() == 5);
  const std::vector<std::int32_t> adjacency = av::ComputeElementAdjacency(strip);
  const std::vector<std::uint8_t> on = av::SitesOnOpenBoundary(strip, adjacency, sites);
  AV_CHECK((on == std::vector<std::uint8_t>{ 1, 0, 1, 1, 1 }));

  av::RestrictedDelaunayMesh rdt;
  rdt.SimplexDim = 2;
  rdt.AmbientDim = 3;
  rdt.Points = sites.Coords;
  rdt.Cells = { 0, 1, 3, 1, 4, 3, 1, 2, 4 };
  rdt.CellElement.assign(3, 0);
  rdt.Inverted.assign(3, 0);
  bool upwards = false;
  AV_CHECK(std::abs(Area(rdt, upwards) - 1.7) < 1e-12 && upwards);
  {
    av::RestrictedDelaunayMesh closed = rdt;
    const av::BoundaryNotchResult r = av::CloseBoundaryNotches(strip, sites, on, closed);
    AV_CHECK(r.Notches == 1 && r.Closed == 1 && r.Left == 0);
    AV_CHECK(closed.NumCells() == 4 && closed.CellElement.size() == 4 && closed.Inverted.size() == 4);
    // The ear (A, C, B): the dual now covers the rectangle A C E D exactly, facing up.
    AV_CHECK_MSG(std::abs(Area(closed, upwards) - 2.0) < 1e-12, "area " << Area(closed, upwards));
    AV_CHECK(upwards);
    AV_CHECK(closed.Cells[9] == 0 && closed.Cells[10] == 2 && closed.Cells[11] == 1);
    // Again: nothing left to do.
    const av::RestrictedDelaunayMesh once = closed;
    const av::BoundaryNotchResult again = av::CloseBoundaryNotches(strip, sites, on, closed);
    AV_CHECK(again.Notches == 0 && again.Closed == 0 && closed.Cells == once.Cells);
  }
  {
    // On a taller strip (h = 2) D and E are inside too, but at convex corners of the dual's
    // boundary: their ears (E, A, D) and (C, D, E) would fold back over (A, B, D) and
    // (B, C, E). Only B's notch is closed.
    const av::SimplexMesh tall = MakeStrip(2.0);
    av::SiteSet s;
    s.Dim = 3;
    for (std::size_t i = 0; i < sites.NumSites(); ++i)
      AddSite(tall, sites.Coords[3 * i], sites.Coords[3 * i + 1], s);
    const std::vector<std::uint8_t> onTall =
      av::SitesOnOpenBoundary(tall, av::ComputeElementAdjacency(tall), s);
    AV_CHECK((onTall == std::vector<std::uint8_t>{ 1, 0, 1, 0, 0 }));
    av::RestrictedDelaunayMesh closed = rdt;
    const av::BoundaryNotchResult r = av::CloseBoundaryNotches(tall, s, onTall, closed);
    AV_CHECK_MSG(r.Notches == 3 && r.Closed == 1 && r.Left == 2,
      r.Notches << " notches, " << r.Closed << " closed, " << r.Left << " left");
    AV_CHECK(std::abs(Area(closed, upwards) - 2.0) < 1e-12 && upwards);
  }
  {
    // A notch that faces the other way than the input (the strip's normal flipped) is not
    // closed: the ear would face against the surface.
    av::SimplexMesh down = strip;
    for (std::size_t c = 0; c < down.NumCells(); ++c)
      std::swap(down.Cells[3 * c + 1], down.Cells[3 * c + 2]);
    av::RestrictedDelaunayMesh same = rdt;
    const av::BoundaryNotchResult r = av::CloseBoundaryNotches(down, sites, on, same);
    AV_CHECK(r.Closed == 0 && same.Cells == rdt.Cells);
  }
  {
    // No site on an open boundary (a closed surface, or its sites all inside): unchanged.
    const std::vector<std::uint8_t> none(sites.NumSites(), 0);
    av::RestrictedDelaunayMesh same = rdt;
    const av::BoundaryNotchResult r = av::CloseBoundaryNotches(strip, sites, none, same);
    AV_CHECK(r.Closed == 0 && same.Cells == rdt.Cells);
    // Not a surface: unchanged.
    av::SimplexMesh flat = strip;
    flat.AmbientDim = 2;
    AV_CHECK(av::SitesOnOpenBoundary(flat, adjacency, sites) == none);
  }
  return av_test::Failures();
}
