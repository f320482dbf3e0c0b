// SPDX-License-Identifier: BSD-3-Clause
#include "MeshTopology.h"

#include <Eigen/Dense>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>

namespace av
{
namespace
{
/// Largest embedding dimension of the fixed-capacity Eigen temporaries below.
constexpr int kMaxEmbeddingDim = 20;

double Det3(const double* p0, const double* p1, const double* p2, const double* p3)
{
  const double a[3] = { p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2] };
  const double b[3] = { p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2] };
  const double c[3] = { p3[0] - p0[0], p3[1] - p0[1], p3[2] - p0[2] };
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
    a[2] * (b[0] * c[1] - b[1] * c[0]);
}
} // namespace

void CheckCellIds(const SimplexMesh& mesh, const std::string& who, const char* kind)
{
  const std::size_t np = mesh.NumPoints();
  const int nv = mesh.VerticesPerCell();
  for (std::size_t c = 0; c < mesh.NumCells(); ++c)
  {
    const std::int32_t* t = mesh.Cell(c);
    for (int k = 0; k < nv; ++k)
    {
      if (t[k] < 0 || static_cast<std::size_t>(t[k]) >= np)
      {
        throw InputError(who + kind + " " + std::to_string(c) + " references point " +
          std::to_string(t[k]) + ", outside [0, " + std::to_string(np) + ")");
      }
    }
  }
}

std::vector<CellFacet> SortedCellFacets(const SimplexMesh& mesh)
{
  const int nv = mesh.SimplexDim + 1;
  std::vector<CellFacet> facets;
  facets.reserve(static_cast<std::size_t>(nv) * mesh.NumCells());
  for (std::size_t c = 0; c < mesh.NumCells(); ++c)
  {
    const std::int32_t* cell = mesh.Cell(c);
    for (int skip = 0; skip < nv; ++skip)
    {
      CellFacet f{ { -1, -1, -1 }, static_cast<std::int32_t>(c) };
      int q = 0;
      for (int a = 0; a < nv; ++a)
        if (a != skip)
          f.Vertices[q++] = cell[a];
      std::sort(f.Vertices.begin(), f.Vertices.begin() + q);
      facets.push_back(f);
    }
  }
  std::sort(facets.begin(), facets.end());
  return facets;
}

std::vector<std::int32_t> UniqueEdges(const SimplexMesh& mesh)
{
  const int nv = mesh.VerticesPerCell();
  std::vector<std::uint64_t> keys;
  keys.reserve(mesh.NumCells() * nv * (nv - 1) / 2);
  for (std::size_t c = 0; c < mesh.NumCells(); ++c)
  {
    const std::int32_t* cell = mesh.Cell(c);
    for (int a = 0; a < nv; ++a)
    {
      for (int b = a + 1; b < nv; ++b)
      {
        std::uint32_t u = static_cast<std::uint32_t>(cell[a]),
                      w = static_cast<std::uint32_t>(cell[b]);
        if (u > w)
        {
          std::swap(u, w);
        }
        keys.push_back((static_cast<std::uint64_t>(u) << 32) | w);
      }
    }
  }
  tbb::parallel_sort(keys.begin(), keys.end()); // plain keys: any order of equals is the same
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  std::vector<std::int32_t> edges(2 * keys.size());
  for (std::size_t e = 0; e < keys.size(); ++e)
  {
    edges[2 * e] = static_cast<std::int32_t>(keys[e] >> 32);
    edges[2 * e + 1] = static_cast<std::int32_t>(keys[e] & 0xffffffffu);
  }
  return edges;
}

std::vector<char> BoundaryVertexMask(const SimplexMesh& mesh)
{
  std::vector<char> mask(mesh.NumPoints(), 0);
  const int nv = mesh.VerticesPerCell();
  if (mesh.SimplexDim == 3)
  {
    std::vector<std::array<std::int32_t, 3>> faces;
    faces.reserve(4 * mesh.NumCells());
    for (std::size_t c = 0; c < mesh.NumCells(); ++c)
    {
      const std::int32_t* cell = mesh.Cell(c);
      for (int skip = 0; skip < 4; ++skip)
      {
        std::array<std::int32_t, 3> f;
        int q = 0;
        for (int a = 0; a < 4; ++a)
        {
          if (a != skip)
          {
            f[q++] = cell[a];
          }
        }
        std::sort(f.begin(), f.end());
        faces.push_back(f);
      }
    }
    tbb::parallel_sort(faces.begin(), faces.end());
    for (std::size_t i = 0; i < faces.size();)
    {
      std::size_t j = i + 1;
      while (j < faces.size() && faces[j] == faces[i])
      {
        ++j;
      }
      if (j - i == 1)
      {
        for (std::int32_t v : faces[i])
        {
          mask[v] = 1;
        }
      }
      i = j;
    }
  }
  else
  {
    std::vector<std::uint64_t> keys;
    keys.reserve(3 * mesh.NumCells());
    for (std::size_t c = 0; c < mesh.NumCells(); ++c)
    {
      const std::int32_t* cell = mesh.Cell(c);
      for (int a = 0; a < nv; ++a)
      {
        std::uint32_t u = static_cast<std::uint32_t>(cell[a]);
        std::uint32_t w = static_cast<std::uint32_t>(cell[(a + 1) % nv]);
        if (u > w)
        {
          std::swap(u, w);
        }
        keys.push_back((static_cast<std::uint64_t>(u) << 32) | w);
      }
    }
    tbb::parallel_sort(keys.begin(), keys.end());
    for (std::size_t i = 0; i < keys.size();)
    {
      std::size_t j = i + 1;
      while (j < keys.size() && keys[j] == keys[i])
      {
        ++j;
      }
      if (j - i == 1)
      {
        mask[keys[i] >> 32] = 1;
        mask[keys[i] & 0xffffffffu] = 1;
      }
      i = j;
    }
  }
  return mask;
}

