// SPDX-License-Identifier: BSD-3-Clause
#include "FinalMeshImprovement.h"

#include "ElementLocator.h"
#include "FeatureSiteLookup.h"
#include "ValidDualMesh.h"

#include "MeshQuality.h"
#include "MetricAlgebra.h" // SurfaceMetricNormals
#include "MeshTopology.h"
#include "TriangleBvh.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

namespace av
{
namespace
{
/// Closest point of the surface `mesh` to x (through `bvh`): its triangle, barycentric
/// coordinates and unit normal. False when that triangle faces away from `hintCell`'s (x would
/// jump to another sheet of a thin part).
bool LocateOnSurface(const SimplexMesh& mesh,
  const TriangleBvh& bvh,
  std::int32_t hintCell,
  const double* x,
  std::int32_t& cell,
  double* lambda,
  Eigen::Vector3d& placed,
  Eigen::Vector3d& normal)
{
  auto corner = [&](std::int32_t c, int i)
  { return Eigen::Map<const Eigen::Vector3d>(mesh.Point(mesh.Cell(c)[i])); };
  auto unitNormal = [&](std::int32_t c)
  { return (corner(c, 1) - corner(c, 0)).cross(corner(c, 2) - corner(c, 0)).normalized(); };
  const Eigen::Vector3d p(x[0], x[1], x[2]);
  cell = -1;
  bvh.ClosestDistance2(p, &cell);
  if (cell < 0)
    return false;
  normal = unitNormal(cell);
  if (hintCell >= 0 && normal.dot(unitNormal(hintCell)) < 0.5)
    return false;
  const Eigen::Vector3d a = corner(cell, 0), b = corner(cell, 1), c = corner(cell, 2);
  placed = ClosestPointOnTriangle(p, a, b, c);
  // Barycentric coordinates of the closest point from the 2x2 normal equations.
  const Eigen::Vector3d e1 = b - a, e2 = c - a, r = placed - a;
  Eigen::Matrix2d g;
  g << e1.dot(e1), e1.dot(e2), e1.dot(e2), e2.dot(e2);
  const Eigen::Vector2d l = g.ldlt().solve(Eigen::Vector2d(e1.dot(r), e2.dot(r)));
  lambda[0] = std::max(0.0, 1.0 - l[0] - l[1]);
  lambda[1] = std::max(0.0, l[0]);
  lambda[2] = std::max(0.0, l[1]);
  lambda[3] = 0.0;
  const double sum = lambda[0] + lambda[1] + lambda[2];
  for (int i = 0; i < 3; ++i)
    lambda[i] /= sum;
  return true;
}

/// Site `v` (v == NumSites(): a new one) at barycentric `lambda` of `cell`.
void SetSite(const SimplexMesh& mesh,
  const Embedding& embedding,
  std::int32_t cell,
  const double* lambda,
  std::size_t v,
  SiteSet& sites)
{
  const int dim = embedding.Dim;
  if (v == sites.NumSites())
  {
    sites.CellIds.push_back(cell);
    sites.Coords.resize(sites.Coords.size() + static_cast<std::size_t>(dim));
    sites.Bary.resize(sites.Bary.size() + 4);
  }
  sites.CellIds[v] = cell;
  const std::int32_t* e = mesh.Cell(static_cast<std::size_t>(cell));
  for (int d = 0; d < dim; ++d)
  {
    double s = 0.0;
    for (int i = 0; i <= mesh.SimplexDim; ++i)
      s += lambda[i] * embedding.At(e[i])[d];
    sites.Coords[v * dim + d] = s;
  }
  for (int i = 0; i < 4; ++i)
    sites.Bary[v * 4 + i] = lambda[i];
}

/// The boundary triangles of a tet mesh (facets without a neighbor in `adjacency`), each
/// ordered so that its normal points into the domain, on the mesh's own points.
SimplexMesh BoundaryTriangles(const SimplexMesh& mesh, const std::vector<std::int32_t>& adjacency)
{
  // The facet opposite local vertex a, counterclockwise seen from a in a positive tet.
  constexpr int Facet[4][3] = { { 1, 3, 2 }, { 0, 2, 3 }, { 0, 3, 1 }, { 0, 1, 2 } };
  SimplexMesh surface;
  surface.AmbientDim = 3;
  surface.SimplexDim = 2;
  surface.Points = mesh.Points;
  for (std::size_t c = 0; c < mesh.NumCells(); ++c)
  {
    const std::int32_t* e = mesh.Cell(c);
    const bool negative = CellMeasure(mesh, c) < 0.0;
    for (int a = 0; a < 4; ++a)
      if (adjacency[4 * c + a] < 0)
      {
        const int j = negative ? 2 : 1, k = negative ? 1 : 2;
        surface.Cells.insert(surface.Cells.end(), { e[Facet[a][0]], e[Facet[a][j]], e[Facet[a][k]] });
      }
  }
  return surface;
}

/// The feature lines of a surface as segments, grouped into lines that end at corners and
/// junctions, for sliding feature-line vertices along them.
class FeatureLineProjector
{
public:
  FeatureLineProjector(const SimplexMesh& mesh, const SharpFeatures& f)
    : Lookup(f)
  {
    const std::size_t ne = f.NumEdges();
    std::vector<std::int32_t> parent(ne);
    for (std::size_t e = 0; e < ne; ++e)
      parent[e] = static_cast<std::int32_t>(e);
    auto find = [&](std::int32_t e)
    {
      while (parent[e] != e)
        e = parent[e] = parent[parent[e]];
      return e;
    };
    // Two edges meeting at a point of exactly two feature edges (not a corner) are one line.
    for (std::size_t p = 0; p + 1 < f.PointEdgeOffsets.size(); ++p)
      if (f.PointEdgeOffsets[p + 1] - f.PointEdgeOffsets[p] == 2 && !f.IsCorner[p])
      {
        const std::int32_t a = find(f.PointEdges[f.PointEdgeOffsets[p]]);
        const std::int32_t b = find(f.PointEdges[f.PointEdgeOffsets[p] + 1]);
        parent[a] = b;
      }
    Lines.resize(ne);
    for (std::size_t e = 0; e < ne; ++e)
    {
      Lines[static_cast<std::size_t>(find(static_cast<std::int32_t>(e)))].push_back(
        static_cast<std::int32_t>(e));
      A.emplace_back(mesh.Point(f.Edges[2 * e]));
      B.emplace_back(mesh.Point(f.Edges[2 * e + 1]));
      LineOf.push_back(find(static_cast<std::int32_t>(e)));
    }
  }

