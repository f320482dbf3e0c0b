// SPDX-License-Identifier: BSD-3-Clause
// SharpFeatures: feature lines by the dihedral-angle test on boundary triangles (tets) or cells
// (triangles), corners where the lines meet or turn.
#include "SharpFeatures.h"

#include "MeshTopology.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace av
{
namespace
{

constexpr double kPi = 3.14159265358979323846;

Eigen::Vector3d PointAt(const SimplexMesh& mesh, std::int32_t id)
{
  const double* p = mesh.Point(static_cast<std::size_t>(id));
  return Eigen::Vector3d(p[0], p[1], mesh.AmbientDim == 3 ? p[2] : 0.0);
}

/// A mesh edge seen from one of its cells (or boundary faces).
struct EdgeRecord
{
  std::int32_t A, B;   // point ids, A < B
  std::int32_t Owner;  // boundary face (tets) or cell (triangles)
  bool Forward;        // the owner lists A before B in its cyclic order (triangles)
  bool operator<(const EdgeRecord& o) const
  {
    return A != o.A ? A < o.A : (B != o.B ? B < o.B : Owner < o.Owner);
  }
};

EdgeRecord MakeEdge(std::int32_t u, std::int32_t v, std::int32_t owner)
{
  return u < v ? EdgeRecord{ u, v, owner, true } : EdgeRecord{ v, u, owner, false };
}

/// Local index of point `id` in cell c (the caller knows it is there).
std::int8_t LocalIndex(const SimplexMesh& mesh, std::size_t c, std::int32_t id)
{
  const std::int32_t* ids = mesh.Cell(c);
  for (int j = 0; j < mesh.VerticesPerCell(); ++j)
    if (ids[j] == id)
      return static_cast<std::int8_t>(j);
  return -1;
}

void Validate(const SimplexMesh& mesh, double angle)
{
  if (!std::isfinite(angle) || !(angle > 0.0))
    throw InputError("sharp features: the feature angle must be a positive number of degrees");
  if (mesh.SimplexDim != 2 && mesh.SimplexDim != 3)
    throw InputError("sharp features: only triangle and tetrahedral meshes are supported");
  if (mesh.AmbientDim != 2 && mesh.AmbientDim != 3)
    throw InputError("sharp features: points must be 2D or 3D");
  if (mesh.NumCells() == 0 || mesh.NumPoints() == 0)
    throw InputError("sharp features: the mesh is empty");
  const auto np = static_cast<std::int32_t>(mesh.NumPoints());
  for (std::int32_t id : mesh.Cells)
    if (id < 0 || id >= np)
      throw InputError("sharp features: cell point id " + std::to_string(id) + " out of range");
}

/// Mesh edges with the owners whose normals are compared: boundary triangles (tets) or cells
/// (triangles), with a unit normal and a cell containing each owner.
struct OwnedEdges
{
  std::vector<EdgeRecord> Edges;
  std::vector<Eigen::Vector3d> Normals; // per owner
  std::vector<std::int32_t> OwnerCell;  // per owner: a cell containing it
};

Eigen::Vector3d UnitOrZero(const Eigen::Vector3d& n)
{
  const double len = n.norm();
  return len > 0.0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
}

/// Tets: the boundary triangles (no neighbor across them), with outward normals.
void CollectBoundaryTriangles(const SimplexMesh& mesh, OwnedEdges& out)
{
  const std::vector<std::int32_t> adjacency = ComputeElementAdjacency(mesh);
  for (std::size_t c = 0; c < mesh.NumCells(); ++c)
  {
    const std::int32_t* ids = mesh.Cell(c);
    for (int i = 0; i < 4; ++i)
    {
      if (adjacency[4 * c + static_cast<std::size_t>(i)] >= 0)
        continue;
      std::array<std::int32_t, 3> f;
      int q = 0;
      for (int j = 0; j < 4; ++j)
        if (j != i)
          f[static_cast<std::size_t>(q++)] = ids[j];
      const Eigen::Vector3d a = PointAt(mesh, f[0]), b = PointAt(mesh, f[1]), d = PointAt(mesh, f[2]);
      Eigen::Vector3d n = (b - a).cross(d - a);
      if (n.dot(PointAt(mesh, ids[i]) - a) > 0.0)
        n = -n;
      const auto owner = static_cast<std::int32_t>(out.Normals.size());
      out.Normals.push_back(UnitOrZero(n));
      out.OwnerCell.push_back(static_cast<std::int32_t>(c));
      out.Edges.push_back(MakeEdge(f[0], f[1], owner));
      out.Edges.push_back(MakeEdge(f[1], f[2], owner));
      out.Edges.push_back(MakeEdge(f[0], f[2], owner));
    }
  }
}

/// Triangles: every cell with its normal (its vertex order's).
void CollectTriangles(const SimplexMesh& mesh, OwnedEdges& out)
{
  for (std::size_t c = 0; c < mesh.NumCells(); ++c)
  {
    const std::int32_t* ids = mesh.Cell(c);
    const Eigen::Vector3d a = PointAt(mesh, ids[0]), b = PointAt(mesh, ids[1]),
                          d = PointAt(mesh, ids[2]);
    out.Normals.push_back(UnitOrZero((b - a).cross(d - a)));
    out.OwnerCell.push_back(static_cast<std::int32_t>(c));
    for (int i = 0; i < 3; ++i)
      out.Edges.push_back(MakeEdge(ids[i], ids[(i + 1) % 3], static_cast<std::int32_t>(c)));
  }
}

/// A line of the feature graph: a feature edge, or (triangle meshes) a boundary edge, which
/// only counts for the corners.
struct Line
{
  std::int32_t A, B, Owner;
  bool Feature;
};

/// The lines among the sorted owned edges: edges whose owners' normals differ by more than the
/// angle (cos below cosLimit), non-manifold edges, and (triangles) the boundary edges.
std::vector<Line> FindLines(const SimplexMesh& mesh, const OwnedEdges& owned, double cosLimit)
{
  const std::vector<EdgeRecord>& edges = owned.Edges;
  const std::vector<Eigen::Vector3d>& normals = owned.Normals;
  std::vector<Line> lines;
  for (std::size_t i = 0; i < edges.size();)
  {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j].A == edges[i].A && edges[j].B == edges[i].B)
      ++j;
    const std::size_t count = j - i;
    const EdgeRecord& e = edges[i];
    if (mesh.SimplexDim == 3)
    {
      bool sharp = count != 2;
      if (count == 2)
      {
        const Eigen::Vector3d& n0 = normals[static_cast<std::size_t>(e.Owner)];
        const Eigen::Vector3d& n1 = normals[static_cast<std::size_t>(edges[i + 1].Owner)];
        sharp = n0.squaredNorm() > 0.0 && n1.squaredNorm() > 0.0 && n0.dot(n1) < cosLimit;
      }
      if (sharp)
        lines.push_back({ e.A, e.B, e.Owner, true });
    }
    else if (count == 1)
      lines.push_back({ e.A, e.B, e.Owner, false }); // domain / surface boundary
    else if (mesh.AmbientDim == 3)
    {
      bool sharp = count > 2;
      if (count == 2)
      {
        // Consistently oriented neighbors traverse the edge in opposite directions.
        const Eigen::Vector3d n0 = normals[static_cast<std::size_t>(e.Owner)];
        Eigen::Vector3d n1 = normals[static_cast<std::size_t>(edges[i + 1].Owner)];
        if (edges[i + 1].Forward == e.Forward)
          n1 = -n1;
        sharp = n0.squaredNorm() > 0.0 && n1.squaredNorm() > 0.0 && n0.dot(n1) < cosLimit;
      }
      if (sharp)
        lines.push_back({ e.A, e.B, e.Owner, true });
    }
    i = j;
  }
  return lines;
}

