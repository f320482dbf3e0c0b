// SPDX-License-Identifier: BSD-3-Clause
// IterativeGlobalSolver: block PCG with an AMG V-cycle (see the header).
#include "IterativeGlobalSolver.h"

#include "BlockRowOps.h"
#include "BoomerAmgHierarchy.h"
#include "CsrMatrix.h"
#include "InputError.h"
#include "MultigridVCycle.h"
#include "Stopwatch.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace av
{

struct IterativeGlobalSolver::Workspace
{
  CsrMatrix K;
  std::unique_ptr<MultigridVCycle> Cycle;
  // Blocks of n x k, row-major: iterate, right-hand side, residual, preconditioned residual,
  // search direction, K times the direction.
  std::vector<double> X, B, R, Z, P, Q;
};

IterativeGlobalSolver::IterativeGlobalSolver(const Eigen::SparseMatrix<double>& lower,
  int maxIterations,
  const Eigen::SparseMatrix<double>* preconditionerLower)
  : W(new Workspace)
  , MaxIterations(std::max(1, maxIterations))
{
  const Stopwatch clock;
  if (lower.rows() != lower.cols() || lower.rows() == 0)
  {
    throw InputError("embedding: the iterative solver needs a non-empty square matrix");
  }
  if (preconditionerLower &&
    (preconditionerLower->rows() != lower.rows() || preconditionerLower->cols() != lower.cols()))
  {
    throw InputError("embedding: the preconditioner's matrix does not match the system's size");
  }
  this->W->K = CsrMatrix::SymmetricFromLower(lower);
  AmgHierarchy levels = BuildBoomerAmgHierarchy(
    preconditionerLower ? CsrMatrix::SymmetricFromLower(*preconditionerLower) : this->W->K);
  try
  {
    this->W->Cycle.reset(
      new MultigridVCycle(std::move(levels.Operators), std::move(levels.Interpolations)));
  }
  catch (const std::invalid_argument& e)
  {
    throw InputError(std::string("embedding: the AMG hierarchy is not usable: ") + e.what());
  }
  const std::size_t size = static_cast<std::size_t>(lower.rows()) * blockrows::kMaxColumns;
  for (std::vector<double>* v :
    { &this->W->X, &this->W->B, &this->W->R, &this->W->Z, &this->W->P, &this->W->Q })
  {
    v->resize(size);
  }
  this->Stats.Levels = this->W->Cycle->Levels();
  this->Stats.SetupSeconds = clock.Seconds();
}

IterativeGlobalSolver::~IterativeGlobalSolver() = default;

long long IterativeGlobalSolver::Solve(const Eigen::MatrixXd& rhs,
  Eigen::MatrixXd& x,
  double tolerance)
{
  const Eigen::Index n = this->W->K.Rows();
  if (rhs.rows() != n || x.rows() != n || x.cols() != rhs.cols())
  {
    throw InputError("embedding: the iterative solve's vectors do not match the matrix");
  }
  long long total = 0;
  for (Eigen::Index first = 0; first < rhs.cols(); first += blockrows::kMaxColumns)
  {
    const int k =
      static_cast<int>(std::min<Eigen::Index>(blockrows::kMaxColumns, rhs.cols() - first));
    this->SolveBlock(rhs, x, first, k, tolerance, total);
  }
  this->Stats.Iterations += total;
  return total;
}

void IterativeGlobalSolver::SolveBlock(const Eigen::MatrixXd& rhs,
  Eigen::MatrixXd& xOut,
  Eigen::Index first,
  int k,
  double tolerance,
  long long& iterations)
{
  Workspace& w = *this->W;
  const std::size_t n = static_cast<std::size_t>(w.K.Rows());
  const std::size_t kk = static_cast<std::size_t>(k);
  double* x = w.X.data();
  double* b = w.B.data();
  double* r = w.R.data();
  double* z = w.Z.data();
  double* p = w.P.data();
  double* q = w.Q.data();
  for (std::size_t i = 0; i < n; ++i)
  {
    for (std::size_t c = 0; c < kk; ++c)
    {
      b[i * kk + c] = rhs(static_cast<Eigen::Index>(i), first + static_cast<Eigen::Index>(c));
      x[i * kk + c] = xOut(static_cast<Eigen::Index>(i), first + static_cast<Eigen::Index>(c));
    }
  }
  double bb[blockrows::kMaxColumns], rr[blockrows::kMaxColumns], rz[blockrows::kMaxColumns],
    rzOld[blockrows::kMaxColumns], pq[blockrows::kMaxColumns], rp[blockrows::kMaxColumns];
  double beta[blockrows::kMaxColumns], alpha[blockrows::kMaxColumns], mask[blockrows::kMaxColumns];
  int done[blockrows::kMaxColumns];
  blockrows::ColumnDots(b, b, n, k, bb);
  // A zero right-hand side has the exact solution 0 (a relative test needs |b| > 0).
  for (std::size_t i = 0; i < n; ++i)
  {
    for (std::size_t c = 0; c < kk; ++c)
    {
      if (bb[c] == 0.0)
      {
        x[i * kk + c] = 0.0;
      }
    }
  }
  w.K.Multiply(x, q, k);
  blockrows::ForRows(n,
    kk,
    [&](std::size_t r0, std::size_t r1)
    {
      for (std::size_t e = r0 * kk; e < r1 * kk; ++e)
      {
        r[e] = b[e] - q[e];
        p[e] = 0.0;
      }
    });
  blockrows::ColumnDots(r, r, n, k, rr);
  int active = 0;
  int columnIterations[blockrows::kMaxColumns] = { 0 };
  const double tol2 = tolerance * tolerance;
  for (int c = 0; c < k; ++c)
  {
    done[c] = bb[c] == 0.0 || rr[c] <= tol2 * bb[c];
    active += !done[c];
    rzOld[c] = 1.0;
  }
  bool firstStep = true;
  while (active > 0)
  {
    w.Cycle->Apply(r, z, k);
    blockrows::ColumnDots(r, z, n, k, rz);
    for (int c = 0; c < k; ++c)
    {
      mask[c] = done[c] ? 0.0 : 1.0;
      beta[c] = done[c] || firstStep || rzOld[c] == 0.0 ? 0.0 : rz[c] / rzOld[c];
      rzOld[c] = rz[c];
    }
    firstStep = false;
    // Finished columns get p = 0: their step is 0 and they stay where they are.
    blockrows::ForRows(n,
      2 * kk,
      [&](std::size_t r0, std::size_t r1)
      {
        for (std::size_t i = r0; i < r1; ++i)
        {
          for (std::size_t c = 0; c < kk; ++c)
          {
            const std::size_t e = i * kk + c;
            p[e] = mask[c] * (z[e] + beta[c] * p[e]);
          }
        }
      });
    w.K.Multiply(p, q, k);
    blockrows::ColumnDots(p, q, n, k, pq);
    blockrows::ColumnDots(r, p, n, k, rp);
    for (int c = 0; c < k; ++c)
    {
      // <r, p> / <p, Kp>: the exact minimizer along p (equal to CG's <r, z> / <p, Kp> in exact
      // arithmetic), so the energy cannot rise even if the preconditioner is slightly off.
      alpha[c] = !done[c] && pq[c] > 0.0 ? rp[c] / pq[c] : 0.0;
    }
    blockrows::ForRows(n,
      2 * kk,
      [&](std::size_t r0, std::size_t r1)
      {
        for (std::size_t i = r0; i < r1; ++i)
        {
          for (std::size_t c = 0; c < kk; ++c)
          {
            const std::size_t e = i * kk + c;
            x[e] += alpha[c] * p[e];
            r[e] -= alpha[c] * q[e];
          }
        }
      });
    blockrows::ColumnDots(r, r, n, k, rr);
    for (int c = 0; c < k; ++c)
    {
      if (done[c])
      {
        continue;
      }
      ++columnIterations[c];
      // pq <= 0 only when p = 0 (K is SPD): nothing left to gain in that column.
      if (rr[c] <= tol2 * bb[c] || !(pq[c] > 0.0) || columnIterations[c] >= this->MaxIterations)
      {
        done[c] = 1;
        --active;
      }
    }
  }
  for (int c = 0; c < k; ++c)
  {
    if (bb[c] == 0.0)
    {
      continue;
    }
    const double residual = std::sqrt(rr[c] / bb[c]);
    ++this->Stats.Solves;
    iterations += columnIterations[c];
    this->Stats.MaxIterations = std::max(this->Stats.MaxIterations, columnIterations[c]);
    this->Stats.WorstRelativeResidual = std::max(this->Stats.WorstRelativeResidual, residual);
    if (residual > tolerance)
    {
      ++this->Stats.NotConverged;
    }
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    for (std::size_t c = 0; c < kk; ++c)
    {
      xOut(static_cast<Eigen::Index>(i), first + static_cast<Eigen::Index>(c)) = x[i * kk + c];
    }
  }
}

} // namespace av
