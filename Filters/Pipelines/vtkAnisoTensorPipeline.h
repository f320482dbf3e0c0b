// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkAnisoTensorPipeline
 * @brief Abstract base of the one-click filters (vtkAnisoVoronoiCells, vtkAnisoAnisotropicMesh):
 * the common front of the paper's pipeline, from a tensor field to isotropic sites in R^m̄.
 *
 * Input: any vtkDataSet of 2D or 3D cells (hexahedra, quadratic cells, ... are split into
 * simplices) with a tensor array chosen with SetInputArrayToProcess(0, 0, 0, association,
 * name): 6 components (XX, YY, ZZ, XY, YZ, XZ) or 9. Default: the active point tensors.
 * - FieldMode TENSOR_FIELD (default): a point or cell physical tensor (stress, strain, ...)
 *   turned into a metric by vtkAnisoTensorToMetric (paper Eq. 20) with MinimumEigenvalue,
 *   MaximumAnisotropy and SmoothingIterations;
 *   and the metric preparation of vtkAnisoTensorToMetric for NumberOfCells output cells
 *   (SizeMode, SizeBlend, HMin, HMax, Gradation, GradationFactor; gradation on by default);
 * - FieldMode METRIC_FIELD: the point array already is an SPD metric (e.g. "Metric" of
 *   vtkAnisoAnalyticMetric) and is used as is (those three knobs are ignored);
 * - FieldMode AUTOMATIC: METRIC_FIELD when the array is a point array named "Metric" (the
 *   name every metric producer of this project gives: the analytic metric source and filter,
 *   vtkAnisoTensorToMetric, the Medit .sol reader), else TENSOR_FIELD. The mode that ran is
 *   told as a text message (vtkOutputWindow) and as the field-data string "FieldMode".
 * Front (run internally on a shallow copy of the input, never modifying it):
 * vtkAnisoSimplexMesh -> vtkAnisoTensorToMetric (TENSOR_FIELD) -> (AdaptBackgroundMesh)
 * vtkAnisoAdaptedBackgroundMesh (NumberOfCells sites, BackgroundEdgeLength) -> vtkAnisoEmbedding
 * (TargetDimension, Iterations, Seed) -> vtkAnisoParticleSampler (NumberOfCells sites,
 * SamplingIterations, Seed). Subclasses add the back end in RequestBackEnd. Progress of the
 * stages is forwarded; an error of any stage becomes this filter's error (RequestData
 * returns 0) naming the stage.
 */
#ifndef vtkAnisoTensorPipeline_h
#define vtkAnisoTensorPipeline_h

#include "AnisoVoronoiFiltersPipelinesModule.h" // export macro
#include <vtkSmartPointer.h> // RunMetricStages result
#include <vtkUnstructuredGridAlgorithm.h>

#include <string> // std::string

class vtkAlgorithm;
class vtkDataArray;
class vtkDataSet;
class vtkFieldData;
class vtkPolyData;
class vtkTable;

