// SPDX-License-Identifier: BSD-3-Clause
// Tests of ConsecutiveFeatureSites and RecoverFeatureEdges on a roof (two planes meeting at a
// 90-degree ridge): the two ridge sites are paired through the ridge vertex between them; the
// dual triangles that cut across the ridge are flipped so that every triangle then lies in
// one of the two planes; a required edge is never flipped away; volumes are left alone.
#include "FeatureEdgeRecovery.h"
#include "SharpFeatures.h"
#include "AnisoTestChecks.h"
#include "HeightFieldSites.h"

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <vector>

namespace
{
double Roof(double y)
{
  return 1.0 - std::abs(y);
}

/// The roof z = 1 - |y| over [0, 2] x [-1, 1]: a 3 x 3 grid of points, each square cut into two
/// triangles oriented with +z normals; the ridge is the line y = 0.
av::SimplexMesh MakeRoof()
{
  av::SimplexMesh m;
  m.AmbientDim = 3;
  m.SimplexDim = 2;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      m.Points.insert(m.Points.end(), { double(i), double(j - 1), Roof(j - 1) });
  auto id = [](int i, int j) { return j * 3 + i; };
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i)
    {
      m.Cells.insert(m.Cells.end(), { id(i, j), id(i + 1, j), id(i + 1, j + 1) });
      m.Cells.insert(m.Cells.end(), { id(i, j), id(i + 1, j + 1), id(i, j + 1) });
    }
  return m;
}

/// Appends a site at (x, y) on the roof.
void AddSite(const av::SimplexMesh& m, double x, double y, av::SiteSet& sites)
{
  av_test::AddSiteOverXY(m, x, y, Roof(y), sites);
}

bool HasEdge(const av::RestrictedDelaunayMesh& rdt, std::int32_t a, std::int32_t b)
{
  for (std::size_t t = 0; t < rdt.NumCells(); ++t)
  {
    const std::int32_t* v = rdt.Cells.data() + 3 * t;
    for (int i = 0; i < 3; ++i)
      if ((v[i] == a && v[(i + 1) % 3] == b) || (v[i] == b && v[(i + 1) % 3] == a))
        return true;
  }
  return false;
}

/// Largest distance of a triangle's centroid from the roof, and whether all face +z.
double WorstCentroidOffset(const av::RestrictedDelaunayMesh& rdt, bool& upwards)
{
  double worst = 0.0;
  upwards = true;
  for (std::size_t t = 0; t < rdt.NumCells(); ++t)
  {
    Eigen::Vector3d p[3];
    for (int i = 0; i < 3; ++i)
      p[i] = Eigen::Map<const Eigen::Vector3d>(rdt.Points.data() + 3 * rdt.Cells[3 * t + i]);
    const Eigen::Vector3d c = (p[0] + p[1] + p[2]) / 3.0;
    worst = std::max(worst, std::abs(c.z() - Roof(c.y())));
    upwards = upwards && (p[1] - p[0]).cross(p[2] - p[0]).z() > 0.0;
  }
  return worst;
}
} // namespace