double CellMeasure(const SimplexMesh& mesh, std::size_t cell)
{
  const std::int32_t* c = mesh.Cell(cell);
  if (mesh.SimplexDim == 3)
  {
    return Det3(mesh.Point(c[0]), mesh.Point(c[1]), mesh.Point(c[2]), mesh.Point(c[3])) / 6.0;
  }
  const int d = mesh.AmbientDim;
  const double* p0 = mesh.Point(c[0]);
  const double* p1 = mesh.Point(c[1]);
  const double* p2 = mesh.Point(c[2]);
  if (d == 2)
  {
    return 0.5 * ((p1[0] - p0[0]) * (p2[1] - p0[1]) - (p1[1] - p0[1]) * (p2[0] - p0[0]));
  }
  const double a[3] = { p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2] };
  const double b[3] = { p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2] };
  const double n[3] = {
    a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]
  };
  return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

std::size_t LabelBodies(const SimplexMesh& mesh, std::vector<std::int32_t>& pointBody)
{
  CheckCellIds(mesh, "LabelBodies: ", "cell");
  // Union-find over the points, each cell joining its vertices.
  std::vector<std::int32_t> parent(mesh.NumPoints());
  for (std::size_t p = 0; p < parent.size(); ++p)
    parent[p] = static_cast<std::int32_t>(p);
  auto root = [&](std::int32_t p)
  {
    while (parent[p] != p)
      p = parent[p] = parent[parent[p]];
    return p;
  };
  const int nv = mesh.SimplexDim + 1;
  for (std::size_t c = 0; c < mesh.NumCells(); ++c)
  {
    const std::int32_t* ids = mesh.Cell(c);
    for (int i = 1; i < nv; ++i)
    {
      const std::int32_t a = root(ids[0]), b = root(ids[i]);
      if (a != b)
        parent[std::max(a, b)] = std::min(a, b);
    }
  }
  pointBody.assign(mesh.NumPoints(), -1);
  std::vector<std::int32_t> bodyOfRoot(mesh.NumPoints(), -1);
  std::int32_t count = 0;
  for (std::size_t c = 0; c < mesh.NumCells(); ++c)
    for (int i = 0; i < nv; ++i)
    {
      const std::int32_t p = mesh.Cell(c)[i], r = root(p);
      if (bodyOfRoot[r] < 0)
        bodyOfRoot[r] = count++;
      pointBody[p] = bodyOfRoot[r];
    }
  return static_cast<std::size_t>(count);
}

std::size_t CountPinchedBoundaryEdges(const SimplexMesh& tets)
{
  if (tets.SimplexDim != 3)
    throw InputError("CountPinchedBoundaryEdges: the mesh must be made of tets");
  const std::vector<CellFacet> facets = SortedCellFacets(tets);
  std::vector<std::pair<std::int32_t, std::int32_t>> edges;
  for (std::size_t i = 0; i < facets.size();)
  {
    std::size_t j = i + 1;
    while (j < facets.size() && facets[j].Vertices == facets[i].Vertices)
      ++j;
    if (j - i == 1) // a boundary face (sorted vertices)
    {
      const auto& v = facets[i].Vertices;
      edges.emplace_back(v[0], v[1]);
      edges.emplace_back(v[0], v[2]);
      edges.emplace_back(v[1], v[2]);
    }
    i = j;
  }
  std::sort(edges.begin(), edges.end());
  std::size_t pinched = 0;
  for (std::size_t i = 0; i < edges.size();)
  {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j] == edges[i])
      ++j;
    pinched += j - i > 2 ? 1 : 0;
    i = j;
  }
  return pinched;
}