  /// The line holding site s (FeatureSiteLookup::EdgeOfSite), or -1.
  std::int32_t LineOfSite(const SimplexMesh& mesh, const SiteSet& sites, std::size_t s) const
  {
    const std::int32_t e = Lookup.EdgeOfSite(mesh, sites, s);
    return e < 0 ? -1 : LineOf[static_cast<std::size_t>(e)];
  }

  /// The closest point of line `line` to x and the unit tangent there.
  void Project(std::int32_t line, const Eigen::Vector3d& x, double* placed, double* tangent) const
  {
    double best = std::numeric_limits<double>::infinity();
    for (std::int32_t e : Lines[static_cast<std::size_t>(line)])
    {
      const Eigen::Vector3d c = Closest(static_cast<std::size_t>(e), x);
      const double d = (c - x).squaredNorm();
      if (d < best)
      {
        best = d;
        const Eigen::Vector3d t = (B[e] - A[e]).normalized();
        for (int k = 0; k < 3; ++k)
        {
          placed[k] = c[k];
          tangent[k] = t[k];
        }
      }
    }
  }

private:
  Eigen::Vector3d Closest(std::size_t e, const Eigen::Vector3d& x) const
  {
    const Eigen::Vector3d d = B[e] - A[e];
    const double t = std::clamp((x - A[e]).dot(d) / d.squaredNorm(), 0.0, 1.0);
    return A[e] + t * d;
  }

