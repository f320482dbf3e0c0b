// SPDX-License-Identifier: BSD-3-Clause
#include "FinalMeshImprovement.h"

#include "ElementLocator.h"
#include "ValidDualMesh.h"

#include "MeshQuality.h"
#include "MeshTopology.h"

#include <Eigen/Dense>

#include <cmath>

namespace av
{

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
    if (!LocateInMesh(mesh, adjacency, cell, x, lambda))
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
  RecountFinalDual(rdt, sites);
  return result;
}

} // namespace av
