// SPDX-License-Identifier: BSD-3-Clause
// EmbeddingSolver local step: the optimal rotation of every element (polar factor of B = T A),
// its right-hand side contribution, and the energies E_em and E_reg of the iterate.
#include "EmbeddingSolverInternals.h"

#include "MetricAlgebra.h"
#include "Stopwatch.h"
#include "TetLocalStepKernel.h"

#include <Eigen/Eigenvalues>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <queue>
#include <utility>
#include <vector>

namespace av
{

namespace
{

/// tr C^{1/2} = sum of sqrt(eigenvalues) of a symmetric positive definite 3x3 matrix with
/// invariants ic1 = tr C, ic2, ic3 = det C, without eigenvalues (no trigonometry: about half the
/// cost of SelfAdjointEigenSolver::computeDirect). s = tr U, U = C^{1/2}, satisfies
/// (s² − ic1)² − 8 √ic3 s − 4 ic2 = 0 (from s² = ic1 + 2 i2, i2² = ic2 + 2 s √ic3); the quartic is
/// convex for s ≥ √ic1 with one root there, so Newton from an upper bound decreases
/// monotonically to it. Returns false if it does not converge.
bool TraceOfSqrtSpd3(double ic1, double ic2, double ic3, double& s)
{
  const double i3 = std::sqrt(ic3);
  s = std::sqrt(ic1 + 2.0 * std::sqrt(3.0 * ic2)); // i2 <= sqrt(3 ic2) (Cauchy-Schwarz)
  for (int it = 0; it < 60; ++it)
  {
    const double q = s * s - ic1;
    const double ds = (q * q - 8.0 * i3 * s - 4.0 * ic2) / (4.0 * s * q - 8.0 * i3);
    s -= ds;
    if (std::abs(ds) <= 1e-7 * s) // quadratic convergence: the error left is ~ds²/s
    {
      return std::isfinite(s);
    }
  }
  return false;
}

/// C^{-1/2} of a symmetric positive definite 3x3 matrix; false when C is (nearly) singular.
/// From the invariants of U = C^{1/2} by Cayley-Hamilton (U^3 - i1 U^2 + i2 U - i3 I = 0), which
/// needs no eigenvectors and is stable for repeated eigenvalues.
bool InverseSqrtSpd3(const Eigen::Matrix3d& c, Eigen::Matrix3d& cinv)
{
  const double ic1 = c.trace();
  const double ic2 = c(0, 0) * c(1, 1) + c(1, 1) * c(2, 2) + c(0, 0) * c(2, 2) -
    c(0, 1) * c(1, 0) - c(1, 2) * c(2, 1) - c(0, 2) * c(2, 0);
  const double ic3 = c.determinant();
  double i1 = 0.0, i2 = 0.0, i3 = 0.0;
  // Well conditioned (smallest eigenvalue >= ic3 / ic2 > 1e-8 ic1): the invariant route.
  if (ic3 > 1e-8 * ic1 * ic2 && ic2 > 0.0 && TraceOfSqrtSpd3(ic1, ic2, ic3, i1))
  {
    i2 = 0.5 * (i1 * i1 - ic1);
    i3 = std::sqrt(ic3);
  }
  else
  {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
    es.computeDirect(c, Eigen::EigenvaluesOnly);
    const Eigen::Vector3d ev = es.eigenvalues();
    if (!(ev(0) > 1e-8 * ev(2) && ev(0) > 0.0))
    {
      return false;
    }
    const double s0 = std::sqrt(ev(0)), s1 = std::sqrt(ev(1)), s2 = std::sqrt(ev(2));
    i1 = s0 + s1 + s2;
    i2 = s0 * s1 + s1 * s2 + s0 * s2;
    i3 = s0 * s1 * s2;
  }
  // U = ((i1² − i2) C − C² + i1 i3 I) / (i1 i2 − i3), U⁻¹ = (C − i1 U + i2 I) / i3; reciprocals
  // once (Eigen divides a matrix by a scalar entry by entry).
  Eigen::Matrix3d u = (i1 * i1 - i2) * c - c * c;
  u.diagonal().array() += i1 * i3;
  u *= 1.0 / (i1 * i2 - i3);
  cinv = c - i1 * u;
  cinv.diagonal().array() += i2;
  cinv *= 1.0 / i3;
  return true;
}

/**
 * Surfaces: R = V A for the polar factor V of the rank-2 B = T A (T is zero along the triangle
 * normal), without an SVD. B's null vector w is the largest column of adj(BᵀB) (rank 1 when BᵀB
 * has rank 2); with Q an orthonormal basis of w's complement, V Q = B Q (QᵀBᵀBQ)^{-1/2} and
 * R = (V Q)(Qᵀ A). The third column of a full polar factor (any unit u ⟂ range B, times wᵀ)
 * changes neither the right-hand side (G's rows are in the triangle plane) nor the optimum;
 * it adds ‖A w‖² to ‖T − R‖², returned in `normalTerm` so that the energy is the SVD route's.
 * False when B has rank below 2 (the caller then takes the SVD).
 */
template <typename MatB>
bool RankTwoRotatedMetric(const MatB& b, const Eigen::Matrix3d& a, MatB& r, double& normalTerm)
{
  const Eigen::Matrix3d s = b.transpose() * b;
  // Cofactors of the symmetric s: adj(s) = λ1 λ2 w wᵀ + O(λ3).
  Eigen::Matrix3d adj;
  adj(0, 0) = s(1, 1) * s(2, 2) - s(1, 2) * s(1, 2);
  adj(1, 1) = s(0, 0) * s(2, 2) - s(0, 2) * s(0, 2);
  adj(2, 2) = s(0, 0) * s(1, 1) - s(0, 1) * s(0, 1);
  adj(0, 1) = adj(1, 0) = s(0, 2) * s(1, 2) - s(0, 1) * s(2, 2);
  adj(0, 2) = adj(2, 0) = s(0, 1) * s(1, 2) - s(0, 2) * s(1, 1);
  adj(1, 2) = adj(2, 1) = s(0, 1) * s(0, 2) - s(0, 0) * s(1, 2);
  int k = 0;
  adj.diagonal().maxCoeff(&k); // the largest column has the largest diagonal entry (PSD)
  const double tr = s.trace();
  if (!(adj(k, k) > 1e-16 * tr * tr))
  {
    return false;
  }
  const Eigen::Vector3d w = adj.col(k).normalized();
  // Orthonormal q0, q1 with w: start from the axis least aligned with w.
  int axis = 0;
  w.cwiseAbs().minCoeff(&axis);
  Eigen::Vector3d q0 = -w(axis) * w;
  q0(axis) += 1.0;
  q0.normalize();
  Eigen::Matrix<double, 3, 2> q;
  q.col(0) = q0;
  q.col(1) = w.cross(q0);
  const Eigen::Matrix2d c = q.transpose() * s * q;
  const SymmetricEigen2 es = EigenDecompose(c);
  if (!(es.Values(0) > 1e-8 * es.Values(1) && es.Values(0) > 0.0))
  {
    return false;
  }
  const Eigen::Vector2d inv = es.Values.cwiseSqrt().cwiseInverse();
  const Eigen::Matrix<double, 2, 3> qa = q.transpose() * a;
  const Eigen::Matrix<double, 2, 3> n = es.Vectors * inv.asDiagonal() * es.Vectors.transpose() * qa;
  r.noalias() = (b * q) * n;
  normalTerm = (a * w).squaredNorm();
  return true;
}

/// Polar factor V (orthonormal columns) of B (rows x M): V = B (B^T B)^{-1/2}; SVD fallback for
/// (nearly) rank-deficient B (surfaces with rank-2 metrics).
template <int M, bool RankDeficient, typename MatB>
void PolarFactor(const MatB& b, MatB& v)
{
  // Dynamic columns bounded by M (no heap): Eigen's thin U/V need a dynamic column count.
  using MatS = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kEmbeddingMaxTargetDim, M>;
  if constexpr (RankDeficient)
  {
    // Surfaces: B = T A has rank 2; the closed form would amplify round-off along the normal.
    Eigen::JacobiSVD<MatS> svd(MatS(b), Eigen::ComputeThinU | Eigen::ComputeThinV);
    v = svd.matrixU() * svd.matrixV().transpose();
    return;
  }
  using MatM = Eigen::Matrix<double, M, M>;
  const MatM c = b.transpose() * b;
  if constexpr (M == 3)
  {
    MatM cinv;
    if (InverseSqrtSpd3(c, cinv))
    {
      v.noalias() = b * cinv;
      return;
    }
  }
  else
  {
    // Closed-form eigenvectors are accurate enough when B is well conditioned (always the case
    // for volumes and 2D domains: the fixed input rows make sigma_min(T) >= 1).
    const SymmetricEigen2 es = EigenDecompose(Eigen::Matrix2d(c));
    const Eigen::Matrix<double, M, 1> ev = es.Values;
    if (ev(0) > 1e-8 * ev(M - 1) && ev(0) > 0.0)
    {
      const Eigen::Matrix<double, M, 1> inv = ev.cwiseSqrt().cwiseInverse();
      v.noalias() = b * (es.Vectors * inv.asDiagonal() * es.Vectors.transpose());
      return;
    }
  }
  // One SVD instantiation per M (compile time): copy into a bounded dynamic-size matrix.
  Eigen::JacobiSVD<MatS> svd(MatS(b), Eigen::ComputeThinU | Eigen::ComputeThinV);
  v = svd.matrixU() * svd.matrixV().transpose();
}
} // namespace

template <int MBT, int MT, int KT>
double EmbeddingSolver::Internals::LocalStepT()
{
  constexpr int NV = KT + 1;
  constexpr int MaxRows = MBT == Eigen::Dynamic ? kEmbeddingMaxTargetDim : MBT;
  using MatB = Eigen::Matrix<double, MBT, MT, 0, MaxRows, MT>;
  using VecB = Eigen::Matrix<double, MBT, 1, 0, MaxRows, 1>;
  using MatG = Eigen::Matrix<double, NV, MT, Eigen::RowMajor>;
  using MatM = Eigen::Matrix<double, MT, MT>;
  using MatC =
    Eigen::Matrix<double, NV, Eigen::Dynamic, Eigen::RowMajor, NV, kEmbeddingMaxTargetDim>;
  constexpr bool kFastVolume = MT == 3 && KT == 3 && MBT != Eigen::Dynamic;
  constexpr int FT = kFastVolume ? MBT - MT : 1; // free dimensions (compile time)
  using MatF = Eigen::Matrix<double, FT, MT>;
  using VecF = Eigen::Matrix<double, FT, 1>;
  using MatCF = Eigen::Matrix<double, NV, FT, FT == 1 ? Eigen::ColMajor : Eigen::RowMajor>;
  const int mb = this->MB, nf = this->F;
  const std::size_t ne = this->NE;
  const std::size_t nchunks = (ne + kEmbeddingChunk - 1) / kEmbeddingChunk;
  std::vector<double> partial(nchunks, 0.0);
  // Tets: four elements per SIMD vector (TetLocalStepKernel); the elements it cannot take (an
  // ill-conditioned BᵀB) come back in a list for the general path below.
  const bool useKernel = kFastVolume && HasTetLocalStepKernel(mb);
  TetLocalStepData kernelData;
  kernelData.Cells = this->Cells.data();
  kernelData.Gt = this->Gt.data();
  kernelData.A = this->A.data();
  kernelData.W = this->W.data();
  kernelData.X = this->X.data();
  kernelData.Stride = mb;
  kernelData.C = this->C.data();
  tbb::parallel_for(std::size_t(0), nchunks, [&](std::size_t ch) {
    const std::size_t j0 = ch * kEmbeddingChunk, j1 = std::min(ne, j0 + kEmbeddingChunk);
    double e = 0.0;
    std::vector<std::int32_t> failed;
    if (useKernel)
    {
      e = TetLocalStepRange(kernelData, j0, j1, failed);
    }
    MatB t(mb, MT), b(mb, MT), v(mb, MT), r(mb, MT);
    const std::size_t count = useKernel ? failed.size() : j1 - j0;
    for (std::size_t k = 0; k < count; ++k)
    {
      const std::size_t j = useKernel ? static_cast<std::size_t>(failed[k]) : j0 + k;
      const std::int32_t* cell = this->Cells.data() + j * NV;
      const Eigen::Map<const MatG> g(this->Gt.data() + j * NV * MT);
      const Eigen::Map<const MatM> a(this->A.data() + j * MT * MT);
      if constexpr (kFastVolume)
      {
        // Tets: the first 3 rows of T are the identity (the input coordinates do not move), so
        // B = [I; T_f] A, BᵀB = A (I + T_fᵀT_f) A and R = V A = T N with N = A (BᵀB)^{-1/2} A:
        // only the free rows are formed.
        MatF tf = MatF::Zero();
        for (int l = 0; l < NV; ++l)
        {
          const Eigen::Map<const VecF> x(
            this->X.data() + static_cast<std::size_t>(cell[l]) * mb + MT);
          tf.noalias() += x * g.row(l);
        }
        MatM pm = tf.transpose() * tf;
        pm.diagonal().array() += 1.0;
        const MatM bb = a * pm * a;
        MatM cinv;
        if (InverseSqrtSpd3(bb, cinv))
        {
          const MatM n = a * cinv * a;
          const MatF rf = tf * n;
          MatM d = -n;
          d.diagonal().array() += 1.0;
          const double w = this->W[j];
          e += w * (d.squaredNorm() + (tf - rf).squaredNorm());
          Eigen::Map<MatCF> c(this->C.data() + j * NV * nf);
          c.noalias() = w * g * rf.transpose();
          continue;
        }
      }
      t.setZero();
      for (int l = 0; l < NV; ++l)
      {
        const Eigen::Map<const VecB> x(this->X.data() + static_cast<std::size_t>(cell[l]) * mb, mb);
        t.noalias() += x * g.row(l);
      }
      b.noalias() = t * a; // A is symmetric: T A^T = T A
      double normalTerm = 0.0;
      bool done = false;
      if constexpr (KT < MT && MT == 3)
      {
        done = RankTwoRotatedMetric(b, Eigen::Matrix3d(a), r, normalTerm);
      }
      if (!done)
      {
        PolarFactor<MT, (KT < MT)>(b, v);
        r.noalias() = v * a;
      }
      const double w = this->W[j];
      e += w * ((t - r).squaredNorm() + normalTerm);
      Eigen::Map<MatC> c(this->C.data() + j * NV * nf, NV, nf);
      c.noalias() = w * g * r.bottomRows(nf).transpose();
    }
    partial[ch] = e;
  });
  double sum = 0.0;
  for (double p : partial)
  {
    sum += p;
  }
  return sum;
}

double EmbeddingSolver::Internals::RegularizerEnergy() const
{
  const int mb = this->MB, m = this->M;
  const std::size_t np = this->NP;
  const std::size_t nchunks = (np + kEmbeddingChunk - 1) / kEmbeddingChunk;
  std::vector<double> partial(nchunks, 0.0);
  tbb::parallel_for(std::size_t(0), nchunks, [&](std::size_t ch) {
    double e = 0.0;
    double lap[kEmbeddingMaxTargetDim];
    for (std::size_t i = ch * kEmbeddingChunk; i < std::min(np, (ch + 1) * kEmbeddingChunk); ++i)
    {
      if (!this->Interior[i])
      {
        continue;
      }
      const double inv = 1.0 / (this->NOff[i + 1] - this->NOff[i]);
      for (int d = m; d < mb; ++d)
      {
        lap[d] = 0.0;
      }
      for (std::int32_t q = this->NOff[i]; q < this->NOff[i + 1]; ++q)
      {
        const double* xk = this->X.data() + static_cast<std::size_t>(this->NIdx[q]) * mb;
        for (int d = m; d < mb; ++d)
        {
          lap[d] += xk[d];
        }
      }
      const double* xi = this->X.data() + i * mb;
      for (int d = m; d < mb; ++d)
      {
        const double l = lap[d] * inv - xi[d];
        e += l * l;
      }
    }
    partial[ch] = e;
  });
  double sum = 0.0;
  for (double p : partial)
  {
    sum += p;
  }
  return sum * this->RegularizerScale;
}

namespace
{
/// M_j = A_j² of an element (A row-major m x m), zero-padded to 3 x 3, and its eigenvectors
/// (columns) with sqrt(max(λ - 1, 0)) in decreasing order of λ.
void ExcessEigen(const double* aj, int m, Eigen::Matrix3d& vectors, Eigen::Vector3d& roots)
{
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  for (int r = 0; r < m; ++r)
    for (int c = 0; c < m; ++c)
      a(r, c) = aj[r * m + c];
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(a * a);
  for (int k = 0; k < 3; ++k) // computeDirect sorts increasingly: reverse
  {
    vectors.col(k) = es.eigenvectors().col(2 - k);
    roots(k) = std::sqrt(std::max(0.0, es.eigenvalues()(2 - k) - 1.0));
  }
}
} // namespace

void EmbeddingSolver::Internals::BuildAlignedTargets(bool eigenFrame)
{
  const int m = this->M;
  this->AlignedTarget.resize(this->NE);
  std::vector<Eigen::Matrix3d>& frames = this->AlignedFrames;
  std::vector<Eigen::Vector3d>& roots = this->AlignedRoots;
  if (frames.size() != this->NE)
  {
    // Once for both targets: the orientation below flips signs only, which the symmetric
    // root V diag Vᵀ does not see.
    frames.resize(this->NE);
    roots.resize(this->NE);
    tbb::parallel_for(std::size_t(0), this->NE, [&](std::size_t j) {
      ExcessEigen(this->A.data() + j * m * m, m, frames[j], roots[j]);
    });
  }
  if (eigenFrame)
  {
    // Orient the eigenvectors so that sqrt(λ_k - 1) v_kᵀ varies smoothly: for a field
    // M = I + (S² - 1) u uᵀ whose u is a gradient direction (radial, a wall normal) the target
    // is then the gradient of H with H' = sqrt(S² - 1), an exact embedding (x, H). First the
    // vertices (the mean of their elements' metrics), each like the edge neighbour it is reached
    // from, most anisotropic first (Prim's order on the gap λ1 - λ2: the best defined top
    // eigenvectors lead), then every element like the mean of its vertices.
    const int nv = this->K + 1;
    const std::size_t np = this->NP;
    std::vector<Eigen::Matrix3d> vframe(np);
    std::vector<double> vgap(np, 0.0);
    tbb::parallel_for(std::size_t(0), np, [&](std::size_t i) {
      Eigen::Matrix3d mean = Eigen::Matrix3d::Zero();
      for (std::int32_t q = this->VOff[i]; q < this->VOff[i + 1]; ++q)
      {
        const std::size_t j = static_cast<std::size_t>(this->VInc[q] / nv);
        mean += frames[j] * (roots[j].array().square() + 1.0).matrix().asDiagonal() * frames[j].transpose();
      }
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
      es.computeDirect(mean);
      for (int k = 0; k < 3; ++k)
        vframe[i].col(k) = es.eigenvectors().col(2 - k);
      vgap[i] = es.eigenvalues()(2) - es.eigenvalues()(1);
    });
    std::vector<std::int32_t> order(np);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](std::int32_t x, std::int32_t y) { return vgap[x] > vgap[y]; });
    std::vector<char> seen(np, 0);
    using Entry = std::pair<double, std::pair<std::int32_t, std::int32_t>>; // gap, (vertex, from)
    std::priority_queue<Entry> heap;
    for (const std::int32_t seed : order)
    {
      if (seen[seed])
        continue;
      heap.push({ vgap[seed], { seed, -1 } });
      while (!heap.empty())
      {
        const std::int32_t i = heap.top().second.first, from = heap.top().second.second;
        heap.pop();
        if (seen[i])
          continue;
        seen[i] = 1;
        if (from >= 0)
          for (int k = 0; k < 3; ++k)
            if (vframe[i].col(k).dot(vframe[from].col(k)) < 0.0)
              vframe[i].col(k) = -vframe[i].col(k);
        for (std::int32_t q = this->NOff[i]; q < this->NOff[i + 1]; ++q)
          if (!seen[this->NIdx[q]])
            heap.push({ vgap[this->NIdx[q]], { this->NIdx[q], i } });
      }
    }
    tbb::parallel_for(std::size_t(0), this->NE, [&](std::size_t j) {
      for (int k = 0; k < 3; ++k)
      {
        Eigen::Vector3d ref = Eigen::Vector3d::Zero();
        for (int l = 0; l < nv; ++l)
          ref += vframe[this->Cells[j * nv + l]].col(k);
        if (frames[j].col(k).dot(ref) < 0.0)
          frames[j].col(k) = -frames[j].col(k);
      }
    });
  }
  tbb::parallel_for(std::size_t(0), this->NE, [&](std::size_t j) {
    // Rows: the first m free axes. Eigen frame: free axis k carries eigen-direction k;
    // symmetric: Q (M - I)^{1/2}, the free vector turning with the frame.
    const Eigen::Matrix3d scaled = roots[j].asDiagonal() * frames[j].transpose();
    this->AlignedTarget[j] = eigenFrame ? scaled : Eigen::Matrix3d(frames[j] * scaled);
  });
}

