// SPDX-License-Identifier: BSD-3-Clause
#include "MultigridVCycle.h"

#include "BlockRowOps.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace av
{

namespace
{
// Chebyshev degree per smoothing pass: 2 kept hypre's Gauss-Seidel iteration counts (6.1 against
// 5.8 per solve at 8k vertices) at one product per pass; 3 gains no iteration for one more.
constexpr int kChebyshevDegree = 2;
// The smoothed interval [kLowerFraction * lambda_max, lambda_max] (hypre's and PETSc's usual
// choice: the coarse grid takes care of the rest of the spectrum).
constexpr double kLowerFraction = 0.3;
// Lanczos estimates lambda_max from below; the margin keeps the smoother convergent.
constexpr double kUpperMargin = 1.1;
constexpr int kLanczosSteps = 10;
constexpr int kDenseCoarseRows = 2000;

/// lambda_max(D^-1 A) from kLanczosSteps Lanczos steps on the symmetric D^-1/2 A D^-1/2, with a
/// fixed start vector (deterministic), at most the Gershgorin bound max_i sum_j |a_ij| / a_ii.
double UpperSpectralBound(const CsrMatrix& a, const std::vector<double>& invDiag)
{
  const int n = a.Rows();
  double gershgorin = 0.0;
  for (int i = 0; i < n; ++i)
  {
    double s = 0.0;
    for (std::int64_t e = a.RowStart()[i]; e < a.RowStart()[i + 1]; ++e)
    {
      s += std::abs(a.Value()[e]);
    }
    gershgorin = std::max(gershgorin, s * invDiag[i]);
  }
  std::vector<double> sqrtInv(n), v(n), vPrev(n, 0.0), w(n), t(n);
  for (int i = 0; i < n; ++i)
  {
    sqrtInv[i] = std::sqrt(invDiag[i]);
    v[i] = 1.0 + 0.5 * std::sin(0.7 * i + 0.3); // generic: not orthogonal to the top mode
  }
  double norm = 0.0;
  for (const double x : v)
  {
    norm += x * x;
  }
  norm = std::sqrt(norm);
  for (double& x : v)
  {
    x /= norm;
  }
  const int steps = std::min(kLanczosSteps, n);
  Eigen::VectorXd alpha(steps), beta(steps);
  int m = 0;
  double betaPrev = 0.0;
  for (; m < steps; ++m)
  {
    for (int i = 0; i < n; ++i)
    {
      t[i] = sqrtInv[i] * v[i];
    }
    a.Multiply(t.data(), w.data(), 1);
    double al = 0.0;
    for (int i = 0; i < n; ++i)
    {
      w[i] = sqrtInv[i] * w[i] - betaPrev * vPrev[i];
      al += w[i] * v[i];
    }
    double b = 0.0;
    for (int i = 0; i < n; ++i)
    {
      w[i] -= al * v[i];
      b += w[i] * w[i];
    }
    b = std::sqrt(b);
    alpha[m] = al;
    beta[m] = b;
    if (b <= 1e-12 * std::abs(al))
    {
      ++m; // invariant subspace: T is exact
      break;
    }
    for (int i = 0; i < n; ++i)
    {
      vPrev[i] = v[i];
      v[i] = w[i] / b;
    }
    betaPrev = b;
  }
  Eigen::MatrixXd tri = Eigen::MatrixXd::Zero(m, m);
  for (int i = 0; i < m; ++i)
  {
    tri(i, i) = alpha[i];
    if (i + 1 < m)
    {
      tri(i, i + 1) = tri(i + 1, i) = beta[i];
    }
  }
  const double estimate =
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(tri, Eigen::EigenvaluesOnly)
      .eigenvalues()
      .maxCoeff();
  return std::min(kUpperMargin * estimate, gershgorin);
}
} // namespace

MultigridVCycle::MultigridVCycle(std::vector<CsrMatrix> operators,
  std::vector<CsrMatrix> interpolations)
{
  if (operators.empty() || interpolations.size() + 1 != operators.size())
  {
    throw std::invalid_argument("MultigridVCycle: need L + 1 operators and L interpolations");
  }
  this->Level.resize(operators.size());
  for (std::size_t l = 0; l < operators.size(); ++l)
  {
    Grid& g = this->Level[l];
    g.A = std::move(operators[l]);
    const int n = g.A.Rows();
    if (n == 0 || g.A.Cols() != n)
    {
      throw std::invalid_argument("MultigridVCycle: level " + std::to_string(l) + " is not square");
    }
    if (l + 1 < this->Level.size())
    {
      g.Interp = std::move(interpolations[l]);
      if (g.Interp.Rows() != n || g.Interp.Cols() != operators[l + 1].Rows())
      {
        throw std::invalid_argument(
          "MultigridVCycle: interpolation " + std::to_string(l) + " does not chain the levels");
      }
      g.Restrict = g.Interp.Transposed();
    }
    const std::vector<double> diag = g.A.Diagonal();
    g.InvDiag.resize(diag.size());
    for (int i = 0; i < n; ++i)
    {
      if (!(diag[i] > 0.0))
      {
        throw std::invalid_argument(
          "MultigridVCycle: a diagonal entry of level " + std::to_string(l) + " is not positive");
      }
      g.InvDiag[i] = 1.0 / diag[i];
    }
    g.Upper = UpperSpectralBound(g.A, g.InvDiag);
    const double lower = kLowerFraction * g.Upper;
    g.Theta = 0.5 * (g.Upper + lower);
    g.Delta = 0.5 * (g.Upper - lower);
    g.Sigma = g.Theta / g.Delta;
  }
  const Grid& coarsest = this->Level.back();
  if (coarsest.A.Rows() <= kDenseCoarseRows)
  {
    const int n = coarsest.A.Rows();
    Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i)
    {
      for (std::int64_t e = coarsest.A.RowStart()[i]; e < coarsest.A.RowStart()[i + 1]; ++e)
      {
        dense(i, coarsest.A.Column()[e]) += coarsest.A.Value()[e];
      }
    }
    this->CoarseFactor.compute(dense);
    this->CoarseDense =
      this->CoarseFactor.info() == Eigen::Success && this->CoarseFactor.isPositive();
  }
}