  std::vector<Eigen::Vector3d> A, B;
  std::vector<std::int32_t> LineOf;              // per segment
  FeatureSiteLookup Lookup;
  std::vector<std::vector<std::int32_t>> Lines;  // per line id (a root segment): its segments
};
} // namespace

MeshImprovementResult ImproveFinalMesh(const SimplexMesh& mesh,
  const Embedding& embedding,
  const std::vector<std::int32_t>& adjacency,
  const MetricField& metric,
  const std::vector<std::uint8_t>* fixedSites,
  const MeshImprovementOptions& options,
  DelaunayRepairResult& repaired,
  std::vector<std::uint8_t>& moved,
  const SharpFeatures* features)
{
  RestrictedDelaunayMesh& rdt = repaired.Delaunay;
  SiteSet& sites = repaired.Sites;
  SimplexMesh dual;
  dual.AmbientDim = rdt.AmbientDim;
  dual.SimplexDim = rdt.SimplexDim;
  dual.Points = rdt.Points;
  dual.Cells = rdt.Cells;
  const bool surface = dual.SimplexDim == 2 && dual.AmbientDim == 3 && mesh.SimplexDim == 2;
  if ((dual.AmbientDim != dual.SimplexDim && !surface) || dual.NumCells() == 0)
  {
    MeshImprovementResult none;
    none.Supported = dual.NumCells() == 0;
    return none;
  }
  const MetricField siteMetric = InterpolateMetricAtSites(mesh, metric, sites);
  const std::vector<Eigen::Vector3d> metricNormals =
    surface ? SurfaceMetricNormals(metric) : std::vector<Eigen::Vector3d>();
  std::vector<std::uint8_t> fixed(sites.NumSites(), 0);
  if (fixedSites)
    for (std::size_t i = 0; i < fixedSites->size() && i < fixed.size(); ++i)
      fixed[i] = (*fixedSites)[i];

  std::unique_ptr<TriangleBvh> bvh;
  if (surface)
    bvh = std::make_unique<TriangleBvh>(mesh);
  // Where x lands: the input element, barycentric coordinates and the point (on a surface the
  // closest point of the input surface, else x itself) and unit normal.
  auto locate = [&](std::int32_t near,
                  const double* x,
                  std::int32_t& cell,
                  double* lambda,
                  Eigen::Vector3d& placed,
                  Eigen::Vector3d& normal)
  {
    cell = sites.CellIds[near];
    lambda[3] = 0.0;
    if (surface)
      return LocateOnSurface(mesh, *bvh, cell, x, cell, lambda, placed, normal);
    placed = Eigen::Vector3d(x[0], x[1], dual.AmbientDim == 3 ? x[2] : 0.0);
    normal = Eigen::Vector3d::UnitZ();
    return LocateInMesh(mesh, adjacency, cell, x, lambda);
  };
  MeshImprovementOptions o = options;
  o.AcceptMove = [&](std::int32_t v, const double* x)
  {
    std::int32_t cell = -1;
    double lambda[4] = { 0, 0, 0, 0 };
    Eigen::Vector3d placed, normal;
    if (!locate(v, x, cell, lambda, placed, normal))
      return false;
    SetSite(mesh, embedding, cell, lambda, static_cast<std::size_t>(v), sites);
    if (static_cast<std::size_t>(v) < moved.size())
      moved[v] = 1;
    return true;
  };
  // Volumes: boundary vertices of curved patches move on the input's boundary surface.
  SimplexMesh inputBoundary;
  std::unique_ptr<TriangleBvh> boundaryBvh;
  if (dual.SimplexDim == 3 && mesh.SimplexDim == 3 && o.PlanarBoundary)
  {
    inputBoundary = BoundaryTriangles(mesh, adjacency);
    if (inputBoundary.NumCells() > 0)
    {
      boundaryBvh = std::make_unique<TriangleBvh>(inputBoundary);
      o.ProjectToBoundary =
        [&](std::int32_t, const double* x, const double* inward, double* placed, double* normal)
      {
        std::int32_t tri = -1;
        const Eigen::Vector3d p(x[0], x[1], x[2]);
        boundaryBvh->ClosestDistance2(p, &tri);
        if (tri < 0)
          return false;
        auto corner = [&](int i)
        {
          return Eigen::Map<const Eigen::Vector3d>(
            inputBoundary.Point(inputBoundary.Cell(static_cast<std::size_t>(tri))[i]));
        };
        const Eigen::Vector3d a = corner(0), b = corner(1), c = corner(2);
        // The same side of the surface (not the other sheet of a thin part).
        const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
        if (n.dot(Eigen::Map<const Eigen::Vector3d>(inward)) < 0.5)
          return false;
        Eigen::Map<Eigen::Vector3d> out(placed);
        out = ClosestPointOnTriangle(p, a, b, c);
        if (normal)
          Eigen::Map<Eigen::Vector3d>{ normal } = n;
        return true;
      };
    }
  }
  std::unique_ptr<FeatureLineProjector> lines; // outlive ImproveMesh: o's callbacks use them
  std::vector<std::int32_t> lineOf;
  // Triangles: where a moved or new vertex lands and its metric; tets: an inserted vertex's.
  o.PlacePoint = [&](std::int32_t near, const double* x, double* placed, double* normal, double* m)
  {
    std::int32_t cell = -1;
    double lambda[4] = { 0, 0, 0, 0 };
    Eigen::Vector3d p, n;
    if (!locate(near, x, cell, lambda, p, n))
      return false;
    for (int d = 0; d < 3; ++d)
    {
      placed[d] = p[d];
      normal[d] = n[d];
    }
    InterpolateMetricInCell(mesh, metric, metricNormals, cell, lambda, m);
    return true;
  };
  // A split's or an insertion's vertex becomes an inserted site (after the repair's).
  o.AddPoint = [&](std::int32_t v, std::int32_t near, const double* x)
  {
    std::int32_t cell = -1;
    double lambda[4] = { 0, 0, 0, 0 };
    Eigen::Vector3d placed, normal;
    if (static_cast<std::size_t>(v) != sites.NumSites() ||
      !locate(near, x, cell, lambda, placed, normal))
      return false;
    SetSite(mesh, embedding, cell, lambda, static_cast<std::size_t>(v), sites);
    ++repaired.NumInserted;
    return true;
  };
  if (dual.SimplexDim == 2)
  {
    // Feature-line sites on a line of the input slide along it (between its corners).
    if (surface && features && features->NumEdges() > 0)
    {
      lines = std::make_unique<FeatureLineProjector>(mesh, *features);
      lineOf.assign(sites.NumSites(), -1);
      for (std::size_t s = 0; s < fixed.size() && s < sites.NumSites(); ++s)
        if (fixed[s] == FeatureLinePoint)
          lineOf[s] = lines->LineOfSite(mesh, sites, s);
      o.ProjectToFeatureLine = [&](std::int32_t v, const double* x, double* placed, double* tangent)
      {
        if (v < 0 || static_cast<std::size_t>(v) >= lineOf.size() || lineOf[v] < 0)
          return false;
        lines->Project(lineOf[v], Eigen::Map<const Eigen::Vector3d>(x), placed, tangent);
        return true;
      };
    }
  }
  MeshImprovementResult result = ImproveMesh(dual, siteMetric, &fixed, o);
  rdt.Points = std::move(dual.Points);
  rdt.Cells = std::move(dual.Cells);
  RecountFinalDual(mesh, rdt, sites);
  return result;
}

} // namespace av