std::vector<std::int32_t> ComputeElementAdjacency(const SimplexMesh& mesh)
{
  // Facets bucketed by their smallest vertex id (counting sort), then matched inside each
  // bucket (a few dozen facets): linear time, no global sort.
  const int nv = mesh.SimplexDim + 1;
  const std::size_t nc = mesh.NumCells();
  const std::size_t np = mesh.NumPoints();
  const std::size_t nf = nc * nv;
  struct F
  {
    std::int32_t K1, K2; // the other facet vertices, sorted (K2 = -1 for triangles)
    std::int64_t Id;     // cell * nv + facet
    bool operator<(const F& o) const
    {
      return K1 < o.K1 || (K1 == o.K1 && (K2 < o.K2 || (K2 == o.K2 && Id < o.Id)));
    }
  };
  auto facetKey = [&](std::size_t id, std::int32_t& v0, F& f)
  {
    const std::int32_t* cell = mesh.Cell(id / nv);
    const int a = static_cast<int>(id % nv);
    std::array<std::int32_t, 4> k = { std::numeric_limits<std::int32_t>::max(),
      std::numeric_limits<std::int32_t>::max(),
      std::numeric_limits<std::int32_t>::max(),
      std::numeric_limits<std::int32_t>::max() };
    int n = 0;
    for (int b = 0; b < nv; ++b)
      if (b != a)
        k[n++] = cell[b];
    std::sort(k.begin(), k.begin() + n);
    v0 = k[0];
    f.K1 = k[1];
    f.K2 = nv == 4 ? k[2] : -1;
    f.Id = static_cast<std::int64_t>(id);
  };
  std::vector<std::int64_t> start(np + 1, 0);
  for (std::size_t id = 0; id < nf; ++id)
  {
    const std::int32_t* cell = mesh.Cell(id / nv);
    const int a = static_cast<int>(id % nv);
    std::int32_t v0 = std::numeric_limits<std::int32_t>::max();
    for (int b = 0; b < nv; ++b)
      if (b != a)
        v0 = std::min(v0, cell[b]);
    ++start[v0 + 1];
  }
  for (std::size_t v = 0; v < np; ++v)
    start[v + 1] += start[v];
  std::vector<F> f(nf);
  {
    std::vector<std::int64_t> fill(start.begin(), start.end() - 1);
    for (std::size_t id = 0; id < nf; ++id)
    {
      std::int32_t v0;
      F x;
      facetKey(id, v0, x);
      f[fill[v0]++] = x;
    }
  }
  std::vector<std::int32_t> adj(nf, -1);
  std::atomic<bool> nonManifold{ false };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, np),
    [&](const tbb::blocked_range<std::size_t>& r)
    {
      for (std::size_t v = r.begin(); v != r.end(); ++v)
      {
        const auto b = f.begin() + start[v], e = f.begin() + start[v + 1];
        std::sort(b, e);
        for (auto i = b; i != e;)
        {
          auto j = i + 1;
          while (j != e && j->K1 == i->K1 && j->K2 == i->K2)
            ++j;
          if (j - i > 2)
            nonManifold = true;
          if (j - i == 2)
          {
            adj[i->Id] = static_cast<std::int32_t>((i + 1)->Id / nv);
            adj[(i + 1)->Id] = static_cast<std::int32_t>(i->Id / nv);
          }
          i = j;
        }
      }
    });
  if (nonManifold)
    throw InputError("RestrictedVoronoi: the mesh is not manifold (a facet is shared by more "
                     "than two cells)");
  return adj;
}

std::vector<double> EmbeddedCellMeasures(const SimplexMesh& mesh, const Embedding& emb)
{
  const std::size_t nc = mesh.NumCells();
  const int k = mesh.SimplexDim, dim = emb.Dim;
  std::vector<double> meas(nc, 0.0);
  const double fact = k == 2 ? 2.0 : 6.0;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nc),
    [&](const tbb::blocked_range<std::size_t>& r)
    {
      Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::ColMajor, kMaxEmbeddingDim, 3> e(dim, 3);
      for (std::size_t c = r.begin(); c != r.end(); ++c)
      {
        const std::int32_t* ids = mesh.Cell(c);
        const Eigen::Map<const Eigen::VectorXd> v0(emb.At(static_cast<std::size_t>(ids[0])), dim);
        for (int j = 0; j < k; ++j)
          e.col(j) =
            Eigen::Map<const Eigen::VectorXd>(emb.At(static_cast<std::size_t>(ids[j + 1])), dim) -
            v0;
        // Gram determinant: measure = sqrt(det(E^T E)) / k!.
        double det;
        if (k == 3)
          det = Eigen::Matrix3d(e.transpose() * e).determinant();
        else
        {
          const auto a = e.col(0), b = e.col(1);
          det = a.squaredNorm() * b.squaredNorm() - a.dot(b) * a.dot(b);
        }
        meas[c] = std::sqrt(std::max(0.0, det)) / fact;
      }
    });
  return meas;
}

} // namespace av