/// Triangle surfaces with patch ids: the edges between cells of different ids and the
/// non-manifold edges are feature lines, the surface boundary counts for the corners.
std::vector<Line> FindPatchLines(const OwnedEdges& owned, const std::vector<std::int32_t>& patch)
{
  const std::vector<EdgeRecord>& edges = owned.Edges;
  std::vector<Line> lines;
  for (std::size_t i = 0; i < edges.size();)
  {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j].A == edges[i].A && edges[j].B == edges[i].B)
      ++j;
    const EdgeRecord& e = edges[i];
    if (j - i == 1)
      lines.push_back({ e.A, e.B, e.Owner, false });
    else if (j - i > 2 ||
      patch[static_cast<std::size_t>(e.Owner)] !=
        patch[static_cast<std::size_t>(edges[i + 1].Owner)])
      lines.push_back({ e.A, e.B, e.Owner, true });
    i = j;
  }
  return lines;
}

/// Corners: line degree other than 2, a turn sharper than the feature angle (cosLimit below
/// -1: none), or flagged in `extra` (may be null). Fills IsCorner and the corners with a cell
/// containing each (the first cell listing it).
void FindCorners(const SimplexMesh& mesh,
  const std::vector<Line>& lines,
  double cosLimit,
  SharpFeatures& out,
  const std::vector<std::uint8_t>* extra = nullptr)
{
  const std::size_t np = mesh.NumPoints(), nc = mesh.NumCells();
  std::vector<std::int32_t> degree(np, 0);
  std::vector<std::array<std::int32_t, 2>> ends(np, { -1, -1 });
  for (const Line& l : lines)
    for (int s = 0; s < 2; ++s)
    {
      const std::int32_t p = s == 0 ? l.A : l.B, q = s == 0 ? l.B : l.A;
      auto& slot = ends[static_cast<std::size_t>(p)];
      if (degree[static_cast<std::size_t>(p)] < 2)
        slot[static_cast<std::size_t>(degree[static_cast<std::size_t>(p)])] = q;
      ++degree[static_cast<std::size_t>(p)];
    }
  for (std::size_t p = 0; p < np; ++p)
  {
    const std::int32_t deg = degree[p];
    bool corner = deg == 1 || deg >= 3;
    if (deg == 2)
    {
      const Eigen::Vector3d x = PointAt(mesh, static_cast<std::int32_t>(p));
      const Eigen::Vector3d u = PointAt(mesh, ends[p][0]) - x, v = PointAt(mesh, ends[p][1]) - x;
      const double uu = u.norm(), vv = v.norm();
      // Straight through: u = -v; the turn is the angle between u and -v.
      corner = uu > 0.0 && vv > 0.0 && (-u.dot(v)) / (uu * vv) < cosLimit;
    }
    out.IsCorner[p] = corner || (extra && (*extra)[p]) ? 1 : 0;
  }
  std::vector<std::int32_t> firstCell(np, -1);
  for (std::size_t c = nc; c-- > 0;)
    for (int j = 0; j < mesh.VerticesPerCell(); ++j)
      firstCell[static_cast<std::size_t>(mesh.Cell(c)[j])] = static_cast<std::int32_t>(c);
  for (std::size_t p = 0; p < np; ++p)
    if (out.IsCorner[p] && firstCell[p] >= 0)
    {
      out.Corners.push_back(static_cast<std::int32_t>(p));
      out.CornerCells.push_back(firstCell[p]);
      out.CornerLocal.push_back(LocalIndex(mesh, static_cast<std::size_t>(firstCell[p]),
        static_cast<std::int32_t>(p)));
    }
}

