// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkAnisoTriangulateDomain
 * @brief Triangulates a flat 2D domain (the background mesh of a 2D metric) at a target size.
 *
 * Input: a vtkPolyData in the z = 0 plane. Its polygons (or closed polylines) are the domain
 * boundary; a polygon inside another is a hole (vtkDelaunay2D's boundary convention: outer
 * loops counter-clockwise, holes clockwise). Without polygons or lines the xy bounding
 * rectangle of the points is triangulated.
 *
 * Output: a vtkPolyData of near-equilateral triangles (boundary resampled at the target edge
 * length, interior points on an equilateral lattice, constrained Delaunay triangulation), all
 * with z = 0 and counter-clockwise orientation, ready for the metric and embedding filters.
 *
 * Parameters: TargetEdgeLength (> 0; 0 = bounding-box diagonal / 50).
 */
#ifndef vtkAnisoTriangulateDomain_h
#define vtkAnisoTriangulateDomain_h

#include "AnisoVoronoiFiltersBackgroundMeshModule.h" // export macro
#include <vtkPolyDataAlgorithm.h>

class ANISOVORONOIFILTERSBACKGROUNDMESH_EXPORT vtkAnisoTriangulateDomain : public vtkPolyDataAlgorithm
{
public:
  static vtkAnisoTriangulateDomain* New();
  vtkTypeMacro(vtkAnisoTriangulateDomain, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Target triangle edge length; 0 (default) picks the bounding-box diagonal / 50.
  vtkSetClampMacro(TargetEdgeLength, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(TargetEdgeLength, double);
  ///@}

protected:
  vtkAnisoTriangulateDomain();
  ~vtkAnisoTriangulateDomain() override = default;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double TargetEdgeLength = 0.0;

private:
  vtkAnisoTriangulateDomain(const vtkAnisoTriangulateDomain&) = delete;
  void operator=(const vtkAnisoTriangulateDomain&) = delete;
};

#endif