double MultigridVCycle::OperatorComplexity() const
{
  double total = 0.0;
  for (const Grid& g : this->Level)
  {
    total += static_cast<double>(g.A.NonZeros());
  }
  return total / static_cast<double>(std::max<std::int64_t>(1, this->Level.front().A.NonZeros()));
}

void MultigridVCycle::Reserve(int k)
{
  if (k <= this->ReservedColumns)
  {
    return;
  }
  for (Grid& g : this->Level)
  {
    const std::size_t size = static_cast<std::size_t>(g.A.Rows()) * k;
    for (std::vector<double>* v : { &g.B, &g.X, &g.R, &g.D, &g.T })
    {
      v->resize(size);
    }
  }
  const int n = this->Level.back().A.Rows();
  this->CoarseRhs.resize(n, k);
  this->CoarseSolution.resize(n, k);
  this->ReservedColumns = k;
}

void MultigridVCycle::Apply(const double* r, double* z, int k)
{
  if (k < 1 || k > blockrows::kMaxColumns)
  {
    throw std::invalid_argument("MultigridVCycle::Apply: block width must be 1..8");
  }
  this->Reserve(k);
  Grid& fine = this->Level.front();
  const std::size_t size = static_cast<std::size_t>(fine.A.Rows()) * k;
  std::copy(r, r + size, fine.B.begin());
  this->Cycle(0, k);
  std::copy(fine.X.begin(), fine.X.begin() + static_cast<std::ptrdiff_t>(size), z);
}

