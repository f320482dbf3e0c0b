// SPDX-License-Identifier: BSD-3-Clause
// Tests of ComputeDomainAngleBound: a cube has 90 degree edges, a wedge its opening angle; a
// metric that stretches one axis changes the angle as the mapped geometry says; a dihedral angle
// of a mesh of the domain never beats the bound (checked on the wedge); bad input is refused.
#include "AnisoTestChecks.h"
#include "DomainAngleBound.h"
#include "InputError.h"
#include "MeshQuality.h"
#include "MeshTopology.h"

#include <cmath>
#include <iostream>
#include <utility>
#include <vector>

namespace
{
const double Pi = 3.14159265358979323846;

av::MetricField Diagonal(std::size_t n, double xx, double yy, double zz)
{
  av::MetricField m;
  m.Values.assign(6 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
  {
    m.Values[6 * i] = xx;
    m.Values[6 * i + 1] = yy;
    m.Values[6 * i + 2] = zz;
  }
  return m;
}

// The unit cube as 6 tets around its diagonal (0, 0, 0) - (1, 1, 1).
av::SimplexMesh Cube()
{
  av::SimplexMesh m;
  for (int i = 0; i < 8; ++i)
    m.Points.insert(m.Points.end(), { double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1) });
  m.Cells = { 0, 1, 3, 7, 0, 3, 2, 7, 0, 2, 6, 7, 0, 6, 4, 7, 0, 4, 5, 7, 0, 5, 1, 7 };
  return m;
}

// A wedge of opening angle `degrees` along the z axis, split into 3 tets: the prism over the
// triangle (0,0) (1,0) (cos a, sin a).
av::SimplexMesh Wedge(double degrees)
{
  const double a = degrees * Pi / 180.0;
  av::SimplexMesh m;
  const double xy[3][2] = { { 0, 0 }, { 1, 0 }, { std::cos(a), std::sin(a) } };
  for (int z = 0; z < 2; ++z)
    for (const auto& p : xy)
      m.Points.insert(m.Points.end(), { p[0], p[1], double(z) });
  m.Cells = { 0, 1, 2, 3, 1, 2, 3, 4, 2, 3, 4, 5 };
  for (std::size_t c = 0; c < m.NumCells(); ++c)
    if (av::CellMeasure(m, c) < 0.0)
      std::swap(m.Cells[4 * c + 2], m.Cells[4 * c + 3]);
  return m;
}
} // namespace

int TestDomainAngleBound(int, char*[])
{
  {
    const av::DomainAngleBound b = av::ComputeDomainAngleBound(Cube(), Diagonal(8, 1, 1, 1));
    std::cout << "cube: " << b.MinAngle << " deg over " << b.NumBoundaryEdges << " edges\n";
    AV_CHECK_NEAR(b.MinAngle, 90.0, 1e-9); // the 12 edges at 90, the face diagonals at 180
    AV_CHECK(b.NumBoundaryEdges == 18 && b.NumBelow15 == 0 && b.NumBelow20 == 0);
  }
  {
    const av::SimplexMesh w = Wedge(40.0);
    const av::DomainAngleBound b = av::ComputeDomainAngleBound(w, Diagonal(6, 1, 1, 1));
    AV_CHECK_NEAR(b.MinAngle, 40.0, 1e-9);
    AV_CHECK(b.NumBelow15 == 0 && b.NumBelow20 == 0);
    // Stretched along y by 0.25 (metric yy = 1/16): the 40 degree opening becomes
    // atan(0.25 tan 40) in the metric, an exact result of the mapping.
    const double expected = std::atan(0.25 * std::tan(40.0 * Pi / 180.0)) * 180.0 / Pi;
    const av::DomainAngleBound s = av::ComputeDomainAngleBound(w, Diagonal(6, 1, 1.0 / 16, 1));
    std::cout << "wedge 40 deg, y shrunk 4x: " << s.MinAngle << " deg (" << expected << ")\n";
    AV_CHECK_NEAR(s.MinAngle, expected, 1e-9);
    AV_CHECK(s.NumBelow15 >= 1 && s.NumBelow20 >= 1);
    // No tet of the wedge has a dihedral angle above the bound.
    const av::MeshQualityResult q = av::EvaluateMeshQuality(w, Diagonal(6, 1, 1.0 / 16, 1));
    AV_CHECK_MSG(q.Summary.ThetaMin <= s.MinAngle + 1e-9,
      q.Summary.ThetaMin << " above the bound " << s.MinAngle);
  }
  {
    av::SimplexMesh bad = Cube();
    AV_CHECK_THROWS(av::ComputeDomainAngleBound(bad, Diagonal(7, 1, 1, 1)));
    bad.Cells[3] = 9;
    AV_CHECK_THROWS(av::ComputeDomainAngleBound(bad, Diagonal(8, 1, 1, 1)));
    av::MetricField nan = Diagonal(8, 1, 1, 1);
    nan.Values[4] = std::nan("");
    AV_CHECK_THROWS(av::ComputeDomainAngleBound(Cube(), nan));
    av::SimplexMesh tri;
    tri.SimplexDim = 2;
    tri.Points = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
    tri.Cells = { 0, 1, 2 };
    AV_CHECK_THROWS(av::ComputeDomainAngleBound(tri, Diagonal(3, 1, 1, 1)));
  }
  return AV_TEST_RESULT();
}
