// SPDX-License-Identifier: BSD-3-Clause
// The iterative global step's building blocks: block sparse products against Eigen, the V-cycle
// is a symmetric positive definite preconditioner that reduces the error, a block of k columns
// gives what k single-column runs give, and bad hierarchies are refused.
#include "AnisoTestChecks.h"
#include "BlockRowOps.h"
#include "BoomerAmgHierarchy.h"
#include "CsrMatrix.h"
#include "IterativeGlobalSolver.h"
#include "MultigridVCycle.h"

#include <Eigen/SparseCore>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace
{
using namespace av;

/// Lower triangle of a 3D 7-point Laplacian on an m^3 grid plus a small shift, with a
/// coefficient jump (x1000 in one half) so that the AMG has real work.
Eigen::SparseMatrix<double> JumpLaplacianLower(int m)
{
  const int n = m * m * m;
  std::vector<Eigen::Triplet<double>> t;
  const auto id = [m](int i, int j, int k) { return (k * m + j) * m + i; };
  std::vector<double> diag(static_cast<std::size_t>(n), 1e-3);
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i)
      {
        const int a = id(i, j, k);
        const int nb[3] = { i + 1 < m ? id(i + 1, j, k) : -1,
          j + 1 < m ? id(i, j + 1, k) : -1,
          k + 1 < m ? id(i, j, k + 1) : -1 };
        for (const int b : nb)
        {
          if (b < 0)
            continue;
          const double w = (i < m / 2 ? 1000.0 : 1.0);
          t.emplace_back(std::max(a, b), std::min(a, b), -w);
          diag[a] += w;
          diag[b] += w;
        }
      }
  for (int a = 0; a < n; ++a)
    t.emplace_back(a, a, diag[a]);
  Eigen::SparseMatrix<double> lower(n, n);
  lower.setFromTriplets(t.begin(), t.end());
  return lower;
}

double Value(int i, int c)
{
  return std::sin(0.37 * i + 1.3 * c) + 0.1 * std::cos(0.011 * i * (c + 1));
}

void CheckMultiply(const Eigen::SparseMatrix<double>& lower)
{
  const Eigen::SparseMatrix<double> full = lower.selfadjointView<Eigen::Lower>();
  const CsrMatrix a = CsrMatrix::SymmetricFromLower(lower);
  const CsrMatrix at = a.Transposed();
  const int n = a.Rows();
  AV_CHECK(a.NonZeros() == full.nonZeros());
  for (const int k : { 1, 3, 8 })
  {
    std::vector<double> x(static_cast<std::size_t>(n) * k), y(x.size()), yt(x.size());
    Eigen::MatrixXd xe(n, k);
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < k; ++c)
        xe(i, c) = x[static_cast<std::size_t>(i) * k + c] = Value(i, c);
    a.Multiply(x.data(), y.data(), k);
    at.Multiply(x.data(), yt.data(), k);
    const Eigen::MatrixXd ye = full * xe;
    double err = 0.0, errT = 0.0;
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < k; ++c)
      {
        err = std::max(err, std::abs(y[static_cast<std::size_t>(i) * k + c] - ye(i, c)));
        errT = std::max(errT, std::abs(yt[static_cast<std::size_t>(i) * k + c] - ye(i, c)));
      }
    AV_CHECK_MSG(err < 1e-9 * ye.cwiseAbs().maxCoeff(), "k = " << k << ": " << err);
    AV_CHECK_MSG(errT < 1e-9 * ye.cwiseAbs().maxCoeff(), "transposed, k = " << k << ": " << errT);
  }
  bool thrown = false;
  try
  {
    std::vector<double> x(static_cast<std::size_t>(n) * 9), y(x.size());
    a.Multiply(x.data(), y.data(), 9);
  }
  catch (const std::invalid_argument&)
  {
    thrown = true;
  }
  AV_CHECK_MSG(thrown, "a block of 9 columns must be refused");
  thrown = false;
  try
  {
    CsrMatrix bad(2, 2, { 0, 1, 3 }, { 0, 1 }, { 1.0, 2.0 });
  }
  catch (const std::invalid_argument&)
  {
    thrown = true;
  }
  AV_CHECK_MSG(thrown, "inconsistent CSR arrays must be refused");
}

