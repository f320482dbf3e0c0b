// SPDX-License-Identifier: BSD-3-Clause
// Domain chords (DomainChords.h) and the cells-across limit of the metric preparation
// (MetricPreparationOptions::MinCellsAcross): on a thin slab the chords are its exact
// thickness and width; an L-shaped domain stops the chords at its re-entrant boundary; the
// limit raises the metric across the slab only, to the asked number of cells, and lowers the
// number of cells across when the slab alone would need more than the target.
#include "AnisoTestChecks.h"
#include "DomainChords.h"
#include "MetricAlgebra.h"
#include "MetricFieldOps.h"
#include "MetricPreparation.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <vector>

namespace
{
/// nx x ny x nz boxes of [0, sx] x [0, sy] x [0, sz], six Kuhn tetrahedra each; `keep(i, j, k)`
/// says which boxes are in the domain.
template <class Keep>
av::SimplexMesh Slab(int nx, int ny, int nz, double sx, double sy, double sz, const Keep& keep)
{
  av::SimplexMesh mesh;
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        mesh.Points.insert(mesh.Points.end(), { sx * i / nx, sy * j / ny, sz * k / nz });
  auto id = [&](int i, int j, int k) { return (k * (ny + 1) + j) * (nx + 1) + i; };
  const int paths[6][3] = {
    { 0, 1, 2 }, { 0, 2, 1 }, { 1, 0, 2 }, { 1, 2, 0 }, { 2, 0, 1 }, { 2, 1, 0 }
  };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
      {
        if (!keep(i, j, k))
          continue;
        for (const auto& path : paths)
        {
          int c[3] = { i, j, k };
          mesh.Cells.push_back(id(c[0], c[1], c[2]));
          for (int axis : path)
          {
            ++c[axis];
            mesh.Cells.push_back(id(c[0], c[1], c[2]));
          }
        }
      }
  return mesh;
}

/// Index of the direction closest to the unit vector u.
std::size_t DirectionIndex(const av::DomainChords& c, const Eigen::Vector3d& u)
{
  std::size_t best = 0;
  double bestDot = -2.0;
  for (std::size_t k = 0; k < c.NumDirections(); ++k)
  {
    const double d =
      std::abs(Eigen::Map<const Eigen::Vector3d>(c.Directions.data() + 3 * k).dot(u));
    if (d > bestDot)
    {
      bestDot = d;
      best = k;
    }
  }
  return best;
}

av::MetricField Isotropic(std::size_t n, double size)
{
  av::MetricField f;
  f.Values.assign(6 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a)
      f.Values[6 * i + a] = 1.0 / (size * size);
  return f;
}

void CheckSlabChords()
{
  const av::SimplexMesh slab = Slab(10, 8, 2, 1.0, 0.8, 0.1, [](int, int, int) { return true; });
  const av::DomainChords c = av::ComputeDomainChords(slab);
  AV_CHECK(c.Dimension == 3 && c.NumDirections() == 13);
  AV_CHECK(c.Chord.size() == slab.NumPoints() * 13);
  const std::size_t x = DirectionIndex(c, { 1, 0, 0 }), y = DirectionIndex(c, { 0, 1, 0 }),
                    z = DirectionIndex(c, { 0, 0, 1 });
  std::size_t bad = 0;
  for (std::size_t i = 0; i < slab.NumPoints(); ++i)
  {
    bad += std::abs(c.Chord[13 * i + x] - 1.0) > 1e-9;
    bad += std::abs(c.Chord[13 * i + y] - 0.8) > 1e-9;
    bad += std::abs(c.Chord[13 * i + z] - 0.1) > 1e-9;
    // Every chord is a segment of the box: positive, at most its diagonal.
    for (std::size_t k = 0; k < 13; ++k)
      bad +=
        !(c.Chord[13 * i + k] > 0.0 && c.Chord[13 * i + k] <= std::sqrt(1.0 + 0.64 + 0.01) + 1e-9);
  }
  AV_CHECK_MSG(bad == 0, bad << " wrong chord(s) on the slab");

  // A walk capped at 2 elements does not reach across the slab's width: +inf there.
  const av::DomainChords capped = av::ComputeDomainChords(slab, 2);
  AV_CHECK(std::isinf(capped.Chord[13 * 0 + x]));
}

void CheckLShapeChords()
{
  // [0,1]^2 x [0, 0.2] without the quarter x > 0.5, y > 0.5: along x, a vertex with y > 0.5
  // sees only the arm of width 0.5, not the whole width 1.
  const av::SimplexMesh l =
    Slab(4, 4, 1, 1.0, 1.0, 0.2, [](int i, int j, int) { return i < 2 || j < 2; });
  const av::DomainChords c = av::ComputeDomainChords(l);
  const std::size_t x = DirectionIndex(c, { 1, 0, 0 });
  std::size_t checked = 0, bad = 0;
  for (std::size_t i = 0; i < l.NumPoints(); ++i)
  {
    const double* p = l.Point(i);
    if (p[1] > 0.6 && p[0] < 0.4) // only elements of the arm around it
    {
      ++checked;
      bad += std::abs(c.Chord[13 * i + x] - 0.5) > 1e-9;
    }
  }
  AV_CHECK(checked > 0);
  AV_CHECK_MSG(bad == 0, bad << " of " << checked << " arm chord(s) not 0.5");
}

void CheckThicknessLimit()
{
  const av::SimplexMesh slab = Slab(10, 8, 2, 1.0, 0.8, 0.1, [](int, int, int) { return true; });
  // Cells of size 0.3: more than 2 across the width (1) and the depth (0.8), much thicker than
  // the slab (0.1).
  const av::MetricField big = Isotropic(slab.NumPoints(), 0.3);
  av::MetricPreparationOptions o;
  o.Gradation = false;
  o.MinCellsAcross = 2.0;
  const av::MetricPreparationResult r = av::PrepareMetric(slab, big, o);
  const av::DomainChords chords = av::ComputeDomainChords(slab);
  std::size_t bad = 0, short_ = 0, grown = 0, interior = 0;
  for (std::size_t i = 0; i < slab.NumPoints(); ++i)
  {
    const Eigen::Matrix3d m = av::UnpackSymmetric(r.Metric.At(i));
    // Every chord holds at least 2 unit lengths, and the metric only grew.
    for (std::size_t k = 0; k < 13; ++k)
    {
      const Eigen::Map<const Eigen::Vector3d> d(chords.Directions.data() + 3 * k);
      short_ += chords.Chord[13 * i + k] * std::sqrt(d.dot(m * d)) < 2.0 - 1e-9;
    }
    grown += Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m - Eigen::Matrix3d::Identity() / 0.09)
               .eigenvalues()
               .minCoeff() < -1e-9;
    // Away from the slab's edges: exactly 2 unit lengths across the thickness 0.1 (M_zz =
    // 400), the size 0.3 kept in the plane (the diagonal chords are satisfied by the update
    // across).
    const double* p = slab.Point(i);
    if (p[0] > 0.3 && p[0] < 0.7 && p[1] > 0.3 && p[1] < 0.5)
    {
      ++interior;
      bad += std::abs(0.1 * std::sqrt(m(2, 2)) - 2.0) > 1e-9;
      bad += std::abs(m(0, 0) - 1.0 / 0.09) > 1e-9 || std::abs(m(1, 1) - 1.0 / 0.09) > 1e-9;
      bad += std::abs(m(0, 1)) > 1e-9 || std::abs(m(0, 2)) > 1e-9 || std::abs(m(1, 2)) > 1e-9;
    }
  }
  AV_CHECK_MSG(short_ == 0 && grown == 0,
    short_ << " chord(s) under 2 unit lengths, " << grown << " metric(s) lowered");
  AV_CHECK(interior > 0);
  AV_CHECK_MSG(bad == 0, bad << " interior vertex metric(s) not limited as expected");
  AV_CHECK(r.NumThicknessLimited == slab.NumPoints() && r.CellsAcross == 2.0);