class ANISOVORONOIFILTERSPIPELINES_EXPORT vtkAnisoTensorPipeline : public vtkUnstructuredGridAlgorithm
{
public:
  vtkTypeMacro(vtkAnisoTensorPipeline, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum FieldModes
  {
    TENSOR_FIELD = 0, ///< physical tensor -> metric with vtkAnisoTensorToMetric
    METRIC_FIELD = 1, ///< the point array is the metric
    AUTOMATIC = 2     ///< METRIC_FIELD for a point array named "Metric", else TENSOR_FIELD
  };

  ///@{
  /// How the chosen array is read (default AUTOMATIC).
  vtkSetClampMacro(FieldMode, int, TENSOR_FIELD, AUTOMATIC);
  vtkGetMacro(FieldMode, int);
  void SetFieldModeToTensorField() { this->SetFieldMode(TENSOR_FIELD); }
  void SetFieldModeToMetricField() { this->SetFieldMode(METRIC_FIELD); }
  void SetFieldModeToAutomatic() { this->SetFieldMode(AUTOMATIC); }
  ///@}

  /// The mode of the last run (TENSOR_FIELD or METRIC_FIELD; AUTOMATIC resolved).
  vtkGetMacro(FieldModeUsed, int);

  ///@{
  /// Number of sites, i.e. of Voronoi cells / mesh vertices (default 2000; at most 8 x the
  /// number of points of the simplicial mesh).
  vtkSetClampMacro(NumberOfCells, int, 1, VTK_INT_MAX);
  vtkGetMacro(NumberOfCells, int);
  ///@}

  ///@{
  /// Embedding dimension m̄ (default 8, range 3..20, larger than the input's dimension).
  vtkSetClampMacro(TargetDimension, int, 3, 20);
  vtkGetMacro(TargetDimension, int);
  ///@}

  ///@{
  /// Embedding local/global iterations (default 50 as the paper).
  vtkSetClampMacro(Iterations, int, 0, 100000);
  vtkGetMacro(Iterations, int);
  ///@}

  ///@{
  /// Particle sampler L-BFGS iterations (default 150; the paper: 50).
  vtkSetClampMacro(SamplingIterations, int, 0, 100000);
  vtkGetMacro(SamplingIterations, int);
  ///@}

  ///@{
  /// Particle sampler warm-up iterations at a narrower kernel, run first (default 100; see
  /// vtkAnisoParticleSampler::WarmupIterations: 0 with 1000 or more SamplingIterations).
  vtkSetClampMacro(SamplingWarmupIterations, int, 0, 100000);
  vtkGetMacro(SamplingWarmupIterations, int);
  ///@}

  ///@{
  /// Sharp features (default on; see vtkAnisoParticleSampler::PreserveSharpFeatures): a fixed
  /// site at every corner, sites kept on the feature lines (dihedral angle > FeatureAngle).
  vtkSetMacro(PreserveSharpFeatures, bool);
  vtkGetMacro(PreserveSharpFeatures, bool);
  vtkBooleanMacro(PreserveSharpFeatures, bool);
  vtkSetClampMacro(FeatureAngle, double, 1e-3, 180.0);
  vtkGetMacro(FeatureAngle, double);
  /// Feature lines given as patch ids (surfaces; see vtkAnisoParticleSampler::FeaturePatchArray).
  vtkSetStringMacro(FeaturePatchArray);
  vtkGetStringMacro(FeaturePatchArray);
  ///@}

  ///@{
  /// TENSOR_FIELD: largest stretch ratio of the metric (default 10).
  vtkSetClampMacro(MaximumAnisotropy, double, 1.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MaximumAnisotropy, double);
  ///@}

  ///@{
  /// TENSOR_FIELD: eigenvalue floor relative to the field's largest |eigenvalue| (default
  /// 0.1). Smaller floors give size contrasts that coarse FE meshes cannot embed well.
  vtkSetClampMacro(MinimumEigenvalue, double, 1e-15, 1.0);
  vtkGetMacro(MinimumEigenvalue, double);
  ///@}

  ///@{
  /// TENSOR_FIELD: log-Euclidean smoothing passes of the metric (default 10).
  vtkSetClampMacro(SmoothingIterations, int, 0, 10000);
  vtkGetMacro(SmoothingIterations, int);
  ///@}

  ///@{
  /// TENSOR_FIELD: metric preparation (see vtkAnisoTensorToMetric): size mode (0 tensor,
  /// 1 uniform, 2 blend; default 0), blend exponent (0.5), size limits in the input's length
  /// units (0 = none), gradation (on) and its factor (MMG's hgrad, 1.3).
  vtkSetClampMacro(SizeMode, int, 0, 2);
  vtkGetMacro(SizeMode, int);
  vtkSetClampMacro(SizeBlend, double, 0.0, 1.0);
  vtkGetMacro(SizeBlend, double);
  vtkSetClampMacro(HMin, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(HMin, double);
  vtkSetClampMacro(HMax, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(HMax, double);
  /// Cells across thin parts (vtkAnisoTensorToMetric::MinCellsAcross, default 1.25, 0 = off).
  vtkSetClampMacro(MinCellsAcross, double, 0.0, 100.0);
  vtkGetMacro(MinCellsAcross, double);
  vtkSetMacro(Gradation, bool);
  vtkGetMacro(Gradation, bool);
  vtkBooleanMacro(Gradation, bool);
  vtkSetClampMacro(GradationFactor, double, 1.0001, 1000.0);
  vtkGetMacro(GradationFactor, double);
  /// Adapt the background mesh to the metric and NumberOfCells before the embedding
  /// (vtkAnisoAdaptedBackgroundMesh) with edges of at most BackgroundEdgeLength output edges
  /// (default 1.5): ADAPT_NEVER, ADAPT_ALWAYS, or ADAPT_WHEN_COARSE (default): in Tensor Field
  /// mode, when the mesh is coarser than the output (its mean edge longer than one output edge;
  /// a coarse FE mesh cannot carry the metric at the scale of the cells); a metric field keeps
  /// its mesh. SetAdaptBackgroundMesh(true / false) still means always / never.
  enum AdaptModes
  {
    ADAPT_NEVER = 0,
    ADAPT_ALWAYS = 1,
    ADAPT_WHEN_COARSE = 2
  };
  vtkSetClampMacro(AdaptBackgroundMesh, int, ADAPT_NEVER, ADAPT_WHEN_COARSE);
  vtkGetMacro(AdaptBackgroundMesh, int);
  vtkBooleanMacro(AdaptBackgroundMesh, int);
  vtkSetClampMacro(BackgroundEdgeLength, double, 1e-3, 10.0);
  vtkGetMacro(BackgroundEdgeLength, double);
  ///@}

  ///@{
  /// Seed of the embedding's initial field and of the sampling (default 1).
  vtkSetMacro(Seed, int);
  vtkGetMacro(Seed, int);
  ///@}

  /// Figures of the last run: average / largest edge length error (%) of the embedding and
  /// the total metric scale (tensor-to-metric scale x embedding scale).
  vtkGetMacro(AverageEdgeLengthError, double);
  vtkGetMacro(MaximumEdgeLengthError, double);
  vtkGetMacro(MetricScale, double);

protected:
  vtkAnisoTensorPipeline();
  ~vtkAnisoTensorPipeline() override;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// The back end: `embedded` (simplices + "Embedding" + "Metric"), `sites` (sampler
  /// output with "Metric"), `energy` (embedding energy table). Progress from 0.85 to 1.
  /// Returns 0 after vtkErrorMacro on failure.
  virtual int RequestBackEnd(vtkUnstructuredGrid* embedded, vtkPolyData* sites, vtkTable* energy,
    vtkInformationVector* outputVector) = 0;

  /// Runs `stage` (inputs already set) with progress mapped to [begin, end] of this filter
  /// and its errors captured; false (message in `error`, prefixed by `what`) on failure.
  bool RunStage(vtkAlgorithm* stage, const char* what, double begin, double end, std::string& error);

  /// The field array of the run, looked up on a shallow copy of `input` (an unnamed one gets a
  /// name there): its name and association (points for MetricField). False after
  /// vtkErrorMacro when it is missing or of the wrong kind.
  bool ChooseFieldArray(vtkInformationVector** inputVector, vtkDataSet* input,
    vtkSmartPointer<vtkDataSet>& copy, std::string& arrayName, int& association);

  /// Simplex split, then (TensorField) tensor to metric: the simplicial mesh with the point
  /// metric `metricName` active; `tensorScale` is the tensor-to-metric scale. Null after
  /// vtkErrorMacro on failure.
  vtkSmartPointer<vtkDataSet> RunMetricStages(vtkDataSet* input, const std::string& arrayName,
    int association, std::string& metricName, double& tensorScale);

  /// FieldMode with AUTOMATIC resolved for the chosen array (null: the active point tensors);
  /// sets FieldModeReason.
  int ResolveFieldMode(vtkDataArray* chosen, int association, vtkDataSet* input);

  /// Adds the front's figures (L_avg, L_max, MetricScale, the FieldMode string, and against the
  /// raw metric L_avg_raw, L_max_raw with the preparation's deviation figures when it ran) to a
  /// field data.
  void AddFrontFieldData(vtkFieldData* fd) const;

  /// The name users see (the ParaView label): messages of the inner stages are re-issued
  /// under it, so that they name the filter the user applied.
  virtual const char* GetUserLabel() const = 0;

  int FieldMode = AUTOMATIC;
  int FieldModeUsed = TENSOR_FIELD;
  std::string FieldModeReason;
  int NumberOfCells = 2000;
  int TargetDimension = 8;
  int Iterations = 50;
  int SamplingIterations = 150;
  int SamplingWarmupIterations = 100;
  bool PreserveSharpFeatures = true;
  double FeatureAngle = 30.0;
  char* FeaturePatchArray = nullptr;
  double MaximumAnisotropy = 10.0;
  double MinimumEigenvalue = 0.1;
  int SmoothingIterations = 10;
  int SizeMode = 0;
  double SizeBlend = 0.5;
  double HMin = 0.0;
  double HMax = 0.0;
  double MinCellsAcross = 1.25;
  bool Gradation = true;
  double GradationFactor = 1.3;
  int AdaptBackgroundMesh = ADAPT_WHEN_COARSE;
  double BackgroundEdgeLength = 1.5;
  int Seed = 1;

  double AverageEdgeLengthError = 0.0;
  double MaximumEdgeLengthError = 0.0;
  double MetricScale = 1.0;
  double FrontFigures[6] = { -1, -1, -1, -1, -1, -1 }; ///< raw L_avg/L_max, deviation; -1 = none

private:
  vtkAnisoTensorPipeline(const vtkAnisoTensorPipeline&) = delete;
  void operator=(const vtkAnisoTensorPipeline&) = delete;
};

#endif
