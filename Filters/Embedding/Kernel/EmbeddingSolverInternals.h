// SPDX-License-Identifier: BSD-3-Clause
// EmbeddingSolver::Internals: the solver's state and steps (internal: defined in EmbeddingSetup,
// EmbeddingAssembly, EmbeddingLocalStep and EmbeddingIterations.cxx).
#ifndef av_EmbeddingSolverInternals_h
#define av_EmbeddingSolverInternals_h

#include "EdgeLengthError.h"
#include "EmbeddingSolver.h"
#include "FloatSupernodalSolver.h"
#include "IterativeGlobalSolver.h"

#include <Eigen/CholmodSupport> // the double-precision factor (Cholesky below)
#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace av
{

class AndersonAcceleration;

/// Largest target dimension m̄ (the bound of the fixed-capacity Eigen types of the local step).
constexpr int kEmbeddingMaxTargetDim = 20;

/// Fixed chunking of element / vertex loops: partial sums are added in chunk order, so energies
/// do not depend on the number of threads.
constexpr std::size_t kEmbeddingChunk = 2048;

struct EmbeddingSolver::Internals
{
  EmbeddingOptions Options;
  int M = 3;  // ambient dimension
  int K = 3;  // simplex dimension
  int MB = 8; // target dimension
  int F = 5;  // free dimensions
  std::size_t NP = 0, NE = 0, NR = 0;
  std::vector<std::int32_t> Cells;
  std::vector<double> Gt;      // NE x (K+1) x M: linear FEM gradient operator, T row d = x^d . Gt
  std::vector<double> A;       // NE x M x M: symmetric sqrt of the element metric
  std::vector<double> W;       // NE: element weights
  std::vector<std::int32_t> VOff, VInc; // vertex -> (element * (K+1) + local) CSR
  std::vector<std::int32_t> NOff, NIdx; // one-ring neighbors CSR
  std::vector<char> Interior;           // regularizer rows
  std::vector<std::int32_t> Pinned;     // vertex -> pinned (smallest) vertex of its component
  std::vector<std::int32_t> Reduced;    // vertex -> unknown index, -1 when pinned
  std::vector<double> X;                // NP x MB row-major: the embedding
  double RegularizerScale = 1.0;        // 1 / ℓ² with ScaleFreeRegularizer, else 1
  std::vector<double> C;                // NE x (K+1) x F: per-element right-hand sides
  struct Cholesky : Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower>
  {
    /// Stored entries of the supernodal factor (fill-in diagnostic).
    std::size_t FactorSize() const
    {
      return this->m_cholmodFactor ? static_cast<std::size_t>(this->m_cholmodFactor->xsize) : 0;
    }
    const cholmod_factor* Factor() const { return this->m_cholmodFactor; }
  };
  Cholesky Chol;
  std::unique_ptr<FloatSupernodalSolver> FloatSolver; // SinglePrecisionSolve
  std::unique_ptr<IterativeGlobalSolver> Iterative;   // EmbeddingGlobalSolver::Iterative
  // Automatic picked the iterative solver: K (with its values) kept to factor it if CG
  // converges slowly.
  Eigen::SparseMatrix<double> SwitchK;
  bool SwitchedToDirect = false;
  IterativeSolveStatistics SwitchedStatistics; // of the iterative solves before the switch
  SimplexMesh ErrorMesh; // a copy for ErrorTarget (the caller's mesh may not outlive us)
  std::vector<std::int32_t> PointBody; // LabelBodies, for SeparateBodies
  std::size_t NumBodies = 1;
  std::size_t ElementMetricFallbacks = 0; // EmbeddingElementMetric::EdgeLengths
  std::unique_ptr<EdgeLengthErrorEvaluator> ErrorTarget; // TargetAverageErrorPercent > 0
  Eigen::MatrixXd LastRhs;                            // right-hand sides of the last global step
  EmbeddingEnergy Energy;
  double SetupSeconds = 0.0, FactorSeconds = 0.0;
  mutable double LocalSeconds = 0.0, SolveSeconds = 0.0;
  std::size_t FactorNonZeros = 0;
  bool Ran = false;
  bool Stalled = false; // a plain step could not lower the energy even solved accurately
  // MetricAligned start only (freed after it): targets, element eigenvectors, sqrt(λ - 1).
  std::vector<Eigen::Matrix3d> AlignedTarget, AlignedFrames;
  std::vector<Eigen::Vector3d> AlignedRoots;

  // Setup (EmbeddingSetup.cxx).
  void Validate(const SimplexMesh& mesh, const MetricField& metric);
  void BuildElements(const SimplexMesh& mesh, const MetricField& metric);
  void BuildTopology(const SimplexMesh& mesh);
  void InitializeState(const SimplexMesh& mesh);

  // Assembly (EmbeddingAssembly.cxx).
  struct ColumnScatter;
  /// Lower triangle of K, column by column; values = false: the pattern only (needs only the
  /// topology, so the ordering can be computed while the element operators are built).
  void AssembleLower(bool values, Eigen::SparseMatrix<double>& kmat, std::vector<double>* vals);
  void AddElementEntries(std::size_t c, bool values, ColumnScatter& scatter) const;
  void AddRegularizerEntries(std::size_t c, ColumnScatter& scatter) const;
  /// Throws a clear InputError when the symbolic analysis left no factor (CHOLMOD's status).
  void RequireAnalysis(const Eigen::SparseMatrix<double>& kmat);
  /// The numeric factorization after the checks: analysis present, memory for the factor.
  void FactorOnce(const Eigen::SparseMatrix<double>& kmat);
  /// Numeric factorization (after the symbolic analysis, which took analyseSeconds of waiting).
  void Factor(
    Eigen::SparseMatrix<double>& kmat, const std::vector<double>& vals, double analyseSeconds);
  /// Throws when the last double-precision CHOLMOD solve failed.
  void RequireSolved();
  /// K without its entries between vertices that share no element, their magnitudes added to
  /// the diagonal: the SPD matrix the iterative solver's AMG hierarchy is built on.
  Eigen::SparseMatrix<double> ElementAdjacentPart(const Eigen::SparseMatrix<double>& kmat) const;
  /// Builds the iterative solver instead of the factorization (kmat: the pattern, vals: values).
  void SetupIterative(Eigen::SparseMatrix<double>& kmat, const std::vector<double>& vals);
  /// CHOLMOD's fill-reducing ordering for K: nested dissection (see the constructor).
  void UseNestedDissection()
  {
    this->Chol.cholmod().nmethods = 1;
    this->Chol.cholmod().method[0].ordering = CHOLMOD_NESDIS;
  }
  /// After the first iterative global step of an Automatic choice: factors SwitchK and drops the
  /// iterative solver when CG took more than kDirectSwitchCgIterations per solve.
  void MaybeSwitchToDirect();
  /// LastRhs = the per-vertex sums of the element contributions C of the last local step.
  void GatherRightHandSides();

  // Local step and energies (EmbeddingLocalStep.cxx).
  EmbeddingEnergy LocalStep();
  /// MetricAligned start: per element the free Jacobian target (first M free axes x input
  /// axes) with F^T F = M_j - I: the eigen frame sqrt(λ_k - 1) v_kᵀ per free axis, eigenvectors
  /// oriented over the vertices in Prim's order of anisotropy, or the symmetric Q (M_j - I)^{1/2}.
  void BuildAlignedTargets(bool eigenFrame);
  /// C from AlignedTarget (a global step then fits the start).
  void SeedMetricAlignedRightHandSides();
  /// sum_j w_j |F_j - target_j|² / sum_j w_j |target_j|² of the current iterate (0 for none).
  double MetricAlignedResidual() const;
  template <int MBT, int MT, int KT>
  double LocalStepT();
  double RegularizerEnergy() const;

  // Global step and iterations (EmbeddingIterations.cxx).
  /// The global step for the current local step; current = the current iterate's free
  /// coordinates (the iterative solver's warm start).
  /// probe = false: never the Automatic solver's probe of CG (a step that is not an iteration).
  Eigen::MatrixXd GlobalStep(const Eigen::MatrixXd& current, bool probe = true);
  /// The same step solved more accurately (double factor, or a 1000x tighter CG tolerance).
  Eigen::MatrixXd RedoGlobalStepAccurately(const Eigen::MatrixXd& current);
  Eigen::MatrixXd GetFree() const;
  /// MetricAligned: the aligned start, kept if its fit is close enough (else the Smooth one).
  void TryMetricAlignedStart(EmbeddingResult& res);
  void SetFree(const Eigen::MatrixXd& xr);
  /// The Anderson candidate from the global step g = G(x), kept (x, cur updated) only when it
  /// lowers the energy; false when there is none or it was rejected.
  bool TryAndersonStep(AndersonAcceleration& anderson, const Eigen::MatrixXd& g,
    Eigen::MatrixXd& x, Eigen::MatrixXd& xa, EmbeddingEnergy& cur, EmbeddingResult& res);
  /// x = g, redone more accurately when the inexact solve raised the energy; if the iterative
  /// solve still does (round-off), x is kept.
  void PlainStep(
    Eigen::MatrixXd& g, Eigen::MatrixXd& x, EmbeddingEnergy& cur, EmbeddingResult& res);
  /// Calls the progress callback; false when it asks to stop.
  bool ReportProgress(
    const EmbeddingSolver* solver, int iteration, const EmbeddingEnergy& cur) const;
  /// The relative energy decrease of the last iteration fell below RelativeEnergyTolerance.
  bool Converged(const std::vector<EmbeddingEnergy>& history) const;
  /// Iteration `it` (1-based) is the last: the cap, or past Iterations and converged.
  bool ShouldStop(int it, const std::vector<EmbeddingEnergy>& history, EmbeddingResult& res) const;
};

} // namespace av

#endif