void CheckVCycle(const Eigen::SparseMatrix<double>& lower)
{
  const Eigen::SparseMatrix<double> full = lower.selfadjointView<Eigen::Lower>();
  const CsrMatrix a = CsrMatrix::SymmetricFromLower(lower);
  AmgHierarchy h = BuildBoomerAmgHierarchy(a);
  const int n = a.Rows();
  AV_CHECK_MSG(h.Operators.size() >= 3, "levels: " << h.Operators.size());
  AV_CHECK(h.Interpolations.size() + 1 == h.Operators.size());
  // Galerkin: A_1 = P_0^T A_0 P_0 (the hierarchy was copied out of hypre correctly).
  {
    const CsrMatrix& p0 = h.Interpolations[0];
    const int nc = p0.Cols();
    double err = 0.0, scale = 0.0;
    for (int col = 0; col < std::min(nc, 5); ++col)
    {
      std::vector<double> e(static_cast<std::size_t>(nc), 0.0), pe(n), ape(n), ptape(nc), a1e(nc);
      e[col] = 1.0;
      p0.Multiply(e.data(), pe.data(), 1);
      a.Multiply(pe.data(), ape.data(), 1);
      p0.Transposed().Multiply(ape.data(), ptape.data(), 1);
      h.Operators[1].Multiply(e.data(), a1e.data(), 1);
      for (int i = 0; i < nc; ++i)
      {
        err = std::max(err, std::abs(ptape[i] - a1e[i]));
        scale = std::max(scale, std::abs(a1e[i]));
      }
    }
    AV_CHECK_MSG(err <= 1e-8 * scale, "Galerkin product off by " << err << " of " << scale);
  }
  MultigridVCycle cycle(h.Operators, h.Interpolations);
  AV_CHECK(cycle.Rows() == n);
  std::cout << "V-cycle: " << cycle.Levels() << " levels, operator complexity "
            << cycle.OperatorComplexity() << "\n";
  // Smoother bound: at least lambda_max(D^-1 A) (a Rayleigh quotient gives a lower bound).
  {
    const std::vector<double> d = a.Diagonal();
    std::vector<double> v(n), av(n);
    for (int i = 0; i < n; ++i)
      v[i] = (i % 2 ? 1.0 : -1.0) / std::sqrt(d[i]); // oscillating: near the top of the spectrum
    a.Multiply(v.data(), av.data(), 1);
    double num = 0.0, den = 0.0;
    for (int i = 0; i < n; ++i)
    {
      num += v[i] * av[i];
      den += v[i] * v[i] * d[i];
    }
    AV_CHECK_MSG(cycle.SmootherUpperBound(0) >= num / den,
      "bound " << cycle.SmootherUpperBound(0) << " below a Rayleigh quotient " << num / den);
  }
  // Symmetric and positive: <M u, v> = <u, M v>, <M u, u> > 0.
  const int k = 3;
  std::vector<double> u(static_cast<std::size_t>(n) * k), mu(u.size());
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < k; ++c)
      u[static_cast<std::size_t>(i) * k + c] = Value(i, c);
  cycle.Apply(u.data(), mu.data(), k);
  double muv = 0.0, umv = 0.0, scale = 0.0;
  for (int i = 0; i < n; ++i)
  {
    muv += mu[static_cast<std::size_t>(i) * k + 0] * u[static_cast<std::size_t>(i) * k + 1];
    umv += u[static_cast<std::size_t>(i) * k + 0] * mu[static_cast<std::size_t>(i) * k + 1];
    scale += std::abs(mu[static_cast<std::size_t>(i) * k] * u[static_cast<std::size_t>(i) * k + 1]);
  }
  AV_CHECK_MSG(std::abs(muv - umv) <= 1e-10 * scale, "<Mu,v> = " << muv << ", <u,Mv> = " << umv);
  double dots[blockrows::kMaxColumns];
  blockrows::ColumnDots(u.data(), mu.data(), static_cast<std::size_t>(n), k, dots);
  for (int c = 0; c < k; ++c)
    AV_CHECK_MSG(dots[c] > 0.0, "<Mu,u> = " << dots[c] << " in column " << c);
  // Each column of the block is what a single-column cycle gives.
  for (int c = 0; c < k; ++c)
  {
    std::vector<double> one(n), mone(n);
    for (int i = 0; i < n; ++i)
      one[i] = u[static_cast<std::size_t>(i) * k + c];
    cycle.Apply(one.data(), mone.data(), 1);
    double err = 0.0, big = 0.0;
    for (int i = 0; i < n; ++i)
    {
      err = std::max(err, std::abs(mone[i] - mu[static_cast<std::size_t>(i) * k + c]));
      big = std::max(big, std::abs(mone[i]));
    }
    AV_CHECK_MSG(err <= 1e-12 * big, "column " << c << " differs by " << err);
  }
  // A preconditioner worth its name: e <- (I - M A) e contracts a smooth and a rough error.
  for (const int c : { 0, 2 })
  {
    Eigen::VectorXd e(n);
    for (int i = 0; i < n; ++i)
      e[i] = c == 0 ? std::sin(0.05 * i) : Value(i, c);
    for (int sweep = 0; sweep < 3; ++sweep)
    {
      const double before = std::sqrt(e.dot(full * e));
      Eigen::VectorXd ae = full * e, mae(n);
      cycle.Apply(ae.data(), mae.data(), 1);
      e -= mae;
      const double after = std::sqrt(e.dot(full * e));
      AV_CHECK_MSG(after < 0.5 * before, "A-norm of the error " << before << " -> " << after);
    }
  }
  // Refused: interpolations that do not chain the levels, a non-positive diagonal.
  bool thrown = false;
  try
  {
    std::vector<CsrMatrix> ops(h.Operators.begin(), h.Operators.end());
    std::vector<CsrMatrix> interp(h.Interpolations.begin(), h.Interpolations.end());
    interp[0] = interp[0].Transposed();
    MultigridVCycle bad(ops, interp);
  }
  catch (const std::invalid_argument&)
  {
    thrown = true;
  }
  AV_CHECK_MSG(thrown, "a transposed interpolation must be refused");
  thrown = false;
  try
  {
    MultigridVCycle bad({ CsrMatrix(2, 2, { 0, 1, 2 }, { 0, 1 }, { 1.0, -1.0 }) }, {});
  }
  catch (const std::invalid_argument&)
  {
    thrown = true;
  }
  AV_CHECK_MSG(thrown, "a negative diagonal must be refused");
}

