// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkAnisoAnalyticMetric
 * @brief Adds one of the paper's closed-form metric fields to any dataset's points.
 *
 * Output = input (shallow copy) plus point arrays "Metric" (6-component symmetric tensor,
 * VTK order XX, YY, ZZ, XY, YZ, XZ) and "Stretch" (the stretch ratio S >= 1). Every preset
 * has the form M = I + (S^2 - 1) u u^T (stretch S along the unit direction u):
 *
 * - Gaussian2D (2D domain [-1,1]^2): M = I + grad h grad h^T, h = a exp(-(x^2+y^2)/(2 s^2)),
 *   s = 0.3, a = 1.83893, so S spans [1, 3.85] (paper Fig. 4); (x, y, h) is an exact embedding.
 * - Cube1 ([0,1]^3): M = diag(S^2, 1, 1), S = 1 + 9x (paper: "S = 10x, S in [1, 10]").
 * - Cube2 ([0,1]^3): M = diag(S^2, 1, 1), S = 0.2 (0.0025 + 0.2 (1 - e^{-|x-0.5|}))^{-0.8}.
 * - Cube3 ([1,11]^3): S = 2 (0.1 + 2 (1 - e^{-0.01 |x^2+y^2-49|}))^{-1} along the radial
 *   direction (x/r, y/r, 0).
 * - SphereCylindrical (unit ball): S = 1 + 4 sqrt(x^2+y^2) along (x/r, y/r, 0).
 * - SphereCosine (unit ball): S = 10 along normalize(2 cos 4x, 1, 0).
 *
 * Filters/Metric/README.md explains the readings chosen where the paper's formulas are
 * garbled. Points with a non-finite coordinate make RequestData fail.
 */
#ifndef vtkAnisoAnalyticMetric_h
#define vtkAnisoAnalyticMetric_h

#include "AnisoVoronoiFiltersMetricModule.h" // export macro
#include <vtkDataSetAlgorithm.h>

class ANISOVORONOIFILTERSMETRIC_EXPORT vtkAnisoAnalyticMetric : public vtkDataSetAlgorithm
{
public:
  static vtkAnisoAnalyticMetric* New();
  vtkTypeMacro(vtkAnisoAnalyticMetric, vtkDataSetAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Presets
  {
    GAUSSIAN_2D = 0,
    CUBE1 = 1,
    CUBE2 = 2,
    CUBE3 = 3,
    SPHERE_CYLINDRICAL = 4,
    SPHERE_COSINE = 5
  };

  ///@{
  /// Which closed-form field (default CUBE1).
  vtkSetClampMacro(Preset, int, GAUSSIAN_2D, SPHERE_COSINE);
  vtkGetMacro(Preset, int);
  void SetPresetToGaussian2D() { this->SetPreset(GAUSSIAN_2D); }
  void SetPresetToCube1() { this->SetPreset(CUBE1); }
  void SetPresetToCube2() { this->SetPreset(CUBE2); }
  void SetPresetToCube3() { this->SetPreset(CUBE3); }
  void SetPresetToSphereCylindrical() { this->SetPreset(SPHERE_CYLINDRICAL); }
  void SetPresetToSphereCosine() { this->SetPreset(SPHERE_COSINE); }
  ///@}

  /// Selects a preset by its short name (gaussian2d, cube1, cube2, cube3, sphere-cyl,
  /// sphere-cos); returns false (and keeps the preset) for an unknown name.
  bool SetPresetByName(const char* name);

  ///@{
  /// Name of the output metric array (default "Metric").
  vtkSetStringMacro(MetricArrayName);
  vtkGetStringMacro(MetricArrayName);
  ///@}

protected:
  vtkAnisoAnalyticMetric();
  ~vtkAnisoAnalyticMetric() override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Preset = CUBE1;
  char* MetricArrayName = nullptr;

private:
  vtkAnisoAnalyticMetric(const vtkAnisoAnalyticMetric&) = delete;
  void operator=(const vtkAnisoAnalyticMetric&) = delete;
};

#endif