  // Off: the metric stays.
  o.MinCellsAcross = 0.0;
  const av::MetricPreparationResult off = av::PrepareMetric(slab, big, o);
  double change = 0.0;
  for (std::size_t v = 0; v < big.Values.size(); ++v)
    change = std::max(change, std::abs(off.Metric.Values[v] - big.Values[v]));
  AV_CHECK(off.NumThicknessLimited == 0 && change < 1e-12);

  // A cube of side 0.1 is thin in every direction: at 2 cells across it alone asks for about
  // 0.001 x 20^3 / UnitVertexMeasure(3) sites, far more than 5. Fewer cells across, and the
  // target is met.
  const av::SimplexMesh cube = Slab(2, 2, 2, 0.1, 0.1, 0.1, [](int, int, int) { return true; });
  o.MinCellsAcross = 2.0;
  o.TargetSites = 5.0;
  const av::MetricPreparationResult fit =
    av::PrepareMetric(cube, Isotropic(cube.NumPoints(), 1.0), o);
  AV_CHECK_MSG(fit.CellsAcross > 0.0 && fit.CellsAcross < 2.0, "cells across " << fit.CellsAcross);
  AV_CHECK_MSG(std::abs(fit.ImpliedSites / 5.0 - 1.0) < 0.06, "implied sites " << fit.ImpliedSites);

  // With the gradation, a thin part's floor also holds the sizes graded from it, so scaling
  // the metric down stops lowering the complexity (squareBend). The preparation must then
  // lower the cells across instead of driving the scale to 0, and still meet the target in a
  // few gradations (31 before that, 10 now).
  const av::SimplexMesh plate = Slab(12, 12, 1, 1.0, 1.0, 0.05, [](int, int, int) { return true; });
  av::MetricPreparationOptions g;
  g.MinCellsAcross = 2.0;
  g.TargetSites = 40.0;
  const av::MetricPreparationResult graded =
    av::PrepareMetric(plate, Isotropic(plate.NumPoints(), 0.5), g);
  AV_CHECK_MSG(
    graded.CellsAcross > 0.0 && graded.CellsAcross < 2.0, "cells across " << graded.CellsAcross);
  AV_CHECK_MSG(
    std::abs(graded.ImpliedSites / 40.0 - 1.0) < 0.05, "implied sites " << graded.ImpliedSites);
  AV_CHECK_MSG(graded.GradationRuns <= 16, graded.GradationRuns << " gradations");

  // Bad input.
  o.MinCellsAcross = -1.0;
  AV_CHECK_THROWS(av::PrepareMetric(slab, big, o));
  AV_CHECK_THROWS(av::ComputeDomainChords(av::SimplexMesh()));
}
} // namespace

int TestDomainChords(int, char*[])
{
  CheckSlabChords();
  CheckLShapeChords();
  CheckThicknessLimit();
  return AV_TEST_RESULT();
}
