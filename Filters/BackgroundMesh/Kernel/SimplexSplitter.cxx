// SPDX-License-Identifier: BSD-3-Clause
#include "SimplexSplitter.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>

namespace av
{
namespace
{
// VTK cell type ids (vtkCellType.h), repeated here to stay VTK-free.
enum : int
{
  kTriangle = 5,
  kPixel = 8,
  kQuad = 9,
  kTetra = 10,
  kVoxel = 11,
  kHexahedron = 12,
  kWedge = 13,
  kPyramid = 14,
  kQuadraticTriangle = 22,
  kQuadraticQuad = 23,
  kQuadraticTetra = 24,
  kQuadraticHexahedron = 25,
  kQuadraticWedge = 26,
  kQuadraticPyramid = 27,
  kBiquadraticQuad = 28,
  kTriquadraticHexahedron = 29
};

/// Linear shape a supported type reduces to, its node count, and its dimension.
struct TypeInfo
{
  int Linear = -1; // kTriangle, kQuad, kTetra, kHexahedron, kWedge, kPyramid; -1 unsupported
  int Nodes = 0;
  int Dim = 0;
};

TypeInfo Info(int type)
{
  switch (type)
  {
    case kTriangle: return { kTriangle, 3, 2 };
    case kQuad: return { kQuad, 4, 2 };
    case kPixel: return { kQuad, 4, 2 };
    case kTetra: return { kTetra, 4, 3 };
    case kHexahedron: return { kHexahedron, 8, 3 };
    case kVoxel: return { kHexahedron, 8, 3 };
    case kWedge: return { kWedge, 6, 3 };
    case kPyramid: return { kPyramid, 5, 3 };
    case kQuadraticTriangle: return { kTriangle, 6, 2 };
    case kQuadraticQuad: return { kQuad, 8, 2 };
    case kBiquadraticQuad: return { kQuad, 9, 2 };
    case kQuadraticTetra: return { kTetra, 10, 3 };
    case kQuadraticHexahedron: return { kHexahedron, 20, 3 };
    case kTriquadraticHexahedron: return { kHexahedron, 27, 3 };
    case kQuadraticWedge: return { kWedge, 15, 3 };
    case kQuadraticPyramid: return { kPyramid, 13, 3 };
    default: return {};
  }
}

/// Splits quad (a, b, c, d) (cyclic) by the diagonal through its smallest id.
inline void SplitQuad(std::int64_t a, std::int64_t b, std::int64_t c, std::int64_t d,
  std::array<std::int64_t, 3>& t0, std::array<std::int64_t, 3>& t1)
{
  if (std::min(a, c) < std::min(b, d))
  {
    t0 = { a, b, c };
    t1 = { a, c, d };
  }
  else
  {
    t0 = { b, c, d };
    t1 = { b, d, a };
  }
}

class Splitter
{
public:
  Splitter(const double* points, int outDim)
    : P(points)
    , OutDim(outDim)
  {
  }

  const double* P;
  int OutDim;
  std::vector<std::int64_t> Simplices; // point ids (input ids, or -1 - k for added point k)
  std::vector<std::int32_t> Parent;
  std::vector<Eigen::Vector3d> Added;
  std::vector<std::array<std::int64_t, 8>> AddedParents;
  std::size_t Dropped = 0;

  Eigen::Vector3d X(std::int64_t id) const
  {
    if (id < 0)
    {
      return this->Added[static_cast<std::size_t>(-1 - id)];
    }
    return Eigen::Map<const Eigen::Vector3d>(this->P + 3 * id);
  }

  /// Adds a tet, positively oriented; drops it when its volume is negligible against scale^3.
  void Tet(std::int64_t a, std::int64_t b, std::int64_t c, std::int64_t d, std::int32_t cell,
    double scale)
  {
    const Eigen::Vector3d xa = this->X(a);
    const double det = (this->X(b) - xa).dot((this->X(c) - xa).cross(this->X(d) - xa));
    if (!(std::abs(det) > 1e-12 * scale * scale * scale))
    {
      ++this->Dropped;
      return;
    }
    if (det < 0.0)
    {
      std::swap(c, d);
    }
    this->Simplices.insert(this->Simplices.end(), { a, b, c, d });
    this->Parent.push_back(cell);
  }

