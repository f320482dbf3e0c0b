// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkAnisoCurvatureMetric
 * @brief The curvature-adapted metric of a triangle surface (paper Eq. 19), from the surface
 * alone.
 *
 * Input: a triangle surface in 3D (vtkPolyData or any vtkDataSet whose cells are triangles;
 * vertex/line cells are ignored). Polygons, quads and strips are errors: triangulate first
 * (vtkTriangleFilter, ParaView: Triangulate). Faces should be consistently oriented. Points used
 * by no triangle get a zero metric (with a warning).
 *
 * Principal curvatures/directions per vertex from per-face second fundamental form fits
 * averaged over the one-ring (Kernel/SurfaceCurvatureMetric.h); stretches s1 = sqrt|K_min|,
 * s2 = sqrt|K_max| with |K| floored at CurvatureThreshold / (bounding-box diagonal), Laplacian
 * smoothing of the stretches and directions (SmoothingIterations), the ratio s2 / s1 capped at
 * MaxStretch, then M = v_min v_min^T + (s2/s1)^2 v_max v_max^T (rank 2, zero along the normal;
 * smallest tangent eigenvalue 1, so no global scale is needed).
 *
 * Output: the input (shallow copy) plus point arrays "Metric" (6 components XX, YY, ZZ, XY, YZ,
 * XZ, the active tensors), "Stretch" (s2 / s1), "KMin", "KMax" (signed principal curvatures of
 * smaller / larger magnitude), "VMin", "VMax" (unit principal directions), and field data
 * "CurvatureFloor" (the absolute |K| floor used) and "CreaseEdges" (edges sharper than CreaseAngle).
 *
 * Parameters: CurvatureThreshold (default 0.1, > 0), SmoothingIterations (default 5),
 * MaxStretch (default 10; 0 = no cap, else >= 1), CreaseAngle (default 180 = none; normal
 * differences are not taken across sharper edges).
 */
#ifndef vtkAnisoCurvatureMetric_h
#define vtkAnisoCurvatureMetric_h

#include "AnisoVoronoiFiltersMetricModule.h" // export macro
#include <vtkDataSetAlgorithm.h>

class ANISOVORONOIFILTERSMETRIC_EXPORT vtkAnisoCurvatureMetric : public vtkDataSetAlgorithm
{
public:
  static vtkAnisoCurvatureMetric* New();
  vtkTypeMacro(vtkAnisoCurvatureMetric, vtkDataSetAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Floor on |K| relative to 1 / (bounding-box diagonal) (default 0.1).
  vtkSetClampMacro(CurvatureThreshold, double, 1e-12, VTK_DOUBLE_MAX);
  vtkGetMacro(CurvatureThreshold, double);
  ///@}

  ///@{
  /// One-ring smoothing iterations of the stretches and directions (default 5).
  vtkSetClampMacro(SmoothingIterations, int, 0, 10000);
  vtkGetMacro(SmoothingIterations, int);
  ///@}

  ///@{
  /// Cap on the stretch ratio s2 / s1 (default 10; 0 = no cap, else >= 1).
  vtkSetClampMacro(MaxStretch, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MaxStretch, double);
  ///@}

  ///@{
  /// Edges whose two triangles' normals differ by more than this (degrees) are creases: the
  /// curvature is not estimated across them, so a sharp CAD edge does not read as a huge
  /// curvature (default 180 = off, the surface is smooth everywhere; 30 = the sampler's
  /// FeatureAngle).
  vtkSetClampMacro(CreaseAngle, double, 1e-3, 180.0);
  vtkGetMacro(CreaseAngle, double);
  ///@}

  ///@{
  /// Name of the output metric array (default "Metric").
  vtkSetStringMacro(MetricArrayName);
  vtkGetStringMacro(MetricArrayName);
  ///@}

protected:
  vtkAnisoCurvatureMetric();
  ~vtkAnisoCurvatureMetric() override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double CurvatureThreshold = 0.1;
  int SmoothingIterations = 5;
  double MaxStretch = 10.0;
  double CreaseAngle = 180.0;
  char* MetricArrayName = nullptr;

private:
  vtkAnisoCurvatureMetric(const vtkAnisoCurvatureMetric&) = delete;
  void operator=(const vtkAnisoCurvatureMetric&) = delete;
};

#endif
