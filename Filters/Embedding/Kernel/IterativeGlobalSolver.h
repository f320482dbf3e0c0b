// SPDX-License-Identifier: BSD-3-Clause
// IterativeGlobalSolver: the embedding's global step by conjugate gradients preconditioned with
// an algebraic-multigrid V-cycle (hierarchy from hypre's BoomerAMG), for meshes whose Cholesky
// factor would not fit.
#ifndef av_IterativeGlobalSolver_h
#define av_IterativeGlobalSolver_h

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include <algorithm>
#include <memory>

namespace av
{

/// Counters of the conjugate-gradient solves (one solve = one right-hand side).
struct IterativeSolveStatistics
{
  long long Solves = 0;
  long long Iterations = 0;           ///< CG iterations summed over all solves
  int MaxIterations = 0;              ///< most CG iterations one solve took
  int NotConverged = 0;               ///< solves that hit the iteration cap before the tolerance
  double SetupSeconds = 0.0;          ///< matrix conversion and AMG hierarchy
  int Levels = 0;                     ///< levels of the AMG hierarchy
  double WorstRelativeResidual = 0.0; ///< largest final |r| / |b| seen
};

/**
 * Solves K X = B for a sparse symmetric positive definite K (given by its lower triangle) and
 * several right-hand sides with preconditioned conjugate gradients. The preconditioner is one
 * V-cycle of an AMG hierarchy: coarsening, interpolation and Galerkin products from hypre's
 * BoomerAMG setup (BoomerAmgHierarchy), the cycle itself ours (MultigridVCycle: Chebyshev
 * smoothing, symmetric, made of matrix products). The right-hand sides go through CG in blocks of
 * up to eight independent columns that share every matrix pass, on all the caller's TBB
 * threads; results do not depend on the thread count.
 *
 * The hierarchy is built once; X on entry is the initial guess (warm start). Each step length is
 * the exact minimizer of the quadratic energy 1/2 x'Kx - b'x along the search direction, so the
 * energy never rises above that of X, whatever the preconditioner's accuracy. So an inexact global
 * step still keeps the local/global energy monotone.
 */
class IterativeGlobalSolver
{
public:
  /// lower: the lower triangle (column major, rows >= column) of K. preconditionerLower, when
  /// given: the lower triangle of an SPD matrix P of the same size, sparser than K and spectrally
  /// close to it; the AMG hierarchy is built on P (cheaper V-cycles), CG still solves K x = b.
  /// Throws InputError when the matrices are empty or do not match, or hypre fails.
  IterativeGlobalSolver(const Eigen::SparseMatrix<double>& lower,
    int maxIterations,
    const Eigen::SparseMatrix<double>* preconditionerLower = nullptr);
  ~IterativeGlobalSolver();
  IterativeGlobalSolver(const IterativeGlobalSolver&) = delete;
  IterativeGlobalSolver& operator=(const IterativeGlobalSolver&) = delete;

  /// For every column d: x.col(d) <- the PCG solution of K x = rhs.col(d), started from
  /// x.col(d), stopped at |r| <= tolerance |b| (a zero column gives 0 and is not counted as a
  /// solve). Returns the CG iterations of this call.
  long long Solve(const Eigen::MatrixXd& rhs, Eigen::MatrixXd& x, double tolerance);

  const IterativeSolveStatistics& Statistics() const { return this->Stats; }
  /// The cap on CG iterations per solve (at least 1); a capped solve counts as NotConverged.
  void SetMaxIterations(int maxIterations) { this->MaxIterations = std::max(1, maxIterations); }
  int GetMaxIterations() const { return this->MaxIterations; }

private:
  void SolveBlock(const Eigen::MatrixXd& rhs,
    Eigen::MatrixXd& x,
    Eigen::Index first,
    int k,
    double tolerance,
    long long& iterations);

  struct Workspace;
  std::unique_ptr<Workspace> W;
  int MaxIterations = 1;
  IterativeSolveStatistics Stats;
};

} // namespace av

#endif
