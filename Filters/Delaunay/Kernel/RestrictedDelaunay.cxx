// SPDX-License-Identifier: BSD-3-Clause
// Dual of the restricted Voronoi diagram: collect the Voronoi vertices, deduplicate them,
// orient each simplex in its element's tangent frame and check its back-projection.
#include "RestrictedDelaunay.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <array>
#include <numeric>

namespace av
{
namespace
{
using Key = std::array<std::int32_t, 4>; // sorted site ids, unused slots = -1

// Insertion sort for the tiny label arrays (std::sort trips GCC 12's -Warray-bounds here).
template <class It>
inline void SortSmall(It b, It e)
{
  for (It i = b; i != e; ++i)
    for (It j = i; j != b && *j < *(j - 1); --j)
      std::iter_swap(j, j - 1);
}

// Coordinates of points in the k-dimensional frame (v1-v0, ..., vk-v0) of an element whose
// vertices are rows `v` in R^dim (least squares = orthogonal projection onto its affine hull),
// then the signed volume (times k!) of the simplex they span. `edgeSquares` (optional) gets
// the sum of its squared edge lengths in the same frame coordinates.
double FrameOrientation(const double* const* v, int k, int dim, const double* const* p,
  double* edgeSquares = nullptr)
{
  Eigen::MatrixXd B(dim, k);
  for (int c = 0; c < k; ++c)
    for (int d = 0; d < dim; ++d)
      B(d, c) = v[c + 1][d] - v[0][d];
  const Eigen::MatrixXd G = B.transpose() * B;
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(G);
  Eigen::MatrixXd C(k, k + 1);
  for (int a = 0; a <= k; ++a)
  {
    Eigen::VectorXd r(dim);
    for (int d = 0; d < dim; ++d)
      r(d) = p[a][d] - v[0][d];
    C.col(a) = ldlt.solve(B.transpose() * r);
  }
  Eigen::MatrixXd E(k, k);
  for (int a = 0; a < k; ++a)
    E.col(a) = C.col(a + 1) - C.col(0);
  if (edgeSquares)
  {
    *edgeSquares = 0.0;
    for (int a = 0; a <= k; ++a)
      for (int b = a + 1; b <= k; ++b)
        *edgeSquares += (C.col(b) - C.col(a)).squaredNorm();
  }
  return E.determinant();
}
// Relative volume (k! V / (sum of squared edges)^(k/2)) below which a simplex is flat; a
// regular tetrahedron has 0.048, a regular triangle 0.29.
constexpr double kFlatTolerance = 1e-7;

using VoronoiVertexRecord = std::pair<Key, std::int32_t>; // sorted site ids, element

// The Voronoi vertices of `rvd` by site set, sorted, each kept once with its lowest element.
std::vector<VoronoiVertexRecord> UniqueVoronoiVertices(
  const RestrictedVoronoiDiagram& rvd, int nv, std::size_t ns)
{
  const std::size_t nvv = rvd.VoronoiVertexElement.size();
  std::vector<VoronoiVertexRecord> recs(nvv);
  for (std::size_t i = 0; i < nvv; ++i)
  {
    Key key = { -1, -1, -1, -1 };
    for (int a = 0; a < nv; ++a)
    {
      const std::int32_t s = rvd.VoronoiVertexSites[i * nv + a];
      if (s < 0 || static_cast<std::size_t>(s) >= ns)
        throw InputError("RestrictedDelaunay: Voronoi vertex refers to a site out of range");
      key[a] = s;
    }
    recs[i] = { key, rvd.VoronoiVertexElement[i] };
  }
  tbb::parallel_sort(recs.begin(), recs.end());
  recs.erase(std::unique(recs.begin(), recs.end(),
               [](const auto& a, const auto& b) { return a.first == b.first; }),
    recs.end());
  return recs;
}

// Surfaces: true when triangle (p0, p1, p2) of site ids `key` faces against the input surface,
// i.e. its normal opposes the sum of the unit normals of the input triangles that hold its
// three sites. The element-frame test below sees one element only; a triangle that spans a
// strongly curved region (a thin tube) can pass it and still be folded over ("flipped").
inline bool FlippedAgainstSurface(const SimplexMesh& mesh, const SiteSet& sites,
  const std::vector<double>& points, const Key& key)
{
  using V3 = Eigen::Vector3d;
  const V3 p0(points.data() + 3 * std::size_t(key[0]));
  const V3 n = (V3(points.data() + 3 * std::size_t(key[1])) - p0)
                 .cross(V3(points.data() + 3 * std::size_t(key[2])) - p0);
  V3 ref = V3::Zero();
  for (int a = 0; a < 3; ++a)
  {
    const std::int32_t* t = mesh.Cell(static_cast<std::size_t>(sites.CellIds[key[a]]));
    const V3 x0(mesh.Point(t[0]));
    ref += (V3(mesh.Point(t[1])) - x0).cross(V3(mesh.Point(t[2])) - x0).normalized();
  }
  return !(n.dot(ref) > 0.0);
}

// Cell c of `out` from its Voronoi vertex record: sites ordered so that the simplex is
// positive in the element's embedded frame, flagged inverted when its back-projection to the
// element's input frame is not positive or is flat.
inline void OrientCell(const SimplexMesh& mesh, const Embedding& embedding, const SiteSet& sites,
  const VoronoiVertexRecord& rec, std::size_t c, RestrictedDelaunayMesh& out)
{
  const int k = mesh.SimplexDim, nv = k + 1, adim = mesh.AmbientDim, dim = embedding.Dim;
  Key key = rec.first;
  const std::int32_t e = rec.second;
  const std::int32_t* cell = mesh.Cell(e);
  const double* ev[4];
  const double* xv[4];
  const double* ep[4];
  const double* xp[4];
  for (int a = 0; a < nv; ++a)
  {
    ev[a] = embedding.At(cell[a]);
    xv[a] = mesh.Point(cell[a]);
  }
  for (int a = 0; a < nv; ++a)
    ep[a] = sites.At(key[a]);
  double oe = FrameOrientation(ev, k, dim, ep);
  if (oe < 0.0)
  {
    std::swap(key[0], key[1]);
    std::swap(ep[0], ep[1]);
    oe = -oe;
  }
  for (int a = 0; a < nv; ++a)
    xp[a] = out.Points.data() + std::size_t(key[a]) * adim;
  double l2 = 0.0;
  const double oi = FrameOrientation(xv, k, adim, xp, &l2);
  // Flat counts as inverted: a simplex whose volume is round-off next to its edges (e.g.
  // four sites on a flat boundary face whose embedded images are not quite coplanar) is
  // no usable element, and the repair breaks it up like an inverted one.
  const double flat = kFlatTolerance * std::pow(l2, 0.5 * k);
  out.Inverted[c] = (oe > 0.0 && oi > flat) ? 0 : 1;
  if (!out.Inverted[c] && k == 2 && adim == 3)
    out.Inverted[c] = FlippedAgainstSurface(mesh, sites, out.Points, key) ? 1 : 0;
  for (int a = 0; a < nv; ++a)
    out.Cells[c * nv + a] = key[a];
  out.CellElement[c] = e;
}

// NumNonManifoldFaces (faces of more than two cells) and NumOpenInteriorFaces (faces of one
// cell that are not dual to a boundary face of `rvd`) of `out`.
void CountFaceSharing(const RestrictedVoronoiDiagram& rvd, RestrictedDelaunayMesh& out)
{
  const int k = out.SimplexDim, nv = k + 1;
  const std::size_t nc = out.NumCells();
  std::vector<Key> faces;
  faces.reserve(nc * nv);
  for (std::size_t c = 0; c < nc; ++c)
    for (int a = 0; a < nv; ++a)
    {
      Key f = { -1, -1, -1, -1 };
      int n = 0;
      for (int b = 0; b < nv; ++b)
        if (b != a)
          f[n++] = out.Cells[c * nv + b];
      SortSmall(f.begin(), f.begin() + n);
      faces.push_back(f);
    }
  tbb::parallel_sort(faces.begin(), faces.end());
  std::vector<Key> bnd;
  for (std::size_t i = 0; i + k <= rvd.BoundaryDualFaces.size(); i += k)
  {
    Key f = { -1, -1, -1, -1 };
    for (int a = 0; a < k; ++a)
      f[a] = rvd.BoundaryDualFaces[i + a];
    SortSmall(f.begin(), f.begin() + k);
    bnd.push_back(f);
  }
  std::sort(bnd.begin(), bnd.end());
  bnd.erase(std::unique(bnd.begin(), bnd.end()), bnd.end());
  for (std::size_t i = 0; i < faces.size();)
  {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j] == faces[i])
      ++j;
    const std::size_t cnt = j - i;
    if (cnt > 2)
      ++out.NumNonManifoldFaces;
    else if (cnt == 1 && !std::binary_search(bnd.begin(), bnd.end(), faces[i]))
      ++out.NumOpenInteriorFaces;
    i = j;
  }
}
} // namespace

