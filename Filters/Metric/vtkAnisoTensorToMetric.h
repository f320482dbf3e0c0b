// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkAnisoTensorToMetric
 * @brief Turns a physical tensor field (stress, strain rate, diffusion, ...) into the SPD metric
 * field the embedding needs (paper §6.4, Eq. 20).
 *
 * Input: any vtkDataSet with a symmetric tensor array of 6 components (VTK order XX, YY, ZZ,
 * XY, YZ, XZ, as vtkMath::TensorFromSymmetricTensor) or 9 (row-major 3x3), chosen with
 * SetInputArrayToProcess(0, 0, 0, association, name). Default: the active point tensors, else
 * the active cell tensors. A non-symmetric 9-component tensor is replaced by its symmetric part
 * (T + T^T) / 2 with a warning giving the largest relative asymmetry.
 *
 * Cell tensors are first averaged to the points (the embedding needs point metrics): each point
 * gets the plain mean of the tensors of the cells that use it (as vtkCellDataToPointData does).
 * Points used by no cell get the identity metric.
 *
 * Per point T = V diag(lambda) V^T, f(lambda) = |lambda| (EigenvalueMode ABSOLUTE) or
 * max(lambda, floor) (CLAMP), floored at MinimumEigenvalue x the largest |lambda| of the field;
 * EIGENVALUES_AS_STRETCH (default, Eq. 20): M = V diag(f^2) V^T; TENSOR_AS_METRIC:
 * M = V diag(f) V^T. The per-point anisotropy is capped at MaximumAnisotropy, the field is
 * optionally smoothed (log-Euclidean, over the mesh edges of the input cells, any cell type)
 * and, with ApplyGlobalScale, multiplied by c = 1 / (smallest eigenvalue) so that every
 * eigenvalue is >= 1 (paper §6).
 *
 * Output: the input (shallow copy) plus point arrays
 * - "Metric" (MetricArrayName): 6 components, set as the active tensors; for a 2D problem
 *   (Dimension 2) only XX, YY, XY are non-zero;
 * - "Stretch": the stretch ratio s_max / s_min (>= 1);
 * and field data "MetricScale" (c), "MaxAsymmetry", "NumNegative" (points with a negative
 * eigenvalue), "NumClamped" (points with an eigenvalue raised to the floor), "NumCapped"
 * (points whose anisotropy was capped), "StretchMin", "StretchMax".
 *
 * On a triangle surface in 3D (every cell a triangle, the points not all at one z) with
 * ProjectOntoSurface on (default), each tensor is first restricted to the tangent plane at
 * its point (unit vertex normals, Max's weights): the metric is rank 2, zero along the normal,
 * and its stretch, floor and cap see the tangent eigenvalues only (av::TangentTensorToMetric).
 * Smoothing is then refused (smooth the tensors first).
 *
 * Errors (RequestData returns 0): no tensor array, not 6/9 components, NaN/Inf values, an
 * all-zero field, invalid option values.
 */
#ifndef vtkAnisoTensorToMetric_h
#define vtkAnisoTensorToMetric_h

#include "AnisoVoronoiFiltersMetricModule.h" // export macro
#include <vtkDataSetAlgorithm.h>

#include <string> // private helpers
#include <vector> // private helpers

#ifndef __VTK_WRAP__
namespace av
{
struct SimplexMesh;
struct TensorToMetricOptions;
struct TensorToMetricResult;
}
#endif

class ANISOVORONOIFILTERSMETRIC_EXPORT vtkAnisoTensorToMetric : public vtkDataSetAlgorithm
{
public:
  static vtkAnisoTensorToMetric* New();
  vtkTypeMacro(vtkAnisoTensorToMetric, vtkDataSetAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Interpretations
  {
    EIGENVALUES_AS_STRETCH = 0, ///< paper Eq. 20: M = V diag(f(lambda)^2) V^T
    TENSOR_AS_METRIC = 1        ///< M = V diag(f(lambda)) V^T
  };

  enum EigenvalueModes
  {
    ABSOLUTE = 0, ///< f(lambda) = |lambda|
    CLAMP = 1     ///< f(lambda) = max(lambda, floor)
  };

  enum Dimensions
  {
    DIMENSION_AUTO = 0, ///< 2 when every point has the same z, else 3
    DIMENSION_2D = 2,
    DIMENSION_3D = 3
  };

  ///@{
  /// How the tensor becomes a metric (default EIGENVALUES_AS_STRETCH).
  vtkSetClampMacro(Interpretation, int, EIGENVALUES_AS_STRETCH, TENSOR_AS_METRIC);
  vtkGetMacro(Interpretation, int);
  void SetInterpretationToEigenvaluesAsStretch()
  {
    this->SetInterpretation(EIGENVALUES_AS_STRETCH);
  }
  void SetInterpretationToTensorAsMetric() { this->SetInterpretation(TENSOR_AS_METRIC); }
  ///@}

  ///@{
  /// What negative eigenvalues become (default ABSOLUTE).
  vtkSetClampMacro(EigenvalueMode, int, ABSOLUTE, CLAMP);
  vtkGetMacro(EigenvalueMode, int);
  void SetEigenvalueModeToAbsolute() { this->SetEigenvalueMode(ABSOLUTE); }
  void SetEigenvalueModeToClamp() { this->SetEigenvalueMode(CLAMP); }
  ///@}

  ///@{
  /// Floor on f(lambda) relative to the largest |lambda| of the field, in (0, 1] (default 1e-3).
  vtkSetClampMacro(MinimumEigenvalue, double, 1e-15, 1.0);
  vtkGetMacro(MinimumEigenvalue, double);
  ///@}

  ///@{
  /// Cap on s_max / s_min per point; 0 = no cap, else >= 1 (default 25).
  vtkSetClampMacro(MaximumAnisotropy, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MaximumAnisotropy, double);
  ///@}

  ///@{
  /// Log-Euclidean Laplacian smoothing iterations over the mesh edges (default 0 = off).
  vtkSetClampMacro(SmoothingIterations, int, 0, 10000);
  vtkGetMacro(SmoothingIterations, int);
  ///@}

  ///@{
  /// DIMENSION_AUTO (default), DIMENSION_2D (only XX, YY, XY are read and written) or
  /// DIMENSION_3D.
  vtkSetClampMacro(Dimension, int, DIMENSION_AUTO, DIMENSION_3D);
  vtkGetMacro(Dimension, int);
  void SetDimensionToAuto() { this->SetDimension(DIMENSION_AUTO); }
  void SetDimensionTo2D() { this->SetDimension(DIMENSION_2D); }
  void SetDimensionTo3D() { this->SetDimension(DIMENSION_3D); }
  ///@}

  ///@{
  /// On a triangle surface, restrict each tensor to the tangent plane first (default on).
  vtkSetMacro(ProjectOntoSurface, bool);
  vtkGetMacro(ProjectOntoSurface, bool);
  vtkBooleanMacro(ProjectOntoSurface, bool);
  ///@}

  /// True when the last update projected the tensors onto the surface's tangent planes.
  vtkGetMacro(UsedTangentProjection, bool);

  ///@{
  /// Scale the field by c = 1 / (smallest eigenvalue) when that is < 1 (default on).
  vtkSetMacro(ApplyGlobalScale, bool);
  vtkGetMacro(ApplyGlobalScale, bool);
  vtkBooleanMacro(ApplyGlobalScale, bool);
  ///@}

  ///@{
  /// Name of the output metric array (default "Metric").
  vtkSetStringMacro(MetricArrayName);
  vtkGetStringMacro(MetricArrayName);
  ///@}

  ///@{
  /// Figures of the last run (also in the output's field data).
  vtkGetMacro(MetricScale, double);
  vtkGetMacro(MaxAsymmetry, double);
  vtkGetMacro(NumberOfNegativeTuples, vtkIdType);
  vtkGetMacro(NumberOfClampedTuples, vtkIdType);
  vtkGetMacro(NumberOfCappedTuples, vtkIdType);
  vtkGetMacro(StretchMin, double);
  vtkGetMacro(StretchMax, double);
  /// The dimension used by the last run (2 or 3).
  vtkGetMacro(UsedDimension, int);
  ///@}

protected:
  vtkAnisoTensorToMetric();
  ~vtkAnisoTensorToMetric() override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Interpretation = EIGENVALUES_AS_STRETCH;
  int EigenvalueMode = ABSOLUTE;
  double MinimumEigenvalue = 1e-3;
  double MaximumAnisotropy = 25.0;
  int SmoothingIterations = 0;
  int Dimension = DIMENSION_AUTO;
  bool ApplyGlobalScale = true;
  bool ProjectOntoSurface = true;
  bool UsedTangentProjection = false;
  char* MetricArrayName = nullptr;

  double MetricScale = 1.0;
  double MaxAsymmetry = 0.0;
  vtkIdType NumberOfNegativeTuples = 0;
  vtkIdType NumberOfClampedTuples = 0;
  vtkIdType NumberOfCappedTuples = 0;
  double StretchMin = 0.0;
  double StretchMax = 0.0;
  int UsedDimension = 3;

private:
#ifndef __VTK_WRAP__
  vtkDataArray* FindTensors(
    vtkInformationVector** inputVector, vtkDataSet* input, bool& cellTensors, std::string& error);
  bool BuildOptions(vtkDataSet* input, av::TensorToMetricOptions& options, std::string& error);
  bool TupleNormals(const av::SimplexMesh& surface, const std::vector<vtkIdType>& used,
    std::vector<double>& normals, std::string& error);
  void WriteOutput(const av::TensorToMetricResult& result, const std::vector<vtkIdType>& used,
    bool cellTensors, int dimension, vtkDataSet* output);
#endif
  vtkAnisoTensorToMetric(const vtkAnisoTensorToMetric&) = delete;
  void operator=(const vtkAnisoTensorToMetric&) = delete;
};

#endif
