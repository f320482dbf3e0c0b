// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkAnisoEmbedding
 * @brief The paper's core step: a self-intersection free embedding of a mesh in R^m̄ whose
 * pull-back metric matches a given metric field (paper §3, Alg. 1).
 *
 * Input: a triangle 2D domain (z = 0), a triangle surface or a tetrahedral volume, with a
 * symmetric metric point array (6 components XX, YY, ZZ, XY, YZ, XZ, or 9), chosen with
 * SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, name); by default
 * the active point tensors, else an array named "Metric". Metrics must be SPD (positive
 * semi-definite rank 2 on surfaces); eigenvalues below 1 cannot be matched by an embedding
 * that only adds coordinates, so with AutoScaleMetric (default on) the whole field is
 * multiplied by c = 1 / (smallest eigenvalue) as in the paper §6 and c is reported.
 *
 * Output 0 (vtkUnstructuredGrid): the input mesh and its point data, plus
 * - "Embedding": m̄-component point array, the embedded coordinates (first m = input coords);
 * - "EdgeLengthError": per-cell largest relative edge length error (%) of the paper §5.1;
 * - field data "L_avg", "L_max" (%), "MetricScale" (c), "EmbeddingDimension",
 *   "EmbeddingIterations", "EmbeddingConverged", "IterativeSolve", "FactorSeconds",
 *   "SolveSeconds", "DoublePrecisionRetries", "EmbeddingSeconds", "CellsAboveErrorThreshold",
 *   "InputBodies" (cells connected through shared points; more than one gets a warning);
 *   when the input has the point array "RawMetric" (left by the metric preparation of
 *   vtkAnisoTensorToMetric: the unprepared metric at the same complexity), also "L_avg_raw",
 *   "L_max_raw": the same errors measured with it.
 * When cells have an error above ErrorWarningThreshold, a warning gives their number and the
 * worst cell's id, location and error (the embedding could not fit the metric there).
 * Output 1 (vtkTable): per iteration (0 = initial state) E_em, E_reg, E_total — chartable.
 *
 * Solver: local step per element (polar factor of a small SVD, parallel), global step with
 * one sparse Cholesky factorisation (CHOLMOD) and one multi-right-hand-side solve per
 * iteration, or (large meshes) AMG-preconditioned conjugate gradients; a smooth random start and energy-safeguarded Anderson acceleration (the energy
 * never increases). Filters/Embedding/README.md gives the details and measured figures.
 *
 * Distributed runs (mpiexec pvbatch, pvserver): needs the whole mesh, so it asks its inputs
 * for the whole dataset and runs redundantly on every process that needs its output (the cost
 * is not divided); the whole result goes to piece 0 and the other pieces are empty, so that
 * gathering the pieces gives one copy. See Documentation/parallel.md.
 */
#ifndef vtkAnisoEmbedding_h
#define vtkAnisoEmbedding_h

#include "AnisoVoronoiFiltersEmbeddingModule.h" // export macro
#include <vtkUnstructuredGridAlgorithm.h>

