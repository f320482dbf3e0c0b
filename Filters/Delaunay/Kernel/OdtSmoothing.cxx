// SPDX-License-Identifier: BSD-3-Clause
// ODT smoothing of restricted Delaunay sites in the embedding.
#include "OdtSmoothing.h"

#include "SiteWalk.h"

#include <Eigen/Dense>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace av
{

namespace
{
void ValidateOdtInput(const SimplexMesh& mesh, const Embedding& embedding, const SiteSet& sites,
  const RestrictedVoronoiDiagram& rvd, const RestrictedDelaunayMesh& rdt,
  const OdtSmoothingOptions& options)
{
  auto fail = [](const std::string& m) { throw InputError("SmoothSitesOdt: " + m); };
  ValidateSiteMoveInput("SmoothSitesOdt", mesh, embedding, sites, rdt);
  const std::size_t ns = sites.NumSites();
  if (!(options.StepFraction >= 0.0) || !std::isfinite(options.StepFraction))
    fail("StepFraction must be finite and >= 0");
  if (options.Iterations < 0)
    fail("Iterations must be >= 0");
  if (rdt.SimplexDim != mesh.SimplexDim)
    fail("the Delaunay mesh does not match the input mesh's simplex dimension");
  for (std::int32_t id : rvd.BoundaryDualFaces)
    if (id < 0 || static_cast<std::size_t>(id) >= ns)
      fail("the Voronoi diagram refers to a site id out of range (pass its sites)");
  if (options.ElementAdjacency &&
    options.ElementAdjacency->size() != mesh.NumCells() * static_cast<std::size_t>(rdt.SimplexDim + 1))
    fail("ElementAdjacency does not match the mesh (pass ComputeElementAdjacency of this mesh)");
  if (options.FixedSites && options.FixedSites->size() != ns)
    fail("FixedSites must have one flag per site");
}

// Circumcenter (Dim values) and measure (times k!, last value; 0 when degenerate) of every
// simplex of `rdt` with the positions of `sites`, in parallel.
void ComputeCircumcenters(const RestrictedDelaunayMesh& rdt, const SiteSet& sites, int dim,
  std::vector<double>& center)
{
  const int k = rdt.SimplexDim, nv = k + 1;
  const std::size_t ncell = rdt.Cells.size() / static_cast<std::size_t>(nv);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, ncell, 512),
    [&](const tbb::blocked_range<std::size_t>& range)
    {
      for (std::size_t c = range.begin(); c != range.end(); ++c)
      {
        const std::int32_t* id = rdt.Cells.data() + nv * c;
        const double* p0 = sites.At(id[0]);
        // Gram matrix of the edges from p0 in a fixed 3x3 (identity pads triangles).
        Eigen::Matrix3d g = Eigen::Matrix3d::Identity();
        for (int i = 0; i < k; ++i)
          for (int j = 0; j <= i; ++j)
          {
            const double* pi = sites.At(id[i + 1]);
            const double* pj = sites.At(id[j + 1]);
            double dot = 0.0;
            for (int q = 0; q < dim; ++q)
              dot += (pi[q] - p0[q]) * (pj[q] - p0[q]);
            g(i, j) = g(j, i) = dot;
          }
        const double det = g.determinant();
        double* out = center.data() + c * (dim + 1);
        out[dim] = 0.0;
        if (!(det > 0.0))
          continue;
        // Circumcenter p0 + E l with 2 G l = diag(G); measure sqrt(det G) / k!.
        const Eigen::Vector3d l = g.ldlt().solve(0.5 * Eigen::Vector3d(g(0, 0), g(1, 1), k == 3 ? g(2, 2) : 0.0));
        if (!l.allFinite())
          continue;
        for (int q = 0; q < dim; ++q)
        {
          double v = p0[q];
          for (int j = 0; j < k; ++j)
            v += l[j] * (sites.At(id[j + 1])[q] - p0[q]);
          out[q] = v;
        }
        out[dim] = std::sqrt(det);
      }
    });
}