void MultigridVCycle::Smooth(Grid& g, int k, bool zeroStart)
{
  // Chebyshev iteration for D^-1 A x = D^-1 b (Saad, Iterative Methods, Alg. 12.1): R is the
  // scaled residual D^-1 (b - A x), D the step.
  const std::size_t n = static_cast<std::size_t>(g.A.Rows());
  const std::size_t kk = static_cast<std::size_t>(k);
  double* x = g.X.data();
  double* res = g.R.data();
  double* d = g.D.data();
  double* t = g.T.data();
  const double* b = g.B.data();
  const double* inv = g.InvDiag.data();
  if (!zeroStart)
  {
    g.A.Multiply(x, t, k);
  }
  const double invTheta = 1.0 / g.Theta;
  blockrows::ForRows(n,
    3 * kk,
    [&](std::size_t r0, std::size_t r1)
    {
      for (std::size_t i = r0; i < r1; ++i)
      {
        for (std::size_t c = i * kk; c < (i + 1) * kk; ++c)
        {
          res[c] = inv[i] * (zeroStart ? b[c] : b[c] - t[c]);
          d[c] = invTheta * res[c];
          x[c] = zeroStart ? d[c] : x[c] + d[c];
        }
      }
    });
  double rho = 1.0 / g.Sigma;
  for (int step = 1; step < kChebyshevDegree; ++step)
  {
    g.A.Multiply(d, t, k);
    const double rhoNext = 1.0 / (2.0 * g.Sigma - rho);
    const double keep = rhoNext * rho, push = 2.0 * rhoNext / g.Delta;
    blockrows::ForRows(n,
      4 * kk,
      [&](std::size_t r0, std::size_t r1)
      {
        for (std::size_t i = r0; i < r1; ++i)
        {
          for (std::size_t c = i * kk; c < (i + 1) * kk; ++c)
          {
            res[c] -= inv[i] * t[c];
            d[c] = keep * d[c] + push * res[c];
            x[c] += d[c];
          }
        }
      });
    rho = rhoNext;
  }
}

void MultigridVCycle::Cycle(std::size_t l, int k)
{
  Grid& g = this->Level[l];
  const std::size_t n = static_cast<std::size_t>(g.A.Rows());
  const std::size_t kk = static_cast<std::size_t>(k);
  if (l + 1 == this->Level.size())
  {
    if (this->CoarseDense)
    {
      for (std::size_t i = 0; i < n; ++i)
      {
        for (std::size_t c = 0; c < kk; ++c)
        {
          this->CoarseRhs(i, c) = g.B[i * kk + c];
        }
      }
      this->CoarseSolution.leftCols(k) = this->CoarseFactor.solve(this->CoarseRhs.leftCols(k));
      for (std::size_t i = 0; i < n; ++i)
      {
        for (std::size_t c = 0; c < kk; ++c)
        {
          g.X[i * kk + c] = this->CoarseSolution(i, c);
        }
      }
    }
    else
    {
      this->Smooth(g, k, true);
      this->Smooth(g, k, false);
    }
    return;
  }
  this->Smooth(g, k, true);
  // Restrict the residual b - A x to the next level's right-hand side.
  g.A.Multiply(g.X.data(), g.T.data(), k);
  blockrows::ForRows(n,
    kk,
    [&](std::size_t r0, std::size_t r1)
    {
      for (std::size_t c = r0 * kk; c < r1 * kk; ++c)
      {
        g.R[c] = g.B[c] - g.T[c];
      }
    });
  Grid& coarse = this->Level[l + 1];
  g.Restrict.Multiply(g.R.data(), coarse.B.data(), k);
  this->Cycle(l + 1, k);
  g.Interp.Multiply(coarse.X.data(), g.T.data(), k);
  blockrows::ForRows(n,
    kk,
    [&](std::size_t r0, std::size_t r1)
    {
      for (std::size_t c = r0 * kk; c < r1 * kk; ++c)
      {
        g.X[c] += g.T[c];
      }
    });
  this->Smooth(g, k, false);
}

} // namespace av