/// The feature edges of `lines` with a cell containing each (its owner's) and the CSR map
/// point -> incident feature edges.
void AddFeatureEdges(const SimplexMesh& mesh, const std::vector<Line>& lines,
  const std::vector<std::int32_t>& ownerCell, SharpFeatures& out)
{
  const std::size_t np = mesh.NumPoints();
  for (const Line& l : lines)
  {
    if (!l.Feature)
      continue;
    const std::int32_t cell = ownerCell[static_cast<std::size_t>(l.Owner)];
    out.Edges.push_back(l.A);
    out.Edges.push_back(l.B);
    out.EdgeCells.push_back(cell);
    out.EdgeLocal.push_back(LocalIndex(mesh, static_cast<std::size_t>(cell), l.A));
    out.EdgeLocal.push_back(LocalIndex(mesh, static_cast<std::size_t>(cell), l.B));
  }
  for (std::size_t e = 0; e < out.NumEdges(); ++e)
  {
    ++out.PointEdgeOffsets[static_cast<std::size_t>(out.Edges[2 * e]) + 1];
    ++out.PointEdgeOffsets[static_cast<std::size_t>(out.Edges[2 * e + 1]) + 1];
  }
  for (std::size_t p = 0; p < np; ++p)
    out.PointEdgeOffsets[p + 1] += out.PointEdgeOffsets[p];
  out.PointEdges.resize(static_cast<std::size_t>(out.PointEdgeOffsets[np]));
  std::vector<std::int32_t> fill(out.PointEdgeOffsets.begin(), out.PointEdgeOffsets.end() - 1);
  for (std::size_t e = 0; e < out.NumEdges(); ++e)
    for (int s = 0; s < 2; ++s)
      out.PointEdges[static_cast<std::size_t>(fill[static_cast<std::size_t>(out.Edges[2 * e + s])]++)] =
        static_cast<std::int32_t>(e);
}

} // namespace

SharpFeatures DetectSharpFeatures(const SimplexMesh& mesh, double featureAngleDegrees)
{
  Validate(mesh, featureAngleDegrees);
  SharpFeatures out;
  const std::size_t np = mesh.NumPoints();
  out.IsCorner.assign(np, 0);
  out.PointEdgeOffsets.assign(np + 1, 0);
  if (featureAngleDegrees >= 180.0)
    return out;
  const double cosLimit = std::cos(featureAngleDegrees * kPi / 180.0);
  OwnedEdges owned;
  if (mesh.SimplexDim == 3)
    CollectBoundaryTriangles(mesh, owned);
  else
    CollectTriangles(mesh, owned);
  std::sort(owned.Edges.begin(), owned.Edges.end());
  const std::vector<Line> lines = FindLines(mesh, owned, cosLimit);
  FindCorners(mesh, lines, cosLimit, out);
  AddFeatureEdges(mesh, lines, owned.OwnerCell, out);
  return out;
}