RestrictedDelaunayMesh ComputeRestrictedDelaunay(const SimplexMesh& mesh,
  const Embedding& embedding, const SiteSet& sites, const RestrictedVoronoiDiagram& rvd)
{
  ValidateRestrictedVoronoiInput(mesh, embedding, sites);
  const int k = mesh.SimplexDim, nv = k + 1;
  if (rvd.SimplexDim != k || rvd.Dim != embedding.Dim || rvd.NumSites != sites.NumSites() ||
    rvd.VoronoiVertexSites.size() != rvd.VoronoiVertexElement.size() * nv)
    throw InputError("RestrictedDelaunay: the Voronoi diagram was not computed from this "
                     "mesh / embedding / site set");
  const std::size_t ns = sites.NumSites();
  const int adim = mesh.AmbientDim;

  RestrictedDelaunayMesh out;
  out.SimplexDim = k;
  out.AmbientDim = adim;
  out.Points.resize(ns * adim);
  for (std::size_t s = 0; s < ns; ++s)
    for (int d = 0; d < adim; ++d)
      out.Points[s * adim + d] = sites.At(s)[d];

  const std::vector<VoronoiVertexRecord> recs = UniqueVoronoiVertices(rvd, nv, ns);
  const std::size_t nc = recs.size();
  out.Cells.resize(nc * nv);
  out.CellElement.resize(nc);
  out.Inverted.assign(nc, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nc), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t c = r.begin(); c != r.end(); ++c)
      OrientCell(mesh, embedding, sites, recs[c], c, out);
  });
  out.NumInverted = static_cast<std::size_t>(std::count(out.Inverted.begin(), out.Inverted.end(), 1));

  CountFaceSharing(rvd, out);
  std::vector<char> used(ns, 0);
  for (std::int32_t s : out.Cells)
    used[s] = 1;
  out.NumUnusedSites = static_cast<std::size_t>(std::count(used.begin(), used.end(), 0));
  return out;
}

