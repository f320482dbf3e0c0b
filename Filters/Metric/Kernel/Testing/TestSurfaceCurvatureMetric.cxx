// SPDX-License-Identifier: BSD-3-Clause
// SurfaceCurvatureMetric: principal curvatures and directions on a cylinder (known: 1/r around,
// 0 along the axis), isotropy on a sphere, a flat patch, Eq. 19 structure, creases (a box, a
// capped cylinder, a smooth torus unchanged), errors.
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
    o.CreaseAngle = 30.0;
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

  // Creases (CreaseAngle 30 degrees; the default 180 is off): a box is flat on every face, so with the creases
  // found the metric is isotropic everywhere; read as smooth (180), its edges look curved.
  {
    const double lo[3] = { 0, 0, 0 }, hi[3] = { 2, 1, 1 };
    const int n[3] = { 8, 4, 4 };
    const av::SimplexMesh box = av::MakeBoxSurface(lo, hi, n);
    av::SurfaceCurvatureMetricOptions o;
    o.CreaseAngle = 30.0;
    const auto r = av::SurfaceCurvatureMetric(box, o);
    AV_CHECK_MSG(r.NumCreaseEdges == 4 * (8 + 4 + 4), r.NumCreaseEdges << " crease edges");
    double maxRatio = 0.0;
    for (double ratio : r.StretchRatio)
      maxRatio = std::max(maxRatio, ratio);
    AV_CHECK_MSG(maxRatio < 1.0 + 1e-9, "box with creases: stretch ratio up to " << maxRatio);
    o.CreaseAngle = 180.0;
    const auto smooth = av::SurfaceCurvatureMetric(box, o);
    AV_CHECK(smooth.NumCreaseEdges == 0);
    const double smoothMax =
      *std::max_element(smooth.StretchRatio.begin(), smooth.StretchRatio.end());
    AV_CHECK_MSG(smoothMax > 3.0, "box read as smooth: stretch ratio only up to " << smoothMax);
  }

  // A capped cylinder (radius 1, height 4): with the rims as creases the flat caps have no
  // curvature (their centres' one-rings are all cap) and the rim vertices at most the side's
  // (1 around, the caps' 0 averaged in); read as smooth, the rim normals tilt the caps' fits.
  // Far from the rims the metric is the same bit for bit.
  {
    const int around = 64, along = 40;
    av::SimplexMesh cyl = av::MakeCylinderSurface(1.0, 4.0, around, along);
    const auto bottom = static_cast<std::int32_t>(cyl.NumPoints());
    cyl.Points.insert(cyl.Points.end(), { 0.0, 0.0, 0.0, 0.0, 0.0, 4.0 });
    const std::int32_t top = bottom + 1, topRing = along * around;
    for (std::int32_t i = 0; i < around; ++i)
    {
      const std::int32_t j = (i + 1) % around;
      cyl.Cells.insert(cyl.Cells.end(), { bottom, j, i, top, topRing + i, topRing + j });
    }
    av::SurfaceCurvatureMetricOptions o;
    o.CreaseAngle = 30.0;
    const auto r = av::SurfaceCurvatureMetric(cyl, o);
    o.CreaseAngle = 180.0;
    const auto smooth = av::SurfaceCurvatureMetric(cyl, o);
    AV_CHECK_MSG(r.NumCreaseEdges == 2 * around, r.NumCreaseEdges << " crease edges");
    double rimK = 0.0, rimKSmooth = 0.0;
    int rim = 0, middle = 0, middleDiffers = 0;
    for (std::size_t i = 0; i + 2 < cyl.NumPoints(); ++i)
    {
      const double z = cyl.Point(i)[2];
      if (z == 0.0 || z == 4.0)
      {
        ++rim;
        rimK = std::max(rimK, std::abs(r.MaxCurvature[i]));
        rimKSmooth = std::max(rimKSmooth, std::abs(smooth.MaxCurvature[i]));
      }
      else if (z > 1.0 && z < 3.0)
      {
        ++middle;
        for (int k = 0; k < 6; ++k)
          middleDiffers += r.Metric.At(i)[k] != smooth.Metric.At(i)[k];
      }
    }
    AV_CHECK(rim == 2 * around && middle > 1000);
    AV_CHECK_MSG(rimK < 1.1, "rim curvature " << rimK << " with creases (the side's is 1)");
    AV_CHECK_MSG(rimKSmooth > 0.5, "rim curvature " << rimKSmooth << " without creases");
    for (const std::int32_t centre : { bottom, top })
    {
      const auto c = static_cast<std::size_t>(centre);
      AV_CHECK_MSG(std::abs(r.MaxCurvature[c]) < 1e-9,
        "cap centre curvature " << r.MaxCurvature[c] << " with creases (flat)");
      AV_CHECK_MSG(std::abs(smooth.MaxCurvature[c]) > 0.5,
        "cap centre curvature " << smooth.MaxCurvature[c] << " without creases");
    }
    AV_CHECK_MSG(middleDiffers == 0, middleDiffers << " metric entries changed far from the rims");
  }

  // A smooth surface has no crease: the metric is the same bit for bit as with CreaseAngle 180.
  {
    const av::SimplexMesh torus = av::MakeTorusSurface(3.0, 1.0, 48, 24);
    av::SurfaceCurvatureMetricOptions o;
    o.CreaseAngle = 30.0;
    const auto r = av::SurfaceCurvatureMetric(torus, o);
    o.CreaseAngle = 180.0;
    const auto smooth = av::SurfaceCurvatureMetric(torus, o);
    AV_CHECK(r.NumCreaseEdges == 0);
    AV_CHECK(r.Metric.Values == smooth.Metric.Values);
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
    av::SurfaceCurvatureMetricOptions badCrease;
    badCrease.CreaseAngle = 0.0;
    AV_CHECK_THROWS(av::SurfaceCurvatureMetric(sphere, badCrease));
    badCrease.CreaseAngle = std::nan("");
    AV_CHECK_THROWS(av::SurfaceCurvatureMetric(sphere, badCrease));
  }
  return AV_TEST_RESULT();
}
