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
 * Metric preparation (MMG's -hmin/-hmax/-hgrad, Alauzet 2010; see av::PrepareMetric and the
 * Metric README), on by default: SizeMode (TENSOR sizes from the tensor; UNIFORM unit
 * determinant, shape only; BLEND det^SizeBlend), normalization to NumberOfSites output cells
 * (unit metric length = one output cell; 0 keeps the tensor's scale), size limits HMin / HMax
 * (input length units, 0 = off) and Gradation (growth per unit metric length bounded by
 * GradationFactor, MMG's hgrad), all in those cell units. With ApplyGlobalScale (default) the
 * normalization factor is then divided out again, so the output keeps the scale the embedding
 * is tuned for (field data "CellUnitScale" multiplies it back into cell units); without, the
 * output is in cell units. Cells of the
 * highest dimension are split into simplices for the complexity integral; the gradation runs on
 * the cell edges. Adds the point array "RawMetric" (the unprepared metric scaled to the same
 * complexity, for the embedding's L_avg against it) and field data "MetricPrepMedianChange",
 * "MetricPrepP95Change", "MetricPrepMaxChange", "MetricPrepChangedFraction" (relative change of
 * length along the raw eigenvectors, see av::MetricDeviation), "MetricComplexity",
 * "ImpliedSites", "NumGraded", "NumHMinClamped", "NumHMaxClamped".
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

#include <cstdint> // private helpers
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

  enum SizeModes
  {
    SIZE_FROM_TENSOR = 0, ///< sizes and shapes from the tensor
    SIZE_UNIFORM = 1,     ///< unit determinant: equal-size cells whose shape shows the tensor
    SIZE_BLEND = 2        ///< det M = det(M_tensor)^SizeBlend
  };

  ///@{
  /// Where the sizes come from (default SIZE_FROM_TENSOR).
  vtkSetClampMacro(SizeMode, int, SIZE_FROM_TENSOR, SIZE_BLEND);
  vtkGetMacro(SizeMode, int);
  void SetSizeModeToTensor() { this->SetSizeMode(SIZE_FROM_TENSOR); }
  void SetSizeModeToUniform() { this->SetSizeMode(SIZE_UNIFORM); }
  void SetSizeModeToBlend() { this->SetSizeMode(SIZE_BLEND); }
  ///@}

  ///@{
  /// SIZE_BLEND: exponent in [0, 1] of det(M_tensor) kept by the sizes (default 0.5).
  vtkSetClampMacro(SizeBlend, double, 0.0, 1.0);
  vtkGetMacro(SizeBlend, double);
  ///@}

  ///@{
  /// Output cells the metric is prepared for: normalized so that its complexity holds that many
  /// unit vertices (default 2000, the composite filters' default); 0 = keep the tensor's scale.
  vtkSetClampMacro(NumberOfSites, int, 0, VTK_INT_MAX);
  vtkGetMacro(NumberOfSites, int);
  ///@}

  ///@{
  /// Smallest / largest size in the input's length units (default 0 = no limit).
  vtkSetClampMacro(HMin, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(HMin, double);
  vtkSetClampMacro(HMax, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(HMax, double);
  ///@}

  ///@{
  /// Volumes and flat 2D domains: at least this many cells across thin parts of the domain
  /// (av::MetricPreparationOptions::MinCellsAcross, chords along 13 directions; default 1.25,
  /// 0 = off). Field data "CellsAcross" (lowered where the thin parts alone would need more
  /// than NumberOfSites) and "NumThicknessLimited".
  vtkSetClampMacro(MinCellsAcross, double, 0.0, 100.0);
  vtkGetMacro(MinCellsAcross, double);
  ///@}

  ///@{
  /// Bounded size growth per unit metric length (default on) with factor GradationFactor
  /// (MMG's hgrad, > 1, default 1.3).
  vtkSetMacro(Gradation, bool);
  vtkGetMacro(Gradation, bool);
  vtkBooleanMacro(Gradation, bool);
  vtkSetClampMacro(GradationFactor, double, 1.0001, 1000.0);
  vtkGetMacro(GradationFactor, double);
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
  /// Metric preparation of the last run (0 when it did not run): median / 95th percentile of
  /// the relative length change against the raw metric, fraction of points changed by more
  /// than 5 %, sites the prepared metric asks for, points the gradation changed.
  vtkGetMacro(MedianChange, double);
  vtkGetMacro(Percentile95Change, double);
  vtkGetMacro(ChangedFraction, double);
  vtkGetMacro(ImpliedSites, double);
  vtkGetMacro(NumberOfGradedPoints, vtkIdType);
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
  int SizeMode = SIZE_FROM_TENSOR;
  double SizeBlend = 0.5;
  int NumberOfSites = 2000;
  double HMin = 0.0;
  double HMax = 0.0;
  double MinCellsAcross = 1.25;
  bool Gradation = true;
  double GradationFactor = 1.3;

  double MetricScale = 1.0;
  double MaxAsymmetry = 0.0;
  vtkIdType NumberOfNegativeTuples = 0;
  vtkIdType NumberOfClampedTuples = 0;
  vtkIdType NumberOfCappedTuples = 0;
  double StretchMin = 0.0;
  double StretchMax = 0.0;
  int UsedDimension = 3;
  double MedianChange = 0.0;
  double Percentile95Change = 0.0;
  double ChangedFraction = 0.0;
  double ImpliedSites = 0.0;
  vtkIdType NumberOfGradedPoints = 0;
  double CellUnitScale = 1.0; ///< factor from the output metric to cell units
  double PreparationFigures[7] = { 0, 0, 0, 0, 0, 0, 0 }; ///< max change, complexity, clamps, sweeps, thickness

private:
#ifndef __VTK_WRAP__
  vtkDataArray* FindTensors(
    vtkInformationVector** inputVector, vtkDataSet* input, bool& cellTensors, std::string& error);
  bool BuildOptions(vtkDataSet* input, av::TensorToMetricOptions& options, std::string& error);
  bool TupleNormals(const av::SimplexMesh& surface, const std::vector<vtkIdType>& used,
    std::vector<double>& normals, std::string& error);
  void WriteOutput(const av::TensorToMetricResult& result, const std::vector<vtkIdType>& used,
    bool cellTensors, int dimension, vtkDataSet* output);
  bool PreparationRequested() const;
  bool Prepare(vtkDataSet* input, const std::vector<std::int32_t>& pointToTuple,
    const std::vector<std::int32_t>& edges, int dimension, av::TensorToMetricResult& result,
    std::vector<double>& rawMetric);
#endif
  vtkAnisoTensorToMetric(const vtkAnisoTensorToMetric&) = delete;
  void operator=(const vtkAnisoTensorToMetric&) = delete;
};

#endif
