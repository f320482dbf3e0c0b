// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkAnisoAnalyticMetricSource
 * @brief The paper's test cases ready to embed: the preset's domain meshed, with its metric.
 *
 * Output: a vtkUnstructuredGrid with the domain of the chosen preset (see
 * vtkAnisoAnalyticMetric for the formulas) and the "Metric" / "Stretch" point arrays:
 * - boxes (Cube1/2/3): a Kuhn tetrahedral grid (6 tets per grid cube) with the paper's sizes,
 *   21^3 = 9,261 vertices for Cube1 and 101 x 21 x 21 = 44,541 for Cube2/Cube3 (Tab. 5);
 * - balls (SphereCylindrical, SphereCosine): a TetGen quality mesh of about 50,000 vertices;
 * - Gaussian2D: a 101 x 101 triangle grid of [-1,1]^2 in the plane z = 0.
 *
 * Resolution (0 = the sizes above) sets the number of vertices along the shortest box side
 * (Cube2/3 keep their 5:1 aspect along x), or the ball's vertex count is scaled to about
 * Resolution^3 vertices. Use it to measure cost from 10k to 1M vertices.
 */
#ifndef vtkAnisoAnalyticMetricSource_h
#define vtkAnisoAnalyticMetricSource_h

#include "AnisoVoronoiFiltersMetricModule.h" // export macro
#include <vtkUnstructuredGridAlgorithm.h>

class ANISOVORONOIFILTERSMETRIC_EXPORT vtkAnisoAnalyticMetricSource : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkAnisoAnalyticMetricSource* New();
  vtkTypeMacro(vtkAnisoAnalyticMetricSource, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Which preset (vtkAnisoAnalyticMetric::Presets; default CUBE1).
  vtkSetClampMacro(Preset, int, 0, 5);
  vtkGetMacro(Preset, int);
  ///@}

  /// Selects a preset by name (gaussian2d, cube1, cube2, cube3, sphere-cyl, sphere-cos).
  bool SetPresetByName(const char* name);

  ///@{
  /// Vertices along the shortest side (boxes / 2D) or cube root of the ball's vertex count;
  /// 0 (default) = the paper's mesh sizes. Range 0 or [3, 400].
  vtkSetClampMacro(Resolution, int, 0, 400);
  vtkGetMacro(Resolution, int);
  ///@}

protected:
  vtkAnisoAnalyticMetricSource();
  ~vtkAnisoAnalyticMetricSource() override = default;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Preset = 1;
  int Resolution = 0;

private:
  vtkAnisoAnalyticMetricSource(const vtkAnisoAnalyticMetricSource&) = delete;
  void operator=(const vtkAnisoAnalyticMetricSource&) = delete;
};

#endif
