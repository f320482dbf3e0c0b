// SPDX-License-Identifier: BSD-3-Clause
#include "MeshImprovement.h"

#include "MeshTopology.h"
#include "MetricAlgebra.h"
#include "MetricSimplexQuality.h"
#include "TetMeshImprover.h"
#include "TriangleMeshImprover.h"

#include <cmath>
#include <string>

namespace av
{

double MetricSimplexQuality(int simplexDim,
  const double* const* points,
  const double* const* sqrtMetrics)
{
  if (simplexDim == 3)
  {
    Eigen::Vector3d p[4];
    Eigen::Matrix3d s[4];
    for (int i = 0; i < 4; ++i)
    {
      p[i] = Eigen::Map<const Eigen::Vector3d>(points[i]);
      s[i] = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(sqrtMetrics[i]);
    }
    return TetQuality(MappedTet(p[0], p[1], p[2], p[3], s[0], s[1], s[2], s[3]));
  }
  if (simplexDim == 2)
  {
    Eigen::Vector2d p[3];
    Eigen::Matrix2d s[3];
    for (int i = 0; i < 3; ++i)
    {
      p[i] = Eigen::Map<const Eigen::Vector2d>(points[i]);
      s[i] = Eigen::Map<const Eigen::Matrix<double, 2, 2, Eigen::RowMajor>>(sqrtMetrics[i]);
    }
    return TriangleMetricQuality(p[0], p[1], p[2], s[0], s[1], s[2]);
  }
  throw InputError("MetricSimplexQuality: simplexDim must be 2 or 3");
}

namespace
{
void ValidateImprovementInput(const SimplexMesh& mesh,
  const MetricField& metric,
  const std::vector<std::uint8_t>* fixedPoints)
{
  const char* who = "ImproveMesh";
  if (mesh.SimplexDim != 2 && mesh.SimplexDim != 3)
    throw InputError(std::string(who) + ": SimplexDim must be 2 or 3");
  if (mesh.AmbientDim < mesh.SimplexDim || mesh.AmbientDim > 3 ||
    mesh.Points.size() % static_cast<std::size_t>(mesh.AmbientDim) != 0 ||
    mesh.Cells.size() % static_cast<std::size_t>(mesh.SimplexDim + 1) != 0)
    throw InputError(std::string(who) + ": inconsistent mesh sizes");
  CheckCellIds(mesh, who, "cell");
  if (metric.Values.size() != 6 * mesh.NumPoints())
    throw InputError(std::string(who) + ": the metric must have 6 values per point");
  if (fixedPoints && fixedPoints->size() != mesh.NumPoints())
    throw InputError(std::string(who) + ": fixedPoints must have one flag per point");
  if (!AllFinite(mesh.Points.data(), static_cast<int>(mesh.Points.size())) ||
    !AllFinite(metric.Values.data(), static_cast<int>(metric.Values.size())))
    throw InputError(std::string(who) + ": non-finite point or metric values");
}
} // namespace

MeshImprovementResult ImproveMesh(SimplexMesh& mesh,
  const MetricField& metric,
  const std::vector<std::uint8_t>* fixedPoints,
  const MeshImprovementOptions& options)
{
  ValidateImprovementInput(mesh, metric, fixedPoints);
  MeshImprovementResult result;
  const std::size_t np = mesh.NumPoints();
  if (mesh.SimplexDim == 3)
  {
    std::vector<Eigen::Matrix3d> roots(np);
    for (std::size_t i = 0; i < np; ++i)
      roots[i] = SymmetricSqrt(UnpackSymmetric(metric.At(i)));
    TetMeshImprover(mesh, std::move(roots), fixedPoints, options).Run(result);
  }
  else if (mesh.AmbientDim == 2 || options.PlacePoint)
  {
    std::vector<Eigen::Matrix3d> roots(np, Eigen::Matrix3d::Zero());
    for (std::size_t i = 0; i < np; ++i)
      if (mesh.AmbientDim == 2)
        roots[i].topLeftCorner<2, 2>() = SymmetricSqrt(UnpackSymmetric2(metric.At(i)));
      else
        roots[i] = SymmetricSqrt(UnpackSymmetric(metric.At(i)));
    TriangleMeshImprover(mesh, std::move(roots), fixedPoints, options).Run(result);
  }
  else
  {
    result.Supported = false; // moving surface vertices needs the surface (PlacePoint)
    result.Moved.assign(np, 0);
  }
  return result;
}

} // namespace av
