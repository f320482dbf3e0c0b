// SPDX-License-Identifier: BSD-3-Clause
// SurfaceCurvatureMetric: principal curvatures and directions on a cylinder (known: 1/r around,
// 0 along the axis), isotropy on a sphere, a flat patch, Eq. 19 structure, errors.
#include "MetricAlgebra.h"
#include "SurfaceCurvatureMetric.h"
#include "SurfaceGenerators.h"
#include "AnisoTestChecks.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

int TestSurfaceCurvatureMetric(int, char*[])
{
  // Cylinder of radius 1 (open, z in [0, 4]): K_max = 1 around, K_min = 0 along z.
  {
    const av::SimplexMesh cyl = av::MakeCylinderSurface(1.0, 4.0, 64, 40);
    av::SurfaceCurvatureMetricOptions o;
    const auto r = av::SurfaceCurvatureMetric(cyl, o);
    const double diag = std::sqrt(2.0 * 2.0 + 2.0 * 2.0 + 4.0 * 4.0);
    AV_CHECK_NEAR(r.CurvatureFloor, 0.1 / diag, 1e-12);
    const double expectRatio = std::sqrt(1.0 / r.CurvatureFloor); // ~7, below the cap of 10
    int checked = 0, badK = 0, badDir = 0, badRatio = 0, badM = 0;
    for (std::size_t i = 0; i < cyl.NumPoints(); ++i)
    {
      const double* p = cyl.Point(i);
      if (p[2] < 1.0 || p[2] > 3.0)
      {
        continue; // away from the open ends
      }
      ++checked;
      badK += std::abs(std::abs(r.MaxCurvature[i]) - 1.0) > 0.05 || std::abs(r.MinCurvature[i]) > 0.05;
      const Eigen::Vector3d vmax(r.MaxDirection.data() + 3 * i);
      const Eigen::Vector3d vmin(r.MinDirection.data() + 3 * i);
      badDir += std::abs(vmax[2]) > 0.02 || std::abs(vmin[2]) < 0.999;
      badRatio += std::abs(r.StretchRatio[i] / expectRatio - 1.0) > 0.05;
      // Eq. 19: the circumferential direction gets ratio^2, the axis 1, the normal 0.
      const Eigen::Matrix3d M = av::UnpackSymmetric(r.Metric.At(i));
      const Eigen::Vector3d around(-p[1], p[0], 0.0), axis(0, 0, 1), n(p[0], p[1], 0.0);
      const double rr = r.StretchRatio[i] * r.StretchRatio[i];
      badM += std::abs(around.dot(M * around) / rr - 1.0) > 0.01 ||
        std::abs(axis.dot(M * axis) - 1.0) > 0.05 || (M * n).norm() > 1e-9;
    }
    AV_CHECK(checked > 1000);
    AV_CHECK_MSG(badK == 0, badK << " vertices with wrong curvatures");
    AV_CHECK_MSG(badDir == 0, badDir << " vertices with wrong directions");
    AV_CHECK_MSG(badRatio == 0, badRatio << " vertices with a wrong stretch ratio");
    AV_CHECK_MSG(badM == 0, badM << " vertices with a wrong metric");

    // The cap applies.
    o.MaxStretch = 3.0;
    const auto capped = av::SurfaceCurvatureMetric(cyl, o);
    AV_CHECK_NEAR(*std::max_element(capped.StretchRatio.begin(), capped.StretchRatio.end()), 3.0,
      1e-12);
  }

  // Sphere: umbilic everywhere, so the metric is (nearly) isotropic in the tangent plane.
  {
    const av::SimplexMesh sphere = av::MakeIcosphere(2.0, 4);
    const auto r = av::SurfaceCurvatureMetric(sphere, av::SurfaceCurvatureMetricOptions());
    double maxRatio = 0.0, worstK = 0.0;
    for (std::size_t i = 0; i < sphere.NumPoints(); ++i)
    {
      maxRatio = std::max(maxRatio, r.StretchRatio[i]);
      worstK = std::max({ worstK, std::abs(std::abs(r.MinCurvature[i]) - 0.5),
        std::abs(std::abs(r.MaxCurvature[i]) - 0.5) });
      const Eigen::Vector3d n(r.Normals.data() + 3 * i);
      AV_CHECK(n.dot(Eigen::Map<const Eigen::Vector3d>(sphere.Point(i)).normalized()) > 0.999);
    }
    AV_CHECK_MSG(maxRatio < 1.05, "sphere stretch ratio up to " << maxRatio);
    AV_CHECK_MSG(worstK < 0.02, "sphere curvature off by " << worstK);
  }

  // Flat patch: both curvatures vanish, both hit the floor, ratio exactly 1.
  {
    av::SimplexMesh flat;
    flat.SimplexDim = 2;
    const int n = 6;
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i)
        flat.Points.insert(flat.Points.end(), { 1.0 * i, 1.0 * j, 0.0 });
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const std::int32_t a = i + (n + 1) * j, b = a + 1, c = a + n + 2, d = a + n + 1;
        flat.Cells.insert(flat.Cells.end(), { a, b, c, a, c, d });
      }
    const auto r = av::SurfaceCurvatureMetric(flat, av::SurfaceCurvatureMetricOptions());
    for (double ratio : r.StretchRatio)
    {
      AV_CHECK_NEAR(ratio, 1.0, 1e-9);
    }
  }

  // Errors.
  {
    av::SimplexMesh sphere = av::MakeIcosphere(1.0, 1);
    av::SimplexMesh volume = sphere;
    volume.SimplexDim = 3;
    AV_CHECK_THROWS(av::SurfaceCurvatureMetric(volume, av::SurfaceCurvatureMetricOptions()));
    av::SimplexMesh nan = sphere;
    nan.Points[5] = std::nan("");
    AV_CHECK_THROWS(av::SurfaceCurvatureMetric(nan, av::SurfaceCurvatureMetricOptions()));
    av::SimplexMesh orphan = sphere;
    orphan.Points.insert(orphan.Points.end(), { 5, 5, 5 });
    AV_CHECK_THROWS(av::SurfaceCurvatureMetric(orphan, av::SurfaceCurvatureMetricOptions()));
    av::SimplexMesh degenerate = sphere;
    degenerate.Cells[2] = degenerate.Cells[1];
    AV_CHECK_THROWS(av::SurfaceCurvatureMetric(degenerate, av::SurfaceCurvatureMetricOptions()));
    av::SurfaceCurvatureMetricOptions bad;
    bad.CurvatureThreshold = 0.0;
    AV_CHECK_THROWS(av::SurfaceCurvatureMetric(sphere, bad));
  }
  return AV_TEST_RESULT();
}