// Measure-weighted sums of the circumcenters at each site (serial: deterministic sums).
void ScatterCircumcenters(const RestrictedDelaunayMesh& rdt, const std::vector<double>& center,
  int dim, std::vector<double>& acc, std::vector<double>& weight)
{
  const int nv = rdt.SimplexDim + 1;
  const std::size_t ncell = rdt.Cells.size() / static_cast<std::size_t>(nv);
  std::fill(acc.begin(), acc.end(), 0.0);
  std::fill(weight.begin(), weight.end(), 0.0);
  for (std::size_t c = 0; c < ncell; ++c)
  {
    const double* out = center.data() + c * (dim + 1);
    const double vol = out[dim];
    if (!(vol > 0.0))
      continue;
    const std::int32_t* id = rdt.Cells.data() + nv * c;
    for (int a = 0; a < nv; ++a)
    {
      const std::size_t s = static_cast<std::size_t>(id[a]);
      weight[s] += vol;
      for (int q = 0; q < dim; ++q)
        acc[s * dim + q] += vol * out[q];
    }
  }
}
} // namespace

OdtSmoothingResult SmoothSitesOdt(const SimplexMesh& mesh, const Embedding& embedding,
  const SiteSet& sites, const RestrictedVoronoiDiagram& rvd, const RestrictedDelaunayMesh& rdt,
  const OdtSmoothingOptions& options)
{
  ValidateOdtInput(mesh, embedding, sites, rvd, rdt, options);
  const std::size_t ns = sites.NumSites();
  const int dim = embedding.Dim;
  const int nv = rdt.SimplexDim + 1;

  OdtSmoothingResult r;
  r.Sites = sites;
  std::vector<char> fixed(ns, 0);
  for (std::int32_t id : rvd.BoundaryDualFaces)
    fixed[static_cast<std::size_t>(id)] = 1;
  if (options.FixedSites)
  {
    for (std::size_t s = 0; s < ns; ++s)
      fixed[s] = fixed[s] || (*options.FixedSites)[s] != 0;
  }

  std::vector<std::int32_t> ownAdjacency;
  if (!options.ElementAdjacency)
    ownAdjacency = ComputeElementAdjacency(mesh);
  const std::vector<std::int32_t>& adj = options.ElementAdjacency ? *options.ElementAdjacency : ownAdjacency;
  std::vector<double> acc(ns * static_cast<std::size_t>(dim), 0.0);
  std::vector<double> weight(ns, 0.0);
  const std::size_t ncell = rdt.Cells.size() / static_cast<std::size_t>(nv);
  std::vector<double> center(ncell * (static_cast<std::size_t>(dim) + 1));
  std::vector<double> d(static_cast<std::size_t>(dim));
  double total = 0.0;
  // Later iterations keep the connectivity of `rdt` and use the moved positions.
  for (int iteration = 0; iteration < options.Iterations; ++iteration)
  {
    r.NumMovedSites = 0;
    r.NumFixedSites = 0;
    ComputeCircumcenters(rdt, r.Sites, dim, center);
    ScatterCircumcenters(rdt, center, dim, acc, weight);
    total = 0.0;
    for (std::size_t s = 0; s < ns; ++s)
    {
      if (!(weight[s] > 0.0))
        continue;
      for (int q = 0; q < dim; ++q)
        d[q] = options.StepFraction * (acc[s * dim + q] / weight[s] - r.Sites.At(s)[q]);
      if (fixed[s])
      {
        // The star of a site whose cell meets the boundary is one-sided: its ODT position is
        // pulled inwards (sliding boundary sites within the boundary measured worse).
        ++r.NumFixedSites;
        continue;
      }
      double norm2 = 0.0;
      for (double v : d)
        norm2 += v * v;
      if (!(norm2 > 0.0) || !std::isfinite(norm2))
        continue;
      total += std::sqrt(norm2);
      WalkSiteOnMesh(mesh, embedding, adj, r.Sites, s, d.data());
      ++r.NumMovedSites;
    }
  }
  r.MeanMove = r.NumMovedSites > 0 ? total / static_cast<double>(r.NumMovedSites) : 0.0;
  return r;
}

} // namespace av