  void Tri(std::int64_t a, std::int64_t b, std::int64_t c, std::int32_t cell, double scale)
  {
    const Eigen::Vector3d xa = this->X(a);
    const Eigen::Vector3d e1 = this->X(b) - xa, e2 = this->X(c) - xa;
    const double area2 = this->OutDim == 2 ? e1[0] * e2[1] - e1[1] * e2[0] : e1.cross(e2).norm();
    if (!(std::abs(area2) > 1e-12 * scale * scale))
    {
      ++this->Dropped;
      return;
    }
    if (area2 < 0.0)
    {
      std::swap(b, c);
    }
    this->Simplices.insert(this->Simplices.end(), { a, b, c });
    this->Parent.push_back(cell);
  }

  void Cell(int linear, const std::int64_t* v, std::int32_t cell)
  {
    const int nodes = linear == kTriangle ? 3
      : linear == kQuad || linear == kTetra ? 4
      : linear == kPyramid                  ? 5
      : linear == kWedge                    ? 6
                                            : 8;
    // Cell size, so that the degeneracy test is scale-free.
    Eigen::Vector3d lo = this->X(v[0]), hi = lo;
    for (int k = 1; k < nodes; ++k)
    {
      lo = lo.cwiseMin(this->X(v[k]));
      hi = hi.cwiseMax(this->X(v[k]));
    }
    const double scale = (hi - lo).norm();
    std::array<std::int64_t, 3> t0, t1;
    switch (linear)
    {
      case kTriangle:
        this->Tri(v[0], v[1], v[2], cell, scale);
        break;
      case kQuad:
        SplitQuad(v[0], v[1], v[2], v[3], t0, t1);
        this->Tri(t0[0], t0[1], t0[2], cell, scale);
        this->Tri(t1[0], t1[1], t1[2], cell, scale);
        break;
      case kTetra:
        this->Tet(v[0], v[1], v[2], v[3], cell, scale);
        break;
      case kPyramid:
        SplitQuad(v[0], v[1], v[2], v[3], t0, t1);
        this->Tet(t0[0], t0[1], t0[2], v[4], cell, scale);
        this->Tet(t1[0], t1[1], t1[2], v[4], cell, scale);
        break;
      case kWedge:
        this->Wedge(v, cell, scale);
        break;
      default:
        this->Hexahedron(v, cell, scale);
        break;
    }
  }

  void Wedge(const std::int64_t* v, std::int32_t cell, double scale)
  {
    // Relabel so that the smallest id is local vertex 0 (rotations of the triangles and the
    // top/bottom swap map a wedge onto itself).
    static const int perm[6][6] = { { 0, 1, 2, 3, 4, 5 }, { 1, 2, 0, 4, 5, 3 },
      { 2, 0, 1, 5, 3, 4 }, { 3, 5, 4, 0, 2, 1 }, { 4, 3, 5, 1, 0, 2 }, { 5, 4, 3, 2, 1, 0 } };
    const int m = static_cast<int>(std::min_element(v, v + 6) - v);
    std::int64_t w[6];
    for (int k = 0; k < 6; ++k)
    {
      w[k] = v[perm[m][k]];
    }
    // Faces through w0 are cut by diagonals from w0: tet (0, 3, 4, 5) + pyramid 0 / (1, 2, 5, 4).
    this->Tet(w[0], w[3], w[4], w[5], cell, scale);
    if (std::min(w[1], w[5]) < std::min(w[2], w[4]))
    {
      this->Tet(w[0], w[1], w[2], w[5], cell, scale);
      this->Tet(w[0], w[1], w[5], w[4], cell, scale);
    }
    else
    {
      this->Tet(w[0], w[1], w[2], w[4], cell, scale);
      this->Tet(w[0], w[4], w[2], w[5], cell, scale);
    }
  }

