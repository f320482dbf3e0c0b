// SPDX-License-Identifier: BSD-3-Clause
// The whole surface pipeline (curvature metric, 8D embedding, particles, RVD, RDT with its
// repair) on a closed torus, an open torus tube, a torus patch and Cyclide1: the dual triangle
// mesh has the input's Euler characteristic and boundary loops, no edge of more than two
// triangles, no triangle flipped against the input surface, no self-intersection, stays within
// 0.5 % of the diagonal of the input (on the patch, only once its boundary's notches are
// closed); the sampler's energy never rises and every RVD piece is nearest to its own site in
// the embedding.
#include "AnisoTestChecks.h"
#include "EmbeddingSolver.h"
#include "MeshingPipeline.h"
#include "ParticleSampler.h"
#include "SurfaceCurvatureMetric.h"
#include "SurfaceFidelity.h"
#include "SurfaceGenerators.h"

#include <Eigen/Dense>

#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace
{
/// Per site (dual vertex), the unit normal of the input triangle that holds it.
std::vector<double> SiteNormals(const av::SimplexMesh& mesh, const av::SiteSet& sites)
{
  std::vector<double> n(3 * sites.NumSites());
  for (std::size_t i = 0; i < sites.NumSites(); ++i)
  {
    const std::int32_t* t = mesh.Cell(static_cast<std::size_t>(sites.CellIds[i]));
    const Eigen::Map<const Eigen::Vector3d> a(mesh.Point(t[0])), b(mesh.Point(t[1])),
      c(mesh.Point(t[2]));
    Eigen::Map<Eigen::Vector3d>(n.data() + 3 * i) = (b - a).cross(c - a).normalized();
  }
  return n;
}

/// Vertices of every RVD piece are not closer to another site than to their own (R^Dim).
std::size_t FartherThanAnotherSite(const av::RestrictedVoronoiDiagram& r, const av::SiteSet& s)
{
  std::size_t bad = 0;
  const int dim = r.Dim;
  for (std::size_t p = 0; p < r.NumPieces(); ++p)
  {
    for (std::int64_t v = r.PieceVertexOffsets[p]; v < r.PieceVertexOffsets[p + 1]; ++v)
    {
      const Eigen::Map<const Eigen::VectorXd> x(r.EmbeddedPoints.data() + v * dim, dim);
      const double own =
        (x - Eigen::Map<const Eigen::VectorXd>(s.At(r.PieceSite[p]), dim)).squaredNorm();
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t q = 0; q < s.NumSites(); ++q)
        best = std::min(best, (x - Eigen::Map<const Eigen::VectorXd>(s.At(q), dim)).squaredNorm());
      bad += own > best + 1e-9 * (1.0 + best) ? 1 : 0;
    }
  }
  return bad;
}

void CheckRemeshing(const char* name,
  const av::SimplexMesh& mesh,
  std::size_t sites,
  long long euler,
  std::size_t loops)
{
  const av::MetricField metric = av::SurfaceCurvatureMetric(mesh, {}).Metric;
  av::EmbeddingOptions eo;
  eo.Iterations = 30;
  const av::Embedding embedded = av::ComputeEmbedding(mesh, metric, eo).Embedded;
  av::ParticleSamplerOptions so;
  so.NumSites = sites;
  const av::ParticleSamplerResult sampled = av::SampleParticles(mesh, embedded, so);
  for (std::size_t k = 1; k < sampled.Energy.size(); ++k)
    AV_CHECK_MSG(sampled.Energy[k] <= sampled.Energy[k - 1] * (1 + 1e-12) + 1e-300,
      name << ": sampler energy rose at iteration " << k);
  AV_CHECK(sampled.Energy.back() < sampled.Energy.front());

  const av::MeshingPipelineResult r =
    av::RunMeshingPipeline(mesh, embedded, sampled.Sites, av::MeshingPipelineOptions());
  const av::RestrictedDelaunayMesh& rdt = r.Repaired.Delaunay;
  av::SimplexMesh dual;
  dual.AmbientDim = 3;
  dual.SimplexDim = 2;
  dual.Points = rdt.Points;
  dual.Cells = rdt.Cells;
  const av::SurfaceTopology topo = av::ComputeSurfaceTopology(dual);
  const std::size_t flipped = av::CountFlippedTriangles(dual, SiteNormals(mesh, r.Repaired.Sites));
  const std::size_t crossings = av::CountSelfIntersections(dual);
  const av::HausdorffResult h = av::SampledHausdorffDistance(dual, mesh);
  std::cout << name << ": " << dual.NumCells() << " triangles, chi " << topo.Euler << ", loops "
            << topo.BoundaryLoops << ", nonmanifold edges " << topo.NonManifoldEdges << ", flipped "
            << flipped << " (RDT inverted before repair " << r.Repaired.InitialInverted
            << ", after " << rdt.NumInverted << "), crossings " << crossings << ", Hausdorff "
            << h.MaxPercent << " %, boundary notches " << r.BoundaryNotches.Notches << " (closed "
            << r.BoundaryNotches.Closed << ")" << std::endl;
  AV_CHECK_MSG(topo.Euler == euler, name << ": chi " << topo.Euler << ", expected " << euler);
  AV_CHECK_MSG(topo.BoundaryLoops == loops, name << ": " << topo.BoundaryLoops << " loops");
  AV_CHECK(topo.Components == 1 && topo.NonManifoldEdges == 0);
  AV_CHECK(rdt.NumUnusedSites == 0);
  AV_CHECK_MSG(flipped == 0, name << ": " << flipped << " flipped triangles");
  AV_CHECK(rdt.NumInverted == 0);
  AV_CHECK_MSG(crossings == 0, name << ": " << crossings << " self-intersections");
  AV_CHECK_MSG(h.MaxPercent < 0.5, name << ": Hausdorff " << h.MaxPercent << " % of the diagonal");

  av::RestrictedVoronoiOptions vo;
  vo.KeepEmbeddedPoints = true; // FartherThanAnotherSite reads them
  const av::RestrictedVoronoiDiagram geometry =
    av::ComputeRestrictedVoronoi(mesh, embedded, r.Repaired.Sites, vo);
  AV_CHECK_MSG(FartherThanAnotherSite(geometry, r.Repaired.Sites) == 0,
    name << ": RVD vertices nearer to another site");
}
} // namespace

int TestSurfaceRemeshing(int, char*[])
{
  CheckRemeshing("torus", av::MakeTorusSurface(3.0, 1.0, 90, 45), 600, 0, 0);
  CheckRemeshing("open tube", av::MakeTorusSurface(3.0, 1.0, 60, 45, 0.5), 500, 0, 2);
  // A patch with four corners: its dual's boundary cut into the surface at 2 sites just inside
  // the rim (Hausdorff 1.59 % of the diagonal) until the notches were closed (0.20 %).
  CheckRemeshing("torus patch", av::MakeTorusSurface(3.0, 1.0, 90, 45, 0.25, 0.5), 600, 1, 1);
  CheckRemeshing("cyclide1", av::MakeDupinCyclideSurface(2.0, 1.0, 1.5, 120, 90), 2000, 0, 0);
  return AV_TEST_RESULT();
}