SharpFeatures SharpFeaturesFromPatches(const SimplexMesh& mesh,
  const std::vector<std::int32_t>& patchIds,
  const std::vector<std::uint8_t>* corners,
  double featureAngleDegrees)
{
  Validate(mesh, featureAngleDegrees);
  if (mesh.SimplexDim != 2 || mesh.AmbientDim != 3)
    throw InputError("sharp features: patch ids need a triangle surface in 3D");
  if (patchIds.size() != mesh.NumCells())
    throw InputError("sharp features: " + std::to_string(patchIds.size()) + " patch ids for " +
      std::to_string(mesh.NumCells()) + " triangles (one per triangle)");
  if (corners && corners->size() != mesh.NumPoints())
    throw InputError("sharp features: " + std::to_string(corners->size()) + " corner flags for " +
      std::to_string(mesh.NumPoints()) + " points (one per point)");
  SharpFeatures out;
  const std::size_t np = mesh.NumPoints();
  out.IsCorner.assign(np, 0);
  out.PointEdgeOffsets.assign(np + 1, 0);
  // Turns sharper than the angle still make corners (a line site cannot go round them).
  const double cosLimit =
    featureAngleDegrees >= 180.0 ? -2.0 : std::cos(featureAngleDegrees * kPi / 180.0);
  OwnedEdges owned;
  CollectTriangles(mesh, owned);
  std::sort(owned.Edges.begin(), owned.Edges.end());
  const std::vector<Line> lines = FindPatchLines(owned, patchIds);
  FindCorners(mesh, lines, cosLimit, out, corners);
  AddFeatureEdges(mesh, lines, owned.OwnerCell, out);
  return out;
}

SharpFeatures SharpFeaturesFromEdges(const SimplexMesh& mesh,
  const std::vector<std::int32_t>& edges,
  const std::vector<std::int32_t>& corners)
{
  Validate(mesh, 30.0);
  if (edges.size() % 2 != 0)
    throw InputError("sharp features: feature edges need two point ids each");
  const std::size_t np = mesh.NumPoints(), nc = mesh.NumCells();
  const auto inRange = [np](std::int32_t p) { return p >= 0 && static_cast<std::size_t>(p) < np; };
  // A cell holding each mesh edge.
  std::vector<EdgeRecord> cellEdges;
  const int nv = mesh.VerticesPerCell();
  cellEdges.reserve(nc * static_cast<std::size_t>(nv * (nv - 1) / 2));
  for (std::size_t c = 0; c < nc; ++c)
    for (int a = 0; a < nv; ++a)
      for (int b = a + 1; b < nv; ++b)
        cellEdges.push_back(
          MakeEdge(mesh.Cell(c)[a], mesh.Cell(c)[b], static_cast<std::int32_t>(c)));
  std::sort(cellEdges.begin(), cellEdges.end());
  std::vector<Line> lines;
  for (std::size_t e = 0; e < edges.size() / 2; ++e)
  {
    const std::int32_t u = edges[2 * e], v = edges[2 * e + 1];
    if (!inRange(u) || !inRange(v) || u == v)
      throw InputError("sharp features: feature edge " + std::to_string(e) + " (" +
        std::to_string(u) + ", " + std::to_string(v) + ") has a bad point id");
    const EdgeRecord key = MakeEdge(u, v, -1);
    const auto it = std::lower_bound(cellEdges.begin(), cellEdges.end(), key);
    if (it == cellEdges.end() || it->A != key.A || it->B != key.B)
      throw InputError("sharp features: feature edge (" + std::to_string(u) + ", " +
        std::to_string(v) + ") is not an edge of the mesh");
    lines.push_back({ key.A, key.B, it->Owner, true });
  }
  std::sort(lines.begin(),
    lines.end(),
    [](const Line& x, const Line& y) { return x.A != y.A ? x.A < y.A : x.B < y.B; });
  lines.erase(std::unique(lines.begin(),
                lines.end(),
                [](const Line& x, const Line& y) { return x.A == y.A && x.B == y.B; }),
    lines.end());
  std::vector<std::uint8_t> flags(np, 0);
  for (std::int32_t p : corners)
  {
    if (!inRange(p))
      throw InputError("sharp features: corner point id " + std::to_string(p) + " out of range");
    flags[static_cast<std::size_t>(p)] = 1;
  }
  SharpFeatures out;
  out.IsCorner.assign(np, 0);
  out.PointEdgeOffsets.assign(np + 1, 0);
  // The given corners and the points where the lines meet other than two at a time (a line's
  // end must be a corner for the sampler); no turn rule (cosLimit below -1).
  FindCorners(mesh, lines, -2.0, out, &flags);
  std::vector<std::int32_t> identity(nc);
  for (std::size_t c = 0; c < nc; ++c)
    identity[c] = static_cast<std::int32_t>(c);
  AddFeatureEdges(mesh, lines, identity, out);
  return out;
}

} // namespace av
