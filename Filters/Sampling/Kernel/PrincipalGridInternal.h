// SPDX-License-Identifier: BSD-3-Clause
// PrincipalGridInternal: what the sampler's two neighbor grids share: the three principal axes of
// a point cloud in R^D, the points' bounds on them and the grid's cell side.
#ifndef av_PrincipalGridInternal_h
#define av_PrincipalGridInternal_h

#include "SamplerDimensions.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cstddef>

namespace av
{
namespace sampling
{

/**
 * Side of the cells of a uniform grid over the box [lo, hi] (3 projected coordinates) for
 * searches of radius r among `count` points: a bit over r, so neighbors are in adjacent
 * cells despite round-off, coarsened while the grid would have more than 4 count + 64 cells
 * (far-apart clusters: still exact). Writes the cell counts per axis.
 */
inline double GridCellSide(const double lo[3],
  const double hi[3],
  double r,
  std::size_t count,
  long long cellsPerAxis[3])
{
  double extent = 0.0;
  for (int a = 0; a < 3; ++a)
    extent = std::max(extent, hi[a] - lo[a]);
  double h = std::max(r * (1.0 + 1e-6), 1e-12 * extent + 1e-300);
  for (;;)
  {
    long long cells = 1;
    for (int a = 0; a < 3; ++a)
    {
      cellsPerAxis[a] = static_cast<long long>((hi[a] - lo[a]) / h) + 1;
      cells *= cellsPerAxis[a];
    }
    if (cells <= 4 * static_cast<long long>(count) + 64)
      return h;
    h *= 1.5;
  }
}

/**
 * The three principal axes (rows; unit eigenvectors of the covariance, largest first; the
 * coordinate axes if the eigen solver fails; zero rows beyond dim) of the `count` points
 * at(0) .. at(count - 1) in R^dim. Serial: deterministic. Cov is the covariance matrix type.
 * Projecting onto orthonormal axes only shortens distances, so a grid on these coordinates
 * misses no pair; the points live on a 2- or 3-manifold, so the coordinates separate them well.
 */
template <int D, class Cov, class PointAt>
AxesMatrix<D> PrincipalAxes(std::size_t count, int dim, PointAt at)
{
  using Vec = PointVector<D>;
  Vec mean = Vec::Zero(dim);
  for (std::size_t i = 0; i < count; ++i)
    mean += Eigen::Map<const Vec>(at(i), dim);
  mean /= static_cast<double>(count);
  Cov cov = Cov::Zero(dim, dim);
  for (std::size_t i = 0; i < count; ++i)
  {
    const Vec c = Eigen::Map<const Vec>(at(i), dim) - mean;
    cov.noalias() += c * c.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Cov> eig(cov);
  AxesMatrix<D> axes = AxesMatrix<D>::Zero(3, dim);
  const int kp = std::min(3, dim);
  for (int a = 0; a < kp; ++a)
    if (eig.info() == Eigen::Success)
      axes.row(a) = eig.eigenvectors().col(dim - 1 - a).transpose().normalized();
    else
      axes(a, a) = 1.0;
  return axes;
}

/// Bounds [lo, hi] of the points' principal coordinates; with `proj`, also stores them (3 per
/// point).
template <int D, class PointAt>
void ProjectedBounds(const AxesMatrix<D>& axes,
  std::size_t count,
  int dim,
  PointAt at,
  double lo[3],
  double hi[3],
  double* proj = nullptr)
{
  for (std::size_t i = 0; i < count; ++i)
  {
    const Eigen::Vector3d y = axes * Eigen::Map<const PointVector<D>>(at(i), dim);
    for (int a = 0; a < 3; ++a)
    {
      if (proj)
        proj[3 * i + a] = y[a];
      lo[a] = i == 0 ? y[a] : std::min(lo[a], y[a]);
      hi[a] = i == 0 ? y[a] : std::max(hi[a], y[a]);
    }
  }
}

} // namespace sampling
} // namespace av

#endif