int TestFeatureEdgeRecovery(int, char*[])
{
  const av::SimplexMesh roof = MakeRoof();
  const av::SharpFeatures features = av::DetectSharpFeatures(roof, 30.0);
  AV_CHECK(features.NumEdges() == 2); // the ridge, split at its middle vertex

  // Sites: A and B on the ridge, either side of its middle vertex; C and D off it, one on
  // each plane; E at the ridge's end vertex (a corner: the ridge meets the boundary there).
  av::SiteSet sites;
  sites.Dim = 3;
  AddSite(roof, 0.5, 0.0, sites);  // A = 0
  AddSite(roof, 1.5, 0.0, sites);  // B = 1
  AddSite(roof, 1.0, 0.5, sites);  // C = 2
  AddSite(roof, 1.0, -0.5, sites); // D = 3
  AV_CHECK(sites.NumSites() == 4);
  {
    const std::vector<std::array<std::int32_t, 2>> pairs =
      av::ConsecutiveFeatureSites(roof, features, sites);
    AV_CHECK(pairs.size() == 1 && pairs[0][0] == 0 && pairs[0][1] == 1);
    av::SiteSet withCorner = sites;
    AddSite(roof, 2.0, 0.0, withCorner); // E = 4, at the ridge's end
    const std::vector<std::array<std::int32_t, 2>> more =
      av::ConsecutiveFeatureSites(roof, features, withCorner);
    AV_CHECK(more.size() == 2 && more[1][0] == 1 && more[1][1] == 4);
  }

  // The dual cuts across the ridge: (A, D, C) and (C, D, B) share the edge C-D.
  av::RestrictedDelaunayMesh rdt;
  rdt.SimplexDim = 2;
  rdt.AmbientDim = 3;
  rdt.Points = sites.Coords;
  rdt.Cells = { 0, 3, 2, 2, 3, 1 };
  bool upwards = false;
  AV_CHECK(WorstCentroidOffset(rdt, upwards) > 0.1);
  AV_CHECK(upwards);

  const std::vector<std::array<std::int32_t, 2>> required =
    av::ConsecutiveFeatureSites(roof, features, sites);
  {
    av::RestrictedDelaunayMesh flipped = rdt;
    const av::FeatureEdgeRecoveryResult r =
      av::RecoverFeatureEdges(roof, sites, required, flipped);
    AV_CHECK(r.Required == 1 && r.Present == 0 && r.Recovered == 1 && r.Missing == 0);
    AV_CHECK(HasEdge(flipped, 0, 1));
    AV_CHECK(!HasEdge(flipped, 2, 3));
    // Both triangles now lie in the planes, still facing up.
    AV_CHECK(WorstCentroidOffset(flipped, upwards) < 1e-12);
    AV_CHECK(upwards);
    // Run again: the edge is there, nothing changes.
    const av::RestrictedDelaunayMesh once = flipped;
    const av::FeatureEdgeRecoveryResult again =
      av::RecoverFeatureEdges(roof, sites, required, flipped);
    AV_CHECK(again.Present == 1 && again.Recovered == 0 && flipped.Cells == once.Cells);
  }
  {
    // A required edge C-D is never flipped away.
    std::vector<std::array<std::int32_t, 2>> both = required;
    both.push_back({ 2, 3 });
    av::RestrictedDelaunayMesh kept = rdt;
    const av::FeatureEdgeRecoveryResult r = av::RecoverFeatureEdges(roof, sites, both, kept);
    AV_CHECK(r.Recovered == 0 && r.Missing == 1 && kept.Cells == rdt.Cells);
  }
  {
    // A flip whose new triangle would face down is refused: D moved across the ridge onto
    // C's plane, beyond B, so that (A, D, B) would be reversed there.
    av::SiteSet moved;
    moved.Dim = 3;
    AddSite(roof, 0.5, 0.0, moved);
    AddSite(roof, 1.5, 0.0, moved);
    AddSite(roof, 1.0, 0.5, moved);
    AddSite(roof, 1.9, 0.9, moved);
    av::RestrictedDelaunayMesh bad = rdt;
    bad.Points = moved.Coords;
    const av::FeatureEdgeRecoveryResult r = av::RecoverFeatureEdges(roof, moved, required, bad);
    AV_CHECK(r.Recovered == 0 && r.Missing == 1 && bad.Cells == rdt.Cells);
  }
  {
    // Not a surface (2D domain or volume): unchanged.
    av::SimplexMesh flat = roof;
    flat.AmbientDim = 2;
    av::RestrictedDelaunayMesh same = rdt;
    const av::FeatureEdgeRecoveryResult r = av::RecoverFeatureEdges(flat, sites, required, same);
    AV_CHECK(r.Recovered == 0 && same.Cells == rdt.Cells);
  }
  return av_test::Failures();
}
