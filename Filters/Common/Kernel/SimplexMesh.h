// SPDX-License-Identifier: BSD-3-Clause
// SimplexMesh: the plain, VTK-free mesh type every kernel of AnisoVoronoi works on.
#ifndef av_SimplexMesh_h
#define av_SimplexMesh_h

#include "InputError.h" // every kernel that takes a SimplexMesh may throw it
#include <algorithm>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{

/**
 * A simplicial mesh: triangles (SimplexDim 2) or tetrahedra (SimplexDim 3) whose
 * vertices live in R^AmbientDim (2 for a flat 2D domain, 3 for a surface or a volume).
 * Points are stored row-major (NumPoints x AmbientDim), cells row-major
 * (NumCells x (SimplexDim + 1)) with 0-based point ids.
 */
struct SimplexMesh
{
  int AmbientDim = 3;
  int SimplexDim = 3;
  std::vector<double> Points;
  std::vector<std::int32_t> Cells;

  std::size_t NumPoints() const { return Points.size() / static_cast<std::size_t>(AmbientDim); }
  std::size_t NumCells() const { return Cells.size() / static_cast<std::size_t>(SimplexDim + 1); }
  int VerticesPerCell() const { return SimplexDim + 1; }
  const double* Point(std::size_t i) const { return Points.data() + i * AmbientDim; }
  const std::int32_t* Cell(std::size_t c) const { return Cells.data() + c * (SimplexDim + 1); }
};

/// Axis-aligned bounds of the mesh points (AmbientDim entries of lo and hi; +-1e300 when empty).
inline void PointBounds(const SimplexMesh& mesh, double lo[3], double hi[3])
{
  for (int d = 0; d < 3; ++d)
  {
    lo[d] = 1e300;
    hi[d] = -1e300;
  }
  for (std::size_t i = 0; i < mesh.NumPoints(); ++i)
  {
    for (int d = 0; d < mesh.AmbientDim; ++d)
    {
      lo[d] = std::min(lo[d], mesh.Point(i)[d]);
      hi[d] = std::max(hi[d], mesh.Point(i)[d]);
    }
  }
}

/// The largest extent of the mesh's bounding box (0 for an empty mesh or a single point).
inline double LargestExtent(const SimplexMesh& mesh)
{
  double lo[3], hi[3], ext = 0.0;
  PointBounds(mesh, lo, hi);
  for (int d = 0; d < mesh.AmbientDim; ++d)
  {
    ext = std::max(ext, hi[d] - lo[d]);
  }
  return ext;
}

/**
 * A symmetric metric per mesh vertex, always stored as a full 3x3 symmetric tensor in
 * VTK's 6-component order (XX, YY, ZZ, XY, YZ, XZ). For a flat 2D domain only the XX, YY,
 * XY entries are used. On a surface the metric may be rank 2 (zero along the normal).
 */
struct MetricField
{
  std::vector<double> Values; // NumPoints x 6

  std::size_t NumPoints() const { return Values.size() / 6; }
  const double* At(std::size_t i) const { return Values.data() + 6 * i; }
};

/**
 * The vertices of a SimplexMesh mapped into R^Dim (the high-dimensional embedding).
 * Coords is row-major NumPoints x Dim; its first AmbientDim columns equal the input
 * coordinates, so mapping back to input space is "keep the first AmbientDim values".
 */
struct Embedding
{
  int Dim = 8;
  std::vector<double> Coords;

  std::size_t NumPoints() const { return Coords.size() / static_cast<std::size_t>(Dim); }
  const double* At(std::size_t i) const { return Coords.data() + i * Dim; }
};

/**
 * Points that live on (or in) a SimplexMesh, e.g. particles / Voronoi sites. Each has its
 * embedded position (Dim values), the mesh cell that contains it and its barycentric
 * coordinates in that cell (always 4 values; the 4th is 0 for triangles).
 */
struct SiteSet
{
  int Dim = 8;
  std::vector<double> Coords;        // NumSites x Dim
  std::vector<std::int32_t> CellIds; // NumSites
  std::vector<double> Bary;          // NumSites x 4

  std::size_t NumSites() const { return CellIds.size(); }
  const double* At(std::size_t i) const { return Coords.data() + i * Dim; }
};

} // namespace av

#endif