void ValidateSiteMoveInput(const char* caller, const SimplexMesh& mesh,
  const Embedding& embedding, const SiteSet& sites, const RestrictedDelaunayMesh& rdt)
{
  auto fail = [caller](const std::string& m) { throw InputError(std::string(caller) + ": " + m); };
  const std::size_t ns = sites.NumSites();
  const int dim = embedding.Dim;
  if (sites.Dim != dim || sites.Coords.size() != ns * static_cast<std::size_t>(dim) ||
    sites.Bary.size() != 4 * ns)
    fail("sites do not match the embedding dimension or have inconsistent array sizes");
  if (embedding.Coords.size() != mesh.NumPoints() * static_cast<std::size_t>(dim))
    fail("embedding has " + std::to_string(embedding.Coords.size()) + " values, expected NumPoints x Dim");
  for (std::int32_t c : sites.CellIds)
    if (c < 0 || static_cast<std::size_t>(c) >= mesh.NumCells())
      fail("a site has a cell id out of range");
  const int nv = rdt.SimplexDim + 1;
  if (rdt.Cells.size() % static_cast<std::size_t>(nv) != 0)
    fail("the Delaunay cells are not a multiple of SimplexDim+1");
  for (std::int32_t id : rdt.Cells)
    if (id < 0 || static_cast<std::size_t>(id) >= ns)
      fail("a Delaunay cell refers to a site id out of range (pass the sites of that mesh)");
}

} // namespace av
