// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkAnisoTetMesher
 * @brief Quality tetrahedral background mesh (TetGen) of a closed surface, a box or a ball.
 *
 * Shape INPUT_SURFACE (default): the input vtkPolyData must be a closed, manifold triangle
 * surface (triangulate it first if it has polygons); its enclosed volume is meshed. Shape BOX
 * meshes the input's bounding box (or [0,1]^3 without input), BALL the ball of the given Radius
 * centered at Center.
 *
 * Size: TargetVertices (> 0) asks for about that many vertices (typically within 15 %); else
 * MaxVolume (> 0) bounds every tet's volume; with neither, TetGen's quality mesh of the
 * surface's own points. RadiusEdgeRatio (> 1, default 1.5) is TetGen's -q quality bound.
 *
 * Output: vtkUnstructuredGrid of positively oriented VTK_TETRA cells, no point data (compute
 * the metric afterwards, e.g. with vtkAnisoAnalyticMetric or by resampling a tensor field).
 */
#ifndef vtkAnisoTetMesher_h
#define vtkAnisoTetMesher_h

#include "AnisoVoronoiFiltersBackgroundMeshModule.h" // export macro
#include <vtkUnstructuredGridAlgorithm.h>

class ANISOVORONOIFILTERSBACKGROUNDMESH_EXPORT vtkAnisoTetMesher : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkAnisoTetMesher* New();
  vtkTypeMacro(vtkAnisoTetMesher, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Shapes
  {
    INPUT_SURFACE = 0,
    BOX = 1,
    BALL = 2
  };

  ///@{
  /// What to mesh (default INPUT_SURFACE).
  vtkSetClampMacro(Shape, int, INPUT_SURFACE, BALL);
  vtkGetMacro(Shape, int);
  void SetShapeToInputSurface() { this->SetShape(INPUT_SURFACE); }
  void SetShapeToBox() { this->SetShape(BOX); }
  void SetShapeToBall() { this->SetShape(BALL); }
  ///@}

  ///@{
  /// Approximate number of output vertices (0 = use MaxVolume). Default 10000.
  vtkSetClampMacro(TargetVertices, int, 0, 50000000);
  vtkGetMacro(TargetVertices, int);
  ///@}

  ///@{
  /// Upper bound on tet volume when TargetVertices is 0 (0 = none).
  vtkSetClampMacro(MaxVolume, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MaxVolume, double);
  ///@}

  ///@{
  /// TetGen's radius-edge quality bound (> 1; default 1.5).
  vtkSetClampMacro(RadiusEdgeRatio, double, 1.05, 10.0);
  vtkGetMacro(RadiusEdgeRatio, double);
  ///@}

  ///@{
  /// Ball center and radius (Shape BALL; default origin and 1).
  vtkSetVector3Macro(Center, double);
  vtkGetVector3Macro(Center, double);
  vtkSetClampMacro(Radius, double, 1e-300, VTK_DOUBLE_MAX);
  vtkGetMacro(Radius, double);
  ///@}

protected:
  vtkAnisoTetMesher();
  ~vtkAnisoTetMesher() override = default;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Shape = INPUT_SURFACE;
  int TargetVertices = 10000;
  double MaxVolume = 0.0;
  double RadiusEdgeRatio = 1.5;
  double Center[3] = { 0, 0, 0 };
  double Radius = 1.0;

private:
  vtkAnisoTetMesher(const vtkAnisoTetMesher&) = delete;
  void operator=(const vtkAnisoTetMesher&) = delete;
};

#endif