void EmbeddingSolver::Internals::SeedMetricAlignedRightHandSides()
{
  const int m = this->M, nf = this->F, nv = this->K + 1;
  tbb::parallel_for(std::size_t(0), this->NE, [&](std::size_t j) {
    const Eigen::Matrix3d& target = this->AlignedTarget[j];
    const double w = this->W[j];
    const double* g = this->Gt.data() + j * nv * m;
    double* c = this->C.data() + j * nv * nf;
    // c(v, d) = w (G targetᵀ)(v, d) for the first m free axes, 0 for the others.
    for (int v = 0; v < nv; ++v)
      for (int d = 0; d < nf; ++d)
      {
        double s = 0.0;
        for (int k = 0; d < m && k < m; ++k)
          s += g[v * m + k] * target(d, k);
        c[v * nf + d] = w * s;
      }
  });
}

double EmbeddingSolver::Internals::MetricAlignedResidual() const
{
  const int m = this->M, nv = this->K + 1, mb = this->MB;
  // Fixed chunks summed in order: the same value whatever the thread count (it decides).
  const std::size_t nchunks = (this->NE + kEmbeddingChunk - 1) / kEmbeddingChunk;
  std::vector<double> residual(nchunks, 0.0), norm(nchunks, 0.0);
  tbb::parallel_for(std::size_t(0), nchunks, [&](std::size_t ch) {
    const std::size_t j1 = std::min(this->NE, (ch + 1) * kEmbeddingChunk);
    for (std::size_t j = ch * kEmbeddingChunk; j < j1; ++j)
    {
      const Eigen::Matrix3d& target = this->AlignedTarget[j];
      const double* g = this->Gt.data() + j * nv * m;
      const std::int32_t* cell = this->Cells.data() + j * nv;
      for (int d = 0; d < m; ++d)
        for (int k = 0; k < m; ++k)
        {
          double t = 0.0; // free Jacobian entry (d, k)
          for (int v = 0; v < nv; ++v)
            t += this->X[static_cast<std::size_t>(cell[v]) * mb + m + d] * g[v * m + k];
          residual[ch] += this->W[j] * (t - target(d, k)) * (t - target(d, k));
          norm[ch] += this->W[j] * target(d, k) * target(d, k);
        }
    }
  });
  const double r = std::accumulate(residual.begin(), residual.end(), 0.0);
  const double n = std::accumulate(norm.begin(), norm.end(), 0.0);
  return n > 0.0 ? r / n : 0.0;
}

