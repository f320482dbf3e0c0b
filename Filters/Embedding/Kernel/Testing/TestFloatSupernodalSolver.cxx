// SPDX-License-Identifier: BSD-3-Clause
// FloatSupernodalSolver against CHOLMOD's double-precision solve on a squared-Laplacian grid
// system like the embedding's global step, with the subtree split forced coarse and fine.
#include "FloatSupernodalSolver.h"
#include "AnisoTestChecks.h"

#include <Eigen/CholmodSupport>
#include <Eigen/Sparse>

#include <iostream>
#include <random>
#include <vector>

namespace
{
struct Cholesky : Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower>
{
  const cholmod_factor* Factor() const { return this->m_cholmodFactor; }
};

/// Graph Laplacian of an nx x ny x nz grid (26 neighbors) plus mu LᵀL, first vertex pinned
/// (the embedding's K has the same two-ring structure).
Eigen::SparseMatrix<double> GridSystem(int nx, int ny, int nz, double mu)
{
  const int n = nx * ny * nz;
  const auto id = [&](int i, int j, int k) { return (k * ny + j) * nx + i; };
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
      {
        int deg = 0;
        for (int c = -1; c <= 1; ++c)
          for (int b = -1; b <= 1; ++b)
            for (int a = -1; a <= 1; ++a)
            {
              const int ii = i + a, jj = j + b, kk = k + c;
              if ((a || b || c) && ii >= 0 && jj >= 0 && kk >= 0 && ii < nx && jj < ny && kk < nz)
              {
                t.emplace_back(id(i, j, k), id(ii, jj, kk), -1.0);
                ++deg;
              }
            }
        t.emplace_back(id(i, j, k), id(i, j, k), deg);
      }
  Eigen::SparseMatrix<double> l(n, n);
  l.setFromTriplets(t.begin(), t.end());
  Eigen::SparseMatrix<double> k = l + mu * Eigen::SparseMatrix<double>(l.transpose() * l);
  k.coeffRef(0, 0) += 1e3; // pin
  return k;
}
} // namespace

int TestFloatSupernodalSolver(int, char*[])
{
  const Eigen::SparseMatrix<double> k = GridSystem(36, 18, 18, 100.0);
  const Eigen::Index n = k.rows();
  Cholesky chol;
  chol.compute(k);
  AV_CHECK(chol.info() == Eigen::Success);
  const cholmod_factor& f = *chol.Factor();
  AV_CHECK(f.is_super);

  std::mt19937 rng(3);
  std::normal_distribution<double> nd;
  for (int nrhs : { 1, 5, 11 })
  {
    Eigen::MatrixXd b(n, nrhs);
    for (Eigen::Index i = 0; i < b.size(); ++i)
    {
      b.data()[i] = nd(rng);
    }
    const Eigen::MatrixXd ref = chol.solve(b);
    double reference = -1.0;
    for (std::size_t taskWork : { std::size_t(0), std::size_t(500), std::size_t(1) << 40 })
    {
      const av::FloatSupernodalSolver solver(f, taskWork);
      AV_CHECK(solver.Rows() == static_cast<std::size_t>(n));
      AV_CHECK(solver.FactorEntries() == f.xsize);
      if (taskWork == 500)
      {
        AV_CHECK_MSG(solver.NumTasks() > 8, solver.NumTasks()); // the split is exercised
      }
      if (taskWork == (std::size_t(1) << 40))
      {
        AV_CHECK(solver.NumTasks() <= 1); // one subtree or everything at the top
      }
      Eigen::MatrixXd x(n, nrhs);
      solver.Solve(b.data(), x.data(), nrhs);
      const double err = (x - ref).norm() / ref.norm();
      std::cout << "nrhs " << nrhs << " taskWork " << taskWork << " tasks " << solver.NumTasks() << " top " << solver.NumTopSupernodes() << " error " << err << " residual " << (k * x - b).norm() / b.norm() << "\n";
      AV_CHECK_MSG(err < 1e-5, "nrhs " << nrhs << " taskWork " << taskWork << " error " << err);
      // The residual carries the factor's float rounding times the (large) matrix norm: far below
      // a wrong answer's O(1).
      const double res = (k * x - b).norm() / b.norm();
      AV_CHECK_MSG(res < 1e-2, "residual " << res);
      // Same factor, same split: bit-identical on a second solve; in place works.
      Eigen::MatrixXd y = b;
      solver.Solve(y.data(), y.data(), nrhs);
      AV_CHECK(y == x);
      if (reference < 0.0)
      {
        reference = err;
      }
    }
  }
  return AV_TEST_RESULT();
}
