// SPDX-License-Identifier: BSD-3-Clause
#include "ElementLocator.h"

#include <Eigen/Dense>

#include <algorithm>

namespace av
{
namespace
{

/// Barycentric coordinates of x in cell c of a volume (or flat 2D) mesh, k + 1 values.
void Barycentric(const SimplexMesh& mesh, std::size_t c, const double* x, double* lambda)
{
  const int k = mesh.SimplexDim;
  const std::int32_t* v = mesh.Cell(c);
  Eigen::Matrix3d a = Eigen::Matrix3d::Identity();
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  for (int d = 0; d < k; ++d)
  {
    for (int j = 0; j < k; ++j)
      a(d, j) = mesh.Point(v[j + 1])[d] - mesh.Point(v[0])[d];
    r[d] = x[d] - mesh.Point(v[0])[d];
  }
  const Eigen::Vector3d l = a.partialPivLu().solve(r);
  lambda[0] = 1.0;
  for (int j = 0; j < k; ++j)
  {
    lambda[j + 1] = l[j];
    lambda[0] -= l[j];
  }
}

} // namespace

bool LocateInMesh(const SimplexMesh& mesh, const std::vector<std::int32_t>& adjacency,
  std::int32_t& cell, const double* x, double* lambda)
{
  const int nv = mesh.SimplexDim + 1;
  for (int step = 0; step < 512; ++step)
  {
    Barycentric(mesh, static_cast<std::size_t>(cell), x, lambda);
    int worst = 0;
    for (int i = 1; i < nv; ++i)
      if (lambda[i] < lambda[worst])
        worst = i;
    if (lambda[worst] >= -1e-12)
    {
      double sum = 0.0;
      for (int i = 0; i < nv; ++i)
        sum += (lambda[i] = std::max(0.0, lambda[i]));
      for (int i = 0; i < nv; ++i)
        lambda[i] /= sum;
      return true;
    }
    const std::int32_t next = adjacency[static_cast<std::size_t>(cell) * nv + worst];
    if (next < 0)
      return false;
    cell = next;
  }
  return false;
}

} // namespace av