/// Block CG: 11 right-hand sides (a block of 8 and one of 3) solved together agree with one
/// at a time, a zero column stays zero and is not counted, and all reach the tolerance.
void CheckBlockSolve(const Eigen::SparseMatrix<double>& lower)
{
  const Eigen::SparseMatrix<double> full = lower.selfadjointView<Eigen::Lower>();
  const int n = static_cast<int>(lower.rows()), cols = 11;
  Eigen::MatrixXd xTrue(n, cols);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < cols; ++c)
      xTrue(i, c) = c == 4 ? 0.0 : Value(i, c);
  const Eigen::MatrixXd b = full * xTrue;
  IterativeGlobalSolver together(lower, 500);
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(n, cols);
  together.Solve(b, x, 1e-10);
  AV_CHECK(together.Statistics().Solves == cols - 1);
  AV_CHECK(together.Statistics().NotConverged == 0);
  AV_CHECK(x.col(4).norm() == 0.0);
  const double err = (x - xTrue).norm() / xTrue.norm();
  std::cout << "block CG: relative error " << err << ", "
            << double(together.Statistics().Iterations) / together.Statistics().Solves
            << " iterations per solve, " << together.Statistics().Levels << " levels\n";
  AV_CHECK_MSG(err < 1e-7, "error " << err);
  AV_CHECK(together.Statistics().MaxIterations < 40);
  IterativeGlobalSolver alone(lower, 500);
  for (int c = 0; c < cols; ++c)
  {
    Eigen::MatrixXd one = Eigen::MatrixXd::Zero(n, 1);
    alone.Solve(b.col(c), one, 1e-10);
    AV_CHECK_MSG((one.col(0) - x.col(c)).norm() <= 1e-12 * (1.0 + x.col(c).norm()),
      "column " << c << " alone differs by " << (one.col(0) - x.col(c)).norm());
  }
  AV_CHECK(alone.Statistics().Iterations == together.Statistics().Iterations);
  // A wrong-sized right-hand side is refused, not read out of bounds.
  Eigen::MatrixXd small = Eigen::MatrixXd::Zero(n - 1, 1);
  AV_CHECK_THROWS(together.Solve(b.topRows(n - 1).leftCols(1), small, 1e-6));
}
} // namespace

int TestMultigridVCycle(int, char*[])
{
  const Eigen::SparseMatrix<double> lower = JumpLaplacianLower(22);
  CheckMultiply(lower);
  CheckVCycle(lower);
  CheckBlockSolve(lower);
  return AV_TEST_RESULT();
}
