// SPDX-License-Identifier: BSD-3-Clause
// TetLocalStepKernel (four tets per SIMD vector) against a direct reference: T from the
// embedded vertices, polar factor of B = T A by SVD, R = V A, energy w‖T − R‖², C = w G R_fᵀ.
#include "TetLocalStepKernel.h"
#include "AnisoTestChecks.h"

#include <Eigen/Dense>

#include <cstdint>
#include <iostream>
#include <random>
#include <vector>

int TestTetLocalStepKernel(int, char*[])
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (int dim : { 4, 5, 6, 8, 10 })
  {
    const int ft = dim - 3;
    AV_CHECK(av::HasTetLocalStepKernel(dim));
    const std::size_t ne = 23; // not a multiple of 4: the padded tail is exercised
    const std::size_t np = 4 * ne;
    std::vector<std::int32_t> cells(4 * ne);
    std::vector<double> gt(12 * ne), a(9 * ne), w(ne), x(np * dim);
    for (std::size_t j = 0; j < ne; ++j)
    {
      Eigen::Matrix3d edges;
      for (int l = 0; l < 4; ++l)
      {
        cells[4 * j + l] = static_cast<std::int32_t>(4 * j + l);
        for (int c = 0; c < dim; ++c)
        {
          x[(4 * j + l) * dim + c] = uni(rng);
        }
      }
      for (int l = 0; l < 3; ++l)
      {
        for (int c = 0; c < 3; ++c)
        {
          edges(c, l) = x[(4 * j + l + 1) * dim + c] - x[(4 * j) * dim + c];
        }
      }
      const Eigen::Matrix3d inv = edges.inverse(); // rows: gradients of vertices 1..3
      for (int c = 0; c < 3; ++c)
      {
        gt[12 * j + c] = -(inv(0, c) + inv(1, c) + inv(2, c));
        for (int l = 0; l < 3; ++l)
        {
          gt[12 * j + (l + 1) * 3 + c] = inv(l, c);
        }
      }
      // A: symmetric, eigenvalues in [1, 25]; the last element is nearly singular instead.
      const Eigen::Matrix3d q = Eigen::Matrix3d::Random().householderQr().householderQ();
      Eigen::Vector3d ev(1.0 + 24.0 * std::abs(uni(rng)), 1.0 + 3.0 * std::abs(uni(rng)), 1.0);
      if (j == ne - 2)
      {
        ev(2) = 1e-9;
      }
      Eigen::Map<Eigen::Matrix3d>(a.data() + 9 * j) = q * ev.asDiagonal() * q.transpose();
      w[j] = 0.5 + std::abs(uni(rng));
    }
    std::vector<double> c(ne * 4 * ft, -12345.0);
    av::TetLocalStepData d;
    d.Cells = cells.data();
    d.Gt = gt.data();
    d.A = a.data();
    d.W = w.data();
    d.X = x.data();
    d.Stride = dim;
    d.C = c.data();
    std::vector<std::int32_t> failed;
    const double energy = av::TetLocalStepRange(d, 0, ne, failed);
    AV_CHECK_MSG(failed.size() == 1 && failed[0] == static_cast<std::int32_t>(ne - 2), failed.size());

    double refEnergy = 0.0, worstC = 0.0;
    for (std::size_t j = 0; j < ne; ++j)
    {
      Eigen::MatrixXd t = Eigen::MatrixXd::Zero(dim, 3);
      for (int l = 0; l < 4; ++l)
      {
        for (int r = 0; r < dim; ++r)
        {
          for (int cc = 0; cc < 3; ++cc)
          {
            t(r, cc) += x[(4 * j + l) * dim + r] * gt[12 * j + l * 3 + cc];
          }
        }
      }
      const Eigen::Matrix3d am = Eigen::Map<const Eigen::Matrix3d>(a.data() + 9 * j);
      const Eigen::MatrixXd b = t * am;
      Eigen::JacobiSVD<Eigen::MatrixXd> svd(b, Eigen::ComputeThinU | Eigen::ComputeThinV);
      const Eigen::MatrixXd r = svd.matrixU() * svd.matrixV().transpose() * am;
      if (j == ne - 2)
      {
        AV_CHECK(c[(j * 4) * ft] == -12345.0); // nothing written for a failed element
        continue;
      }
      AV_CHECK_NEAR(t.topRows(3).norm(), std::sqrt(3.0), 1e-10); // the identity rows
      refEnergy += w[j] * (t - r).squaredNorm();
      for (int l = 0; l < 4; ++l)
      {
        for (int f = 0; f < ft; ++f)
        {
          double ref = 0.0;
          for (int cc = 0; cc < 3; ++cc)
          {
            ref += w[j] * gt[12 * j + l * 3 + cc] * r(3 + f, cc);
          }
          worstC = std::max(worstC, std::abs(c[(j * 4 + l) * ft + f] - ref) / (1.0 + std::abs(ref)));
        }
      }
    }
    std::cout << "dim " << dim << ": energy " << energy << " (reference " << refEnergy
              << "), worst C deviation " << worstC << "\n";
    // Same digits as the C check below: an -O2 sanitizer build misses 1e-9 at dim 10.
    AV_CHECK_NEAR(energy, refEnergy, 1e-7 * refEnergy);
    AV_CHECK(worstC < 1e-7); // random, badly shaped tets: the closed form loses a few digits
  }
  return AV_TEST_RESULT();
}
