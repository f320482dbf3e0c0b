// SPDX-License-Identifier: BSD-3-Clause
// Input validation of the RVD: mesh, embedding and sites (ValidateRestrictedVoronoiInput),
// degenerate embedded elements, the element adjacency and range options.
#include "RestrictedVoronoiValidation.h"

#include "RestrictedVoronoiPrimitives.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace av
{
namespace rvd
{

void CheckDegenerateElements(const SimplexMesh& mesh, const Embedding& embedding,
  const std::int32_t* list, std::size_t n)
{
  const int K = mesh.SimplexDim, nv = K + 1;
  std::vector<char> bad(n, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i)
    {
      const std::size_t c = list ? static_cast<std::size_t>(list[i]) : i;
      const double* v[4];
      const std::int32_t* cell = mesh.Cell(c);
      double h2 = 0.0;
      for (int a = 0; a < nv; ++a)
        v[a] = embedding.At(cell[a]);
      const bool d8 = embedding.Dim == 8; // the usual embedding: compile-time loops
      for (int a = 0; a < nv; ++a)
        for (int b = a + 1; b < nv; ++b)
          h2 = std::max(h2, d8 ? Dist2<8>(v[a], v[b], 8) : Dist2<-1>(v[a], v[b], embedding.Dim));
      const double m = d8 ? SimplexMeasureT<8>(v, K, 8) : SimplexMeasure(v, K, embedding.Dim);
      bad[i] = !(m > 1e-12 * std::pow(std::sqrt(h2), K));
    }
  });
  for (std::size_t i = 0; i < n; ++i)
    if (bad[i])
      throw InputError("RestrictedVoronoi: embedded element " +
        std::to_string(list ? static_cast<std::size_t>(list[i]) : i) +
        " is degenerate (zero area/volume)");
}

const std::vector<std::int32_t>& ElementAdjacencyFor(const SimplexMesh& mesh,
  const RestrictedVoronoiOptions& options, std::vector<std::int32_t>& own)
{
  const std::size_t nc = mesh.NumCells();
  const int nv = mesh.SimplexDim + 1;
  if (!options.ElementAdjacency)
    own = ComputeElementAdjacency(mesh);
  else if (options.ElementAdjacency->size() != nc * static_cast<std::size_t>(nv))
    throw InputError("RestrictedVoronoi: ElementAdjacency has " +
      std::to_string(options.ElementAdjacency->size()) + " entries, expected NumCells x (SimplexDim+1) = " +
      std::to_string(nc * static_cast<std::size_t>(nv)) + " (pass ComputeElementAdjacency of this mesh)");
  return options.ElementAdjacency ? *options.ElementAdjacency : own;
}

void ElementRangeOf(
  const RestrictedVoronoiOptions& options, std::size_t numElements, std::size_t& first, std::size_t& last)
{
  const std::size_t nc = numElements;
  if (options.ElementBegin < 0 || options.ElementBegin > static_cast<std::int64_t>(nc) ||
    (options.ElementEnd >= 0 &&
      (options.ElementEnd < options.ElementBegin || options.ElementEnd > static_cast<std::int64_t>(nc))))
    throw InputError("RestrictedVoronoi: element range [" + std::to_string(options.ElementBegin) +
      ", " + std::to_string(options.ElementEnd) + ") is not inside [0, " + std::to_string(nc) + ")");
  first = static_cast<std::size_t>(options.ElementBegin);
  last = options.ElementEnd < 0 ? nc : static_cast<std::size_t>(options.ElementEnd);
}

} // namespace rvd

void ValidateRestrictedVoronoiInput(
  const SimplexMesh& mesh, const Embedding& emb, const SiteSet& sites)
{
  auto fail = [](const std::string& s) { throw InputError("RestrictedVoronoi: " + s); };
  if (mesh.SimplexDim != 2 && mesh.SimplexDim != 3)
    fail("the mesh must be made of triangles (SimplexDim 2) or tetrahedra (SimplexDim 3)");
  if (mesh.AmbientDim < mesh.SimplexDim || mesh.AmbientDim > 3)
    fail("AmbientDim must be between SimplexDim and 3");
  if (mesh.Points.empty() || mesh.Points.size() % mesh.AmbientDim != 0)
    fail("mesh points are empty or not a multiple of AmbientDim");
  if (mesh.Cells.empty() || mesh.Cells.size() % (mesh.SimplexDim + 1) != 0)
    fail("mesh cells are empty or not a multiple of SimplexDim+1");
  const std::size_t np = mesh.NumPoints();
  for (std::int32_t id : mesh.Cells)
    if (id < 0 || static_cast<std::size_t>(id) >= np)
      fail("a cell refers to a point id out of range");
  if (emb.Dim < mesh.AmbientDim)
    fail("embedding dimension is smaller than the mesh's AmbientDim");
  if (emb.Coords.size() != np * static_cast<std::size_t>(emb.Dim))
    fail("embedding has " + std::to_string(emb.Coords.size()) + " values, expected NumPoints x Dim = " +
      std::to_string(np * emb.Dim));
  for (double x : emb.Coords)
    if (!std::isfinite(x))
      fail("embedding contains NaN or infinite coordinates");
  const std::size_t ns = sites.NumSites();
  if (ns == 0)
    fail("no sites");
  if (sites.Dim != emb.Dim)
    fail("sites have dimension " + std::to_string(sites.Dim) + " but the embedding has " +
      std::to_string(emb.Dim));
  if (sites.Coords.size() != ns * static_cast<std::size_t>(sites.Dim) || sites.Bary.size() != 4 * ns)
    fail("site arrays have inconsistent sizes (Coords NumSites x Dim, Bary NumSites x 4)");
  if (ns > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    fail("too many sites");
  // Scale for the "site lies in its cell" test.
  double scale = 0.0;
  for (double x : emb.Coords)
    scale = std::max(scale, std::abs(x));
  scale = std::max(scale, 1e-300);
  const int nv = mesh.SimplexDim + 1;
  for (std::size_t s = 0; s < ns; ++s)
  {
    const std::int32_t c = sites.CellIds[s];
    if (c < 0 || static_cast<std::size_t>(c) >= mesh.NumCells())
      fail("site " + std::to_string(s) + " has a cell id out of range");
    const double* b = sites.Bary.data() + 4 * s;
    double sum = 0.0;
    for (int a = 0; a < 4; ++a)
    {
      if (!std::isfinite(b[a]))
        fail("site " + std::to_string(s) + " has NaN barycentric weights");
      if (a < nv && b[a] < -1e-8)
        fail("site " + std::to_string(s) + " has a negative barycentric weight (outside its cell)");
      if (a >= nv && b[a] != 0.0)
        fail("site " + std::to_string(s) + ": the 4th barycentric weight must be 0 on triangles");
      sum += b[a];
    }
    if (std::abs(sum - 1.0) > 1e-8)
      fail("site " + std::to_string(s) + " has barycentric weights that do not sum to 1");
    const std::int32_t* cell = mesh.Cell(c);
    for (int d = 0; d < emb.Dim; ++d)
    {
      double x = 0.0;
      for (int a = 0; a < nv; ++a)
        x += b[a] * emb.At(cell[a])[d];
      const double y = sites.Coords[s * emb.Dim + d];
      if (!std::isfinite(y))
        fail("site " + std::to_string(s) + " has NaN coordinates");
      if (std::abs(x - y) > 1e-6 * scale)
        fail("site " + std::to_string(s) +
          " is not at the barycentric position in its cell (site outside the mesh?)");
    }
  }
}

} // namespace av