class ANISOVORONOIFILTERSEMBEDDING_EXPORT vtkAnisoEmbedding : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkAnisoEmbedding* New();
  vtkTypeMacro(vtkAnisoEmbedding, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Initializations
  {
    SMOOTH = 0,
    RANDOM = 1,
    METRIC_ALIGNED = 2
  };

  enum ElementMetrics
  {
    VERTEX_MEAN = 0,
    EDGE_LENGTHS = 1
  };

  enum GlobalSolvers
  {
    AUTOMATIC_SOLVER = 0,
    DIRECT_SOLVER = 1,
    ITERATIVE_SOLVER = 2
  };

  ///@{
  /// Target dimension m̄ (default 8; 3 is enough for the Gaussian 2D case). Range 3..20 and
  /// larger than the input's dimension.
  vtkSetClampMacro(TargetDimension, int, 3, 20);
  vtkGetMacro(TargetDimension, int);
  ///@}

  ///@{
  /// Local/global iterations always run (default 50 as the paper).
  vtkSetClampMacro(Iterations, int, 0, 100000);
  vtkGetMacro(Iterations, int);
  ///@}

  ///@{
  /// Run to convergence: after Iterations, go on while L_avg is above TargetAverageError and
  /// the energy still drops by more than
  /// ConvergenceTolerance (default 1e-4) per iteration on average over the last 10, up to
  /// MaxIterations in all (default 500; <= Iterations: exactly Iterations). High-stretch inputs
  /// need hundreds of iterations; converged ones stop at Iterations.
  vtkSetClampMacro(MaxIterations, int, 0, 100000);
  vtkGetMacro(MaxIterations, int);
  vtkSetClampMacro(ConvergenceTolerance, double, 0.0, 1.0);
  vtkGetMacro(ConvergenceTolerance, double);
  ///@}

  ///@{
  /// Past Iterations, stop as soon as L_avg (%) is at or below this (default 2, the paper's
  /// grade; 0 = only ConvergenceTolerance and MaxIterations stop the run). Inputs that fit at
  /// Iterations stop there, as before.
  vtkSetClampMacro(TargetAverageError, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(TargetAverageError, double);
  ///@}

  ///@{
  /// Global-step solver: AUTOMATIC_SOLVER (default: direct below 20,000 vertices for tet meshes
  /// and 150,000 for triangle meshes, iterative from there), DIRECT_SOLVER (sparse Cholesky,
  /// memory ~n^1.3) or ITERATIVE_SOLVER (conjugate gradients with an algebraic-multigrid V-cycle
  /// on a hypre BoomerAMG hierarchy, warm-started, memory linear in n).
  vtkSetClampMacro(GlobalSolver, int, AUTOMATIC_SOLVER, ITERATIVE_SOLVER);
  vtkGetMacro(GlobalSolver, int);
  ///@}

  ///@{
  /// Cells whose largest edge length error (%) exceeds this are counted and the worst one is
  /// named in a warning (default 50, the paper's L_max grade; 0 = no warning).
  vtkSetClampMacro(ErrorWarningThreshold, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(ErrorWarningThreshold, double);
  ///@}

  ///@{
  /// Regularization weight μ (default 100 as the paper).
  vtkSetClampMacro(Mu, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Mu, double);
  ///@}

  ///@{
  /// Measure the regularizer in units of the input's largest bounding-box extent, so that μ
  /// means the same for a part in millimetres and in metres; off (default): in the input's own
  /// length unit, as the paper prints it (its inputs are unit-sized; a part given in mm is then
  /// regularized 10^6 times more strongly than the same part in m). On: lower L_avg on large-unit
  /// inputs, worse final meshes on the coarse real volumes (Filters/Embedding/README.md).
  vtkSetMacro(ScaleFreeRegularizer, bool);
  vtkGetMacro(ScaleFreeRegularizer, bool);
  vtkBooleanMacro(ScaleFreeRegularizer, bool);
  ///@}

  ///@{
  /// Seed of the random initial field (default 1): same seed, same result.
  vtkSetMacro(Seed, int);
  vtkGetMacro(Seed, int);
  ///@}

  ///@{
  /// Stop early when the relative energy decrease of an iteration is below this (0 = off).
  vtkSetClampMacro(RelativeEnergyTolerance, double, 0.0, 1.0);
  vtkGetMacro(RelativeEnergyTolerance, double);
  ///@}

  ///@{
  /// Weight each element's term by its measure (off = the paper's unweighted Eq. 11).
  vtkSetMacro(ElementMeasureWeighting, bool);
  vtkGetMacro(ElementMeasureWeighting, bool);
  vtkBooleanMacro(ElementMeasureWeighting, bool);
  ///@}

  ///@{
  /// The constant metric each element is fitted to: VERTEX_MEAN (default), the average of the
  /// element's vertex metrics (paper-notes.md); or EDGE_LENGTHS, the metric whose lengths of the
  /// element's edges are the paper's §5.1 edge lengths, so that neighbours agree on every shared
  /// edge (elements far from any such metric blend towards the mean). EDGE_LENGTHS gives a lower
  /// L_avg on every preset and real volume measured but worse final meshes on every real case
  /// (Filters/Embedding/README.md, "Element metric").
  vtkSetClampMacro(ElementMetric, int, VERTEX_MEAN, EDGE_LENGTHS);
  vtkGetMacro(ElementMetric, int);
  ///@}

  ///@{
  /// Initial extra coordinates: METRIC_ALIGNED (default: the first extra coordinates fitted to
  /// (M - I)^{1/2}, almost isometric at once where the stretch directions do not turn, e.g.
  /// boundary layers; SMOOTH where that fit is poor; av::EmbeddingInitialization), a SMOOTH
  /// low-frequency random field, or the paper's i.i.d. small RANDOM perturbation.
  vtkSetClampMacro(Initialization, int, SMOOTH, METRIC_ALIGNED);
  vtkGetMacro(Initialization, int);
  ///@}

  ///@{
  /// Anderson acceleration window (default 5; 0 = plain local/global iterations).
  vtkSetClampMacro(AndersonWindow, int, 0, 20);
  vtkGetMacro(AndersonWindow, int);
  ///@}

  ///@{
  /// Global-step solves with a single-precision, multi-threaded copy of the Cholesky factor
  /// (default on: about half the memory traffic of the solves, which dominate an iteration).
  /// A step whose energy would rise from the float rounding is redone in double, so the energy
  /// still never increases. Off: CHOLMOD's double-precision solve throughout.
  vtkSetMacro(SinglePrecisionSolve, bool);
  vtkGetMacro(SinglePrecisionSolve, bool);
  vtkBooleanMacro(SinglePrecisionSolve, bool);
  ///@}

  ///@{
  /// Bodies of the input (parts with no shared point, as in a contact assembly) are moved apart
  /// along the last embedding coordinate (default on), so that the sampler, the Voronoi cells
  /// and the mesh treat each as its own domain: no cell spans two bodies. Lengths inside a body
  /// do not change. Off: they stay where the solve leaves them, touching where they touch.
  vtkSetMacro(SeparateBodies, bool);
  vtkGetMacro(SeparateBodies, bool);
  vtkBooleanMacro(SeparateBodies, bool);
  ///@}

  ///@{
  /// Multiply the metric by c = 1/λmin when λmin < 1 (paper §6). Default on; when off, such a
  /// metric is an error.
  vtkSetMacro(AutoScaleMetric, bool);
  vtkGetMacro(AutoScaleMetric, bool);
  vtkBooleanMacro(AutoScaleMetric, bool);
  ///@}

  ///@{
  /// Name of the output embedding array (default "Embedding").
  vtkSetStringMacro(EmbeddingArrayName);
  vtkGetStringMacro(EmbeddingArrayName);
  ///@}

  /// Figures of the last run (also in the output's field data).
  vtkGetMacro(AverageEdgeLengthError, double);
  vtkGetMacro(MaximumEdgeLengthError, double);
  vtkGetMacro(MetricScale, double);
  vtkGetMacro(CellsAboveErrorThreshold, vtkIdType);
  vtkGetMacro(NumberOfInputBodies, vtkIdType);

protected:
  vtkAnisoEmbedding();
  ~vtkAnisoEmbedding() override;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int TargetDimension = 8;
  int Iterations = 50;
  int MaxIterations = 500;
  double ConvergenceTolerance = 1e-4;
  double TargetAverageError = 2.0;
  int GlobalSolver = AUTOMATIC_SOLVER;
  double ErrorWarningThreshold = 50.0;
  double Mu = 100.0;
  bool ScaleFreeRegularizer = false;
  int Seed = 1;
  double RelativeEnergyTolerance = 0.0;
  bool ElementMeasureWeighting = false;
  int ElementMetric = VERTEX_MEAN;
  int Initialization = METRIC_ALIGNED;
  int AndersonWindow = 5;
  bool SinglePrecisionSolve = true;
  bool SeparateBodies = true;
  bool AutoScaleMetric = true;
  char* EmbeddingArrayName = nullptr;

  double AverageEdgeLengthError = 0.0;
  double MaximumEdgeLengthError = 0.0;
  double MetricScale = 1.0;
  vtkIdType CellsAboveErrorThreshold = 0;
  vtkIdType NumberOfInputBodies = 0;

private:
  vtkAnisoEmbedding(const vtkAnisoEmbedding&) = delete;
  void operator=(const vtkAnisoEmbedding&) = delete;
};

#endif
