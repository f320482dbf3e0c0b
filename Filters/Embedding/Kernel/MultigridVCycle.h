// SPDX-License-Identifier: BSD-3-Clause
// MultigridVCycle: one V-cycle of an algebraic-multigrid hierarchy with Chebyshev smoothing,
// applied to blocks of up to eight vectors at once; the iterative global step's preconditioner.
#ifndef av_MultigridVCycle_h
#define av_MultigridVCycle_h

#include "CsrMatrix.h"

#include <Eigen/Dense>

#include <cstddef>
#include <vector>

namespace av
{

/**
 * z = M^-1 r for the V-cycle of a Galerkin hierarchy A_0 (finest), ..., A_L with interpolations
 * P_l (n_l x n_{l+1}) and restrictions P_l^T. Smoother: Chebyshev polynomial of degree 2 in
 * D^-1 A on [0.3 lambda_max, lambda_max] (lambda_max from a few Lanczos steps, safeguarded by the
 * Gershgorin bound), the same before and after the coarse correction, so M is symmetric; it is
 * positive definite because the smoother contracts every error component (its residual
 * polynomial lies in (-1, 1) on (0, lambda_max]). Unlike Gauss-Seidel, the smoother is made of
 * matrix products only: they run on all threads and read each matrix once for all k vectors.
 * Coarsest level: dense Cholesky (LDLT) when it has at most 2000 rows, else smoothing.
 *
 * Apply() uses workspace held by the object: one call at a time.
 */
class MultigridVCycle
{
public:
  /// operators[l] = A_l (square, positive diagonal), interpolations[l] = P_l, l < L. Throws
  /// std::invalid_argument when sizes do not chain or a diagonal entry is not positive.
  MultigridVCycle(std::vector<CsrMatrix> operators, std::vector<CsrMatrix> interpolations);

  /// z = M^-1 r for k vectors (n_0 x k, row-major), 1 <= k <= 8. r and z may not overlap.
  void Apply(const double* r, double* z, int k);

  int Levels() const { return static_cast<int>(this->Level.size()); }
  int Rows() const { return this->Level.empty() ? 0 : this->Level.front().A.Rows(); }
  /// Sum of the nonzeros of all operators over those of A_0 (the hierarchy's memory and work).
  double OperatorComplexity() const;
  /// The smoother's upper spectral bound on level l (the interval's right end).
  double SmootherUpperBound(int l) const { return this->Level[l].Upper; }

private:
  struct Grid
  {
    CsrMatrix A, Interp, Restrict; // Interp/Restrict empty on the coarsest level
    std::vector<double> InvDiag;
    double Upper = 0.0, Theta = 0.0, Delta = 0.0, Sigma = 0.0;
    std::vector<double> B, X, R, D, T; // rhs, iterate, scaled residual, step, product
  };

  void Cycle(std::size_t l, int k);
  void Smooth(Grid& g, int k, bool zeroStart);
  void Reserve(int k);

  std::vector<Grid> Level;
  Eigen::LDLT<Eigen::MatrixXd> CoarseFactor;
  bool CoarseDense = false;
  Eigen::MatrixXd CoarseRhs, CoarseSolution; // column-major copies for the dense solve
  int ReservedColumns = 0;
};

} // namespace av

#endif
