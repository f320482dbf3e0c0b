// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkAnisoSimplexMesh
 * @brief Splits every non-simplex cell into conforming triangles/tetrahedra, as the embedding
 * and Voronoi filters need.
 *
 * Input: any vtkDataSet of 2D cells (triangle, quad, pixel, quadratic triangle/quad,
 * biquadratic quad) or of 3D cells (tetrahedron, hexahedron, voxel, wedge, pyramid and their
 * quadratic versions, triquadratic hexahedron); vertex and line cells are ignored with a
 * warning. Mixed 2D/3D cells and other types (polygons, polyhedra, ...) are errors that name
 * the type.
 *
 * Splitting (Kernel/SimplexSplitter.h): quadrilateral faces are cut by the diagonal through their
 * smallest point id, so neighboring cells agree and the result is conforming; wedges give 3
 * tetrahedra, pyramids 2, quads 2 triangles; hexahedra and voxels get one new point at their
 * center and 12 tetrahedra. Quadratic cells are reduced to their corner nodes (mid-edge nodes
 * are dropped, curved edges become straight). Tetrahedra come out positively oriented.
 *
 * Output (vtkUnstructuredGrid):
 * - the simplices; point data: every input point array, interpolated to the added center points
 *   with the parent weights (the mean of the 8 corners); input points keep their ids when no
 *   point is dropped;
 * - cell data: every input cell array copied from the parent cell, plus "ParentCellId";
 * - field data "SplitSummary" (one string), e.g. "split 560 VTK_QUADRATIC_HEXAHEDRON into
 *   6720 tetrahedra (560 center points added, ...)". When something was split the summary is
 *   also printed with vtkWarningMacro so that users notice.
 * Input that is already all triangles or all tetrahedra passes through unchanged (same points,
 * cells and ids; ParentCellId = cell id).
 */
#ifndef vtkAnisoSimplexMesh_h
#define vtkAnisoSimplexMesh_h

#include "AnisoVoronoiFiltersBackgroundMeshModule.h" // export macro
#include <vtkUnstructuredGridAlgorithm.h>

#include <string> // SplitSummary

class ANISOVORONOIFILTERSBACKGROUNDMESH_EXPORT vtkAnisoSimplexMesh : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkAnisoSimplexMesh* New();
  vtkTypeMacro(vtkAnisoSimplexMesh, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Print the summary with vtkWarningMacro when cells were split (default on).
  vtkSetMacro(ReportSplit, bool);
  vtkGetMacro(ReportSplit, bool);
  vtkBooleanMacro(ReportSplit, bool);
  ///@}

  /// The summary of the last run (also the "SplitSummary" field data).
  const char* GetSplitSummary() const { return this->SplitSummary.c_str(); }

  ///@{
  /// Figures of the last run: input cells that were split, output simplices, added points.
  vtkGetMacro(NumberOfSplitCells, vtkIdType);
  vtkGetMacro(NumberOfOutputSimplices, vtkIdType);
  vtkGetMacro(NumberOfAddedPoints, vtkIdType);
  ///@}

protected:
  vtkAnisoSimplexMesh();
  ~vtkAnisoSimplexMesh() override = default;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  bool ReportSplit = true;
  std::string SplitSummary;
  vtkIdType NumberOfSplitCells = 0;
  vtkIdType NumberOfOutputSimplices = 0;
  vtkIdType NumberOfAddedPoints = 0;

private:
  vtkAnisoSimplexMesh(const vtkAnisoSimplexMesh&) = delete;
  void operator=(const vtkAnisoSimplexMesh&) = delete;
};

#endif
