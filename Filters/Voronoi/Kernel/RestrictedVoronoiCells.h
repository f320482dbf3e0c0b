// SPDX-License-Identifier: BSD-3-Clause
// RestrictedVoronoiCells: the RVD drawn as cells in input space (one glued polyhedron / polygon
// per site, or one per piece), shrunk about their centroids, with their faces and face kinds.
#ifndef av_RestrictedVoronoiCells_h
#define av_RestrictedVoronoiCells_h

#include "RestrictedVoronoi.h"
#include "SimplexMesh.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace av
{

/// Options of BuildRestrictedVoronoiCells.
struct RestrictedVoronoiCellOptions
{
  /// One cell per site (the diagram must then come from RestrictedVoronoiOptions::MergeBySite:
  /// pieces sorted by site, no element faces) or one per piece (a diagram without it).
  bool MergeBySite = true;
  /// Every cell is scaled about its vertex centroid by this factor (1: none).
  double ShrinkFactor = 1.0;
  /// Polled every 1024 sites while merging; true stops the build (the cells so far are kept).
  std::function<bool()> Abort;
};

/**
 * Cells in input space (z = 0 in 2D). Points are not shared between cells: the points of cell c
 * are CellPointOffsets[c]..[c+1], in the order of a VTK_POLYHEDRON's point list. Faces (3D:
 * polygons, outward; 2D: edges) are listed per cell, with global point ids. 2D cells also have
 * their polygon as one counter-clockwise loop (LoopPoints).
 *
 * Merged cells: the pieces of a site are glued by the symbolic identity of their vertices
 * (bisector sites + mesh vertices of the sub-simplex they lie on), element faces are dropped
 * and so are the points only they used. A 2D site whose kept edges are not one simple loop
 * (a hole, several components) comes out as one polygon per piece instead.
 */
struct RestrictedVoronoiCells
{
  int SimplexDim = 3;

  std::vector<double> Points; ///< NumPoints x 3

  // Per cell.
  std::vector<std::int64_t> CellPointOffsets; ///< NumCells + 1
  std::vector<std::int64_t> CellFaceOffsets;  ///< NumCells + 1, into the faces
  std::vector<std::int64_t> CellLoopOffsets;  ///< NumCells + 1 into LoopPoints (2D only)
  std::vector<std::int64_t> LoopPoints;       ///< 2D polygons, point ids
  std::vector<std::int32_t> CellSite;
  std::vector<std::int32_t> CellElement; ///< element of a piece, -1 for a merged cell
  std::vector<double> CellMeasure;         ///< input space, times ShrinkFactor^k
  std::vector<double> CellEmbeddedMeasure; ///< in R^Dim, times ShrinkFactor^k

  // Per face (3D) / edge (2D).
  std::vector<std::int64_t> FaceOffsets;  ///< NumFaces + 1 into FaceVertices
  std::vector<std::int64_t> FaceVertices; ///< point ids
  std::vector<RVDFaceKind> FaceKind;
  std::vector<std::int32_t> FaceNeighbor; ///< the other site of a bisector, else -1

  std::size_t NumNonEmptySites = 0; ///< sites with at least one piece
  double TotalMeasure = 0.0;        ///< sum of the (unshrunk) piece measures
  double DomainMeasure = 0.0;       ///< measure of the input mesh
  bool Aborted = false;             ///< options.Abort stopped the build

  std::size_t NumCells() const { return CellSite.size(); }
  std::size_t NumPoints() const { return Points.size() / 3; }
  std::size_t NumFaces() const { return FaceKind.size(); }
};

/**
 * The cells of `rvd` (computed with ComputeGeometry on) on `mesh`. Faces are oriented outward
 * in input space: pieces of elements with negative orientation (tets, flat triangles) are
 * reversed.
 */
RestrictedVoronoiCells BuildRestrictedVoronoiCells(const SimplexMesh& mesh,
  const RestrictedVoronoiDiagram& rvd,
  const RestrictedVoronoiCellOptions& options = RestrictedVoronoiCellOptions());

} // namespace av

#endif
