// SPDX-License-Identifier: BSD-3-Clause
// IterativeGlobalSolver: the embedding's global step by conjugate gradients preconditioned with
// hypre's BoomerAMG (algebraic multigrid), for meshes whose Cholesky factor would not fit.
#ifndef av_IterativeGlobalSolver_h
#define av_IterativeGlobalSolver_h

#include <Eigen/Dense>
#include <Eigen/SparseCore>

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
  double WorstRelativeResidual = 0.0; ///< largest final |r| / |b| seen
};

/**
 * Solves K X = B for a sparse symmetric positive definite K (given by its lower triangle) and
 * several right-hand sides, one column at a time, with hypre's PCG + BoomerAMG (one V-cycle per
 * CG iteration, symmetric l1 Gauss-Seidel smoothing so that the preconditioner is SPD). The
 * hierarchy is built once; X on entry is the initial guess (warm start). CG started from X never
 * raises the quadratic energy 1/2 x'Kx - b'x above that of X: every iterate minimizes the
 * K-norm of the error over a growing subspace that contains X. So an inexact global step still
 * keeps the local/global energy monotone.
 *
 * hypre is built with MPI in Debian: MPI is initialized (singleton) on first use if the process
 * has not done it, and finalized at exit. The solver runs on MPI_COMM_SELF (this rank only).
 */
class IterativeGlobalSolver
{
public:
  /// lower: the lower triangle (column major, rows >= column) of K. preconditionerLower, when
  /// given: the lower triangle of an SPD matrix P of the same size, sparser than K and spectrally
  /// close to it; the AMG hierarchy is built on P (cheaper V-cycles), CG still solves K x = b.
  /// Throws InputError when hypre fails to build the hierarchy.
  IterativeGlobalSolver(const Eigen::SparseMatrix<double>& lower,
    int maxIterations,
    const Eigen::SparseMatrix<double>* preconditionerLower = nullptr);
  ~IterativeGlobalSolver();
  IterativeGlobalSolver(const IterativeGlobalSolver&) = delete;
  IterativeGlobalSolver& operator=(const IterativeGlobalSolver&) = delete;

  /// For every column d: x.col(d) <- the PCG solution of K x = rhs.col(d), started from
  /// x.col(d), stopped at |r| <= tolerance |b|. Returns the CG iterations of this call.
  long long Solve(const Eigen::MatrixXd& rhs, Eigen::MatrixXd& x, double tolerance);

  const IterativeSolveStatistics& Statistics() const { return this->Stats; }

private:
  struct Hypre;
  std::unique_ptr<Hypre> H;
  IterativeSolveStatistics Stats;
};

} // namespace av

#endif
