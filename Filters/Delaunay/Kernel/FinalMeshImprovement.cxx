// SPDX-License-Identifier: BSD-3-Clause
#include "FinalMeshImprovement.h"

#include "MeshQuality.h"
#include "MeshTopology.h"

#include <Eigen/Dense>

#include <cmath>

namespace av
{
namespace
{
// Relative volume below which a simplex counts as flat (the value of ComputeRestrictedDelaunay).
constexpr double kFlatTolerance = 1e-7;

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

/// Walks from `cell` towards x across the facet of the most negative coordinate. False when the
/// walk leaves the domain or takes too long.
bool Locate(const SimplexMesh& mesh,
  const std::vector<std::int32_t>& adjacency,
  std::int32_t& cell,
  const double* x,
  double* lambda)
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

void RecountInverted(RestrictedDelaunayMesh& rdt, const SiteSet& sites)
{
  SimplexMesh dual;
  dual.AmbientDim = rdt.AmbientDim;
  dual.SimplexDim = rdt.SimplexDim;
  dual.Points = rdt.Points;
  dual.Cells = rdt.Cells;
  const int k = rdt.SimplexDim;
  const double factorial = k == 3 ? 6.0 : 2.0;
  rdt.Inverted.assign(dual.NumCells(), 0);
  rdt.CellElement.assign(dual.NumCells(), 0);
  rdt.NumInverted = 0;
  for (std::size_t c = 0; c < dual.NumCells(); ++c)
  {
    const std::int32_t* v = dual.Cell(c);
    double l2 = 0.0;
    for (int i = 0; i <= k; ++i)
      for (int j = i + 1; j <= k; ++j)
        for (int d = 0; d < dual.AmbientDim; ++d)
        {
          const double e = dual.Point(v[i])[d] - dual.Point(v[j])[d];
          l2 += e * e;
        }
    const double measure = factorial * CellMeasure(dual, c);
    rdt.Inverted[c] = measure > kFlatTolerance * std::pow(l2, 0.5 * k) ? 0 : 1;
    rdt.NumInverted += rdt.Inverted[c];
    rdt.CellElement[c] = sites.CellIds[v[0]];
  }
}
} // namespace

MeshImprovementResult ImproveFinalMesh(const SimplexMesh& mesh,
  const Embedding& embedding,
  const std::vector<std::int32_t>& adjacency,
  const MetricField& metric,
  const std::vector<std::uint8_t>* fixedSites,
  const MeshImprovementOptions& options,
  DelaunayRepairResult& repaired,
  std::vector<std::uint8_t>& moved)
{
  RestrictedDelaunayMesh& rdt = repaired.Delaunay;
  SiteSet& sites = repaired.Sites;
  SimplexMesh dual;
  dual.AmbientDim = rdt.AmbientDim;
  dual.SimplexDim = rdt.SimplexDim;
  dual.Points = rdt.Points;
  dual.Cells = rdt.Cells;
  if (dual.AmbientDim != dual.SimplexDim || dual.NumCells() == 0)
  {
    MeshImprovementResult none;
    none.Supported = dual.NumCells() == 0;
    return none;
  }
  const MetricField siteMetric = InterpolateMetricAtSites(mesh, metric, sites);
  std::vector<std::uint8_t> fixed(sites.NumSites(), 0);
  if (fixedSites)
    for (std::size_t i = 0; i < fixedSites->size() && i < fixed.size(); ++i)
      fixed[i] = (*fixedSites)[i];

  const int nv = mesh.SimplexDim + 1;
  const int dim = embedding.Dim;
  MeshImprovementOptions o = options;
  o.AcceptMove = [&](std::int32_t v, const double* x)
  {
    std::int32_t cell = sites.CellIds[v];
    double lambda[4] = { 0, 0, 0, 0 };
    if (!Locate(mesh, adjacency, cell, x, lambda))
      return false;
    sites.CellIds[v] = cell;
    const std::int32_t* e = mesh.Cell(static_cast<std::size_t>(cell));
    for (int d = 0; d < dim; ++d)
    {
      double s = 0.0;
      for (int i = 0; i < nv; ++i)
        s += lambda[i] * embedding.At(e[i])[d];
      sites.Coords[static_cast<std::size_t>(v) * dim + d] = s;
    }
    for (int i = 0; i < 4; ++i)
      sites.Bary[static_cast<std::size_t>(v) * 4 + i] = lambda[i];
    if (static_cast<std::size_t>(v) < moved.size())
      moved[v] = 1;
    return true;
  };
  MeshImprovementResult result = ImproveMesh(dual, siteMetric, &fixed, o);
  rdt.Points = std::move(dual.Points);
  rdt.Cells = std::move(dual.Cells);
  RecountInverted(rdt, sites);
  return result;
}

} // namespace av
