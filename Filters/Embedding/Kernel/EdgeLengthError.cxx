// SPDX-License-Identifier: BSD-3-Clause
#include "EdgeLengthError.h"

#include "MetricAlgebra.h"
#include "MeshTopology.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace av
{

std::vector<Eigen::Matrix3d> VertexMetricRoots(const MetricField& metric, int ambientDim)
{
  std::vector<Eigen::Matrix3d> a(metric.NumPoints());
  tbb::parallel_for(std::size_t(0), a.size(), [&](std::size_t i) {
    if (ambientDim == 2)
    {
      a[i].setZero();
      a[i].topLeftCorner<2, 2>() = SymmetricSqrt(UnpackSymmetric2(metric.At(i)));
    }
    else
    {
      a[i] = SymmetricSqrt(UnpackSymmetric(metric.At(i)));
    }
  });
  return a;
}

EdgeLengthErrorEvaluator::EdgeLengthErrorEvaluator(const SimplexMesh& mesh, const MetricField& metric)
  : Mesh(&mesh)
{
  const std::size_t np = mesh.NumPoints();
  if (metric.Values.size() != 6 * np)
  {
    throw InputError("edge length error: metric has " + std::to_string(metric.Values.size()) +
      " values, expected 6 per point (" + std::to_string(6 * np) + ")");
  }
  const std::vector<Eigen::Matrix3d> a = VertexMetricRoots(metric, mesh.AmbientDim);
  const bool surface = mesh.AmbientDim == 3 && mesh.SimplexDim == 2;
  const std::vector<Eigen::Vector3d> normals =
    surface ? SurfaceMetricNormals(metric) : std::vector<Eigen::Vector3d>();
  this->Edges = UniqueEdges(mesh);
  const std::size_t ne = this->Edges.size() / 2;
  this->MetricLength.resize(ne);
  tbb::parallel_for(std::size_t(0), ne, [&](std::size_t e) {
    const std::int32_t p = this->Edges[2 * e], q = this->Edges[2 * e + 1];
    this->MetricLength[e] = std::sqrt(surface ? SurfaceMetricEdgeLength2(mesh, a, normals, p, q)
                                              : MetricEdgeLength2(mesh, a, p, q));
  });
  for (std::size_t e = 0; e < ne; ++e)
  {
    if (!(this->MetricLength[e] > 0.0) || !std::isfinite(this->MetricLength[e]))
    {
      throw InputError("edge length error: edge (" + std::to_string(this->Edges[2 * e]) + ", " +
        std::to_string(this->Edges[2 * e + 1]) + ") has zero or invalid metric length");
    }
  }
}

EdgeLengthErrorResult EdgeLengthErrorEvaluator::Evaluate(
  const Embedding& emb, bool perEdge, bool perCell) const
{
  const SimplexMesh& mesh = *this->Mesh;
  if (emb.NumPoints() != mesh.NumPoints() || emb.Dim < mesh.AmbientDim)
  {
    throw InputError("edge length error: embedding has " + std::to_string(emb.NumPoints()) +
      " points of dimension " + std::to_string(emb.Dim) + ", mesh has " +
      std::to_string(mesh.NumPoints()) + " points");
  }
  const std::size_t ne = this->MetricLength.size();
  const int dim = emb.Dim;
  std::vector<double> err(ne);
  using Acc = std::pair<double, double>;
  // Deterministic reduce: the range splits into the same 4096-edge chunks, summed in the same
  // order, whatever the thread count and scheduling (a plain parallel_reduce made L_avg differ
  // in the last bits between identical runs).
  const Acc total = tbb::parallel_deterministic_reduce(
    tbb::blocked_range<std::size_t>(0, ne, 4096), Acc(0.0, 0.0),
    [&](const tbb::blocked_range<std::size_t>& r, Acc acc) {
      for (std::size_t e = r.begin(); e != r.end(); ++e)
      {
        const double* pa = emb.At(this->Edges[2 * e]);
        const double* pb = emb.At(this->Edges[2 * e + 1]);
        double s = 0.0;
        for (int k = 0; k < dim; ++k)
        {
          s += (pb[k] - pa[k]) * (pb[k] - pa[k]);
        }
        const double l = this->MetricLength[e];
        const double rel = std::abs(std::sqrt(s) - l) / l;
        err[e] = rel;
        acc.first += rel;
        acc.second = std::max(acc.second, rel);
      }
      return acc;
    },
    [](Acc x, Acc y) { return Acc(x.first + y.first, std::max(x.second, y.second)); });
  EdgeLengthErrorResult res;
  res.NumEdges = ne;
  res.AveragePercent = ne ? 100.0 * total.first / static_cast<double>(ne) : 0.0;
  res.MaxPercent = 100.0 * total.second;
  if (perEdge)
  {
    res.Edges = this->Edges;
    res.EdgePercent.resize(ne);
    for (std::size_t e = 0; e < ne; ++e)
    {
      res.EdgePercent[e] = 100.0 * err[e];
    }
  }
  if (perCell)
  {
    // Edges are sorted by (a, b): find each cell edge by binary search.
    const int nv = mesh.VerticesPerCell();
    res.CellMaxPercent.assign(mesh.NumCells(), 0.0);
    tbb::parallel_for(std::size_t(0), mesh.NumCells(), [&](std::size_t c) {
      const std::int32_t* cell = mesh.Cell(c);
      double mx = 0.0;
      for (int i = 0; i < nv; ++i)
      {
        for (int j = i + 1; j < nv; ++j)
        {
          const std::uint64_t key = (static_cast<std::uint64_t>(std::min(cell[i], cell[j])) << 32) |
            static_cast<std::uint32_t>(std::max(cell[i], cell[j]));
          std::size_t lo = 0, hi = ne;
          while (lo < hi)
          {
            const std::size_t mid = (lo + hi) / 2;
            const std::uint64_t k = (static_cast<std::uint64_t>(this->Edges[2 * mid]) << 32) |
              static_cast<std::uint32_t>(this->Edges[2 * mid + 1]);
            if (k < key)
            {
              lo = mid + 1;
            }
            else
            {
              hi = mid;
            }
          }
          if (lo < ne)
          {
            mx = std::max(mx, err[lo]);
          }
        }
      }
      res.CellMaxPercent[c] = 100.0 * mx;
    });
  }
  return res;
}

EdgeLengthErrorResult ComputeEdgeLengthError(const SimplexMesh& mesh, const MetricField& metric,
  const Embedding& embedding, bool perEdge, bool perCell)
{
  return EdgeLengthErrorEvaluator(mesh, metric).Evaluate(embedding, perEdge, perCell);
}

} // namespace av