  void Hexahedron(const std::int64_t* v, std::int32_t cell, double scale)
  {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    std::array<std::int64_t, 8> parents;
    for (int k = 0; k < 8; ++k)
    {
      c += this->X(v[k]);
      parents[static_cast<std::size_t>(k)] = v[k];
    }
    this->Added.push_back(c / 8.0);
    this->AddedParents.push_back(parents);
    const std::int64_t center = -static_cast<std::int64_t>(this->Added.size());
    static const int faces[6][4] = { { 0, 3, 2, 1 }, { 4, 5, 6, 7 }, { 0, 1, 5, 4 },
      { 1, 2, 6, 5 }, { 2, 3, 7, 6 }, { 3, 0, 4, 7 } };
    std::array<std::int64_t, 3> t0, t1;
    for (const auto& f : faces)
    {
      SplitQuad(v[f[0]], v[f[1]], v[f[2]], v[f[3]], t0, t1);
      this->Tet(t0[0], t0[1], t0[2], center, cell, scale);
      this->Tet(t1[0], t1[1], t1[2], center, cell, scale);
    }
  }
};
} // namespace

std::string VtkCellTypeName(int type)
{
  switch (type)
  {
    case 0: return "VTK_EMPTY_CELL";
    case 1: return "VTK_VERTEX";
    case 2: return "VTK_POLY_VERTEX";
    case 3: return "VTK_LINE";
    case 4: return "VTK_POLY_LINE";
    case kTriangle: return "VTK_TRIANGLE";
    case 6: return "VTK_TRIANGLE_STRIP";
    case 7: return "VTK_POLYGON";
    case kPixel: return "VTK_PIXEL";
    case kQuad: return "VTK_QUAD";
    case kTetra: return "VTK_TETRA";
    case kVoxel: return "VTK_VOXEL";
    case kHexahedron: return "VTK_HEXAHEDRON";
    case kWedge: return "VTK_WEDGE";
    case kPyramid: return "VTK_PYRAMID";
    case 15: return "VTK_PENTAGONAL_PRISM";
    case 16: return "VTK_HEXAGONAL_PRISM";
    case 21: return "VTK_QUADRATIC_EDGE";
    case kQuadraticTriangle: return "VTK_QUADRATIC_TRIANGLE";
    case kQuadraticQuad: return "VTK_QUADRATIC_QUAD";
    case kQuadraticTetra: return "VTK_QUADRATIC_TETRA";
    case kQuadraticHexahedron: return "VTK_QUADRATIC_HEXAHEDRON";
    case kQuadraticWedge: return "VTK_QUADRATIC_WEDGE";
    case kQuadraticPyramid: return "VTK_QUADRATIC_PYRAMID";
    case kBiquadraticQuad: return "VTK_BIQUADRATIC_QUAD";
    case kTriquadraticHexahedron: return "VTK_TRIQUADRATIC_HEXAHEDRON";
    case 42: return "VTK_POLYHEDRON";
    default: return "cell type " + std::to_string(type);
  }
}

namespace
{
/// Checks the points and every cell first, so that the split itself cannot fail half-way;
/// returns the cells' dimension (2 or 3).
int ValidateCells(const double* points, std::size_t numPoints, const std::uint8_t* types,
  const std::int64_t* offsets, const std::int64_t* connectivity, std::size_t numCells,
  int outputAmbientDim)
{
  const std::string who = "SplitIntoSimplices: ";
  if (numCells == 0 || types == nullptr || offsets == nullptr)
  {
    throw InputError(who + "the dataset has no cells");
  }
  if (outputAmbientDim != 2 && outputAmbientDim != 3)
  {
    throw InputError(who + "the output ambient dimension must be 2 or 3");
  }
  if (numCells > 0x7fffffff || numPoints > 0x3fffffff)
  {
    throw InputError(who + "too many cells or points for 32-bit ids");
  }
  for (std::size_t i = 0; i < 3 * numPoints; ++i)
  {
    if (!std::isfinite(points[i]))
    {
      throw InputError(who + "point " + std::to_string(i / 3) + " has a NaN or infinite coordinate");
    }
  }
  int dim = 0;
  std::size_t firstDimCell = 0;
  for (std::size_t c = 0; c < numCells; ++c)
  {
    const TypeInfo info = Info(types[c]);
    if (info.Linear < 0)
    {
      throw InputError(who + "cell " + std::to_string(c) + " is a " + VtkCellTypeName(types[c]) +
        ", which cannot be split into simplices here (supported: triangles, quads, pixels, "
        "tetrahedra, hexahedra, voxels, wedges, pyramids and their quadratic versions)");
    }
    if (dim == 0)
    {
      dim = info.Dim;
      firstDimCell = c;
    }
    else if (info.Dim != dim)
    {
      throw InputError(who + "the dataset mixes 2D and 3D cells (cell " +
        std::to_string(firstDimCell) + " is " + VtkCellTypeName(types[firstDimCell]) +
        ", cell " + std::to_string(c) + " is " + VtkCellTypeName(types[c]) +
        "); extract the surface or the volume first");
    }
    const std::int64_t n = offsets[c + 1] - offsets[c];
    if (offsets[c] < 0 || n != info.Nodes)
    {
      throw InputError(who + "cell " + std::to_string(c) + " (" + VtkCellTypeName(types[c]) +
        ") has " + std::to_string(n) + " points, expected " + std::to_string(info.Nodes));
    }
    for (std::int64_t k = offsets[c]; k < offsets[c + 1]; ++k)
    {
      if (connectivity[k] < 0 || static_cast<std::size_t>(connectivity[k]) >= numPoints)
      {
        throw InputError(who + "cell " + std::to_string(c) + " references point " +
          std::to_string(connectivity[k]) + ", outside [0, " + std::to_string(numPoints) + ")");
      }
    }
  }

  return dim;
}

/// The split of the cells' linear corners (pixels and voxels reordered to VTK's hexahedron
/// order) into simplices.
void SplitCells(Splitter& s, const std::uint8_t* types, const std::int64_t* offsets,
  const std::int64_t* connectivity, std::size_t numCells, int dim)
{
  s.Simplices.reserve(numCells * (dim == 3 ? 12 * 4 : 6));
  for (std::size_t c = 0; c < numCells; ++c)
  {
    std::int64_t v[8];
    const std::int64_t* src = connectivity + offsets[c];
    const int type = types[c];
    const TypeInfo info = Info(type);
    const int corners = info.Linear == kTriangle ? 3
      : info.Linear == kQuad || info.Linear == kTetra ? 4
      : info.Linear == kPyramid                       ? 5
      : info.Linear == kWedge                         ? 6
                                                      : 8;
    std::copy(src, src + corners, v);
    if (type == kPixel) // pixel/voxel number their corners lexicographically
    {
      std::swap(v[2], v[3]);
    }
    else if (type == kVoxel)
    {
      std::swap(v[2], v[3]);
      std::swap(v[6], v[7]);
    }
    s.Cell(info.Linear, v, static_cast<std::int32_t>(c));
  }

}

/// The output: the used input points (in input order), then the added ones with their parent
/// weights, and the simplices on those ids.
SimplexSplitResult AssembleSplit(Splitter& s, const double* points, std::size_t numPoints,
  int outputAmbientDim, int dim)
{
  SimplexSplitResult r;
  r.NumDroppedSimplices = s.Dropped;
  r.NumAddedPoints = s.Added.size();
  r.CellParent = std::move(s.Parent);
  // Keep used input points (in input order), then the added ones.
  std::vector<std::int32_t> remap(numPoints, -1);
  for (std::int64_t id : s.Simplices)
  {
    if (id >= 0)
    {
      remap[static_cast<std::size_t>(id)] = 0;
    }
  }
  std::int32_t next = 0;
  SimplexMesh& m = r.Mesh;
  m.AmbientDim = outputAmbientDim;
  m.SimplexDim = dim;
  r.PointParentOffsets.push_back(0);
  for (std::size_t i = 0; i < numPoints; ++i)
  {
    if (remap[i] < 0)
    {
      r.InputPointsKept = false;
      continue;
    }
    remap[i] = next++;
    m.Points.insert(m.Points.end(), points + 3 * i, points + 3 * i + outputAmbientDim);
    r.PointParents.push_back(static_cast<std::int64_t>(i));
    r.PointWeights.push_back(1.0);
    r.PointParentOffsets.push_back(static_cast<std::int64_t>(r.PointParents.size()));
  }
  const std::int32_t firstAdded = next;
  for (std::size_t k = 0; k < s.Added.size(); ++k)
  {
    m.Points.insert(m.Points.end(), s.Added[k].data(), s.Added[k].data() + outputAmbientDim);
    for (std::int64_t p : s.AddedParents[k])
    {
      r.PointParents.push_back(p);
      r.PointWeights.push_back(1.0 / 8.0);
    }
    r.PointParentOffsets.push_back(static_cast<std::int64_t>(r.PointParents.size()));
  }
  m.Cells.resize(s.Simplices.size());
  for (std::size_t i = 0; i < s.Simplices.size(); ++i)
  {
    const std::int64_t id = s.Simplices[i];
    m.Cells[i] = id >= 0 ? remap[static_cast<std::size_t>(id)]
                         : firstAdded + static_cast<std::int32_t>(-1 - id);
  }
  return r;
}
} // namespace

SimplexSplitResult SplitIntoSimplices(const double* points, std::size_t numPoints,
  const std::uint8_t* types, const std::int64_t* offsets, const std::int64_t* connectivity,
  std::size_t numCells, int outputAmbientDim)
{
  const int dim = ValidateCells(
    points, numPoints, types, offsets, connectivity, numCells, outputAmbientDim);
  Splitter s(points, outputAmbientDim);
  SplitCells(s, types, offsets, connectivity, numCells, dim);
  SimplexSplitResult r = AssembleSplit(s, points, numPoints, outputAmbientDim, dim);
  if (r.Mesh.Cells.empty())
  {
    throw InputError("SplitIntoSimplices: every cell is degenerate (zero volume or area)");
  }
  return r;
}

} // namespace av