EmbeddingEnergy EmbeddingSolver::Internals::LocalStep()
{
  const Stopwatch clock;
  double em = 0.0;
  const int key = this->M * 10 + this->K;
  // Compile-time target dimensions for the common cases, bounded dynamic size otherwise.
  switch (key * 100 + this->MB)
  {
    case 2203:
      em = this->LocalStepT<3, 2, 2>();
      break;
    case 2204:
      em = this->LocalStepT<4, 2, 2>();
      break;
    case 2208:
      em = this->LocalStepT<8, 2, 2>();
      break;
    case 3204:
      em = this->LocalStepT<4, 3, 2>();
      break;
    case 3208:
      em = this->LocalStepT<8, 3, 2>();
      break;
    case 3304:
      em = this->LocalStepT<4, 3, 3>();
      break;
    case 3305:
      em = this->LocalStepT<5, 3, 3>();
      break;
    case 3306:
      em = this->LocalStepT<6, 3, 3>();
      break;
    case 3308:
      em = this->LocalStepT<8, 3, 3>();
      break;
    case 3310:
      em = this->LocalStepT<10, 3, 3>();
      break;
    default:
      if (key == 33)
      {
        em = this->LocalStepT<Eigen::Dynamic, 3, 3>();
      }
      else if (key == 32)
      {
        em = this->LocalStepT<Eigen::Dynamic, 3, 2>();
      }
      else
      {
        em = this->LocalStepT<Eigen::Dynamic, 2, 2>();
      }
      break;
  }
  EmbeddingEnergy e;
  e.Embedding = em;
  e.Regularization = this->RegularizerEnergy();
  e.Total = e.Embedding + this->Options.Mu * e.Regularization;
  this->Energy = e;
  this->LocalSeconds += clock.Seconds();
  return e;
}

} // namespace av
