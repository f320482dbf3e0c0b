#include "EmbeddingSolver.h"

#include "FloatSupernodalSolver.h"
#include "TetLocalStepKernel.h"

#include "MetricAlgebra.h"
#include "MeshTopology.h"

#include <Eigen/CholmodSupport>
#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <thread>

namespace av
{

namespace
{
using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

constexpr int kMaxTargetDim = 20;
// Fixed chunking of element / vertex loops: partial sums are added in chunk order, so energies
// do not depend on the number of threads.
constexpr std::size_t kChunk = 2048;

std::string Str(double v)
{
  std::ostringstream s;
  s << v;
  return s.str();
}

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

/// Polar factor V (orthonormal columns) of B (rows x M): V = B (B^T B)^{-1/2}; SVD fallback for
/// (nearly) rank-deficient B (surfaces with rank-2 metrics).
template <int M, bool RankDeficient, typename MatB>
void PolarFactor(const MatB& b, MatB& v)
{
  using MatS = Eigen::Matrix<double, Eigen::Dynamic, M, 0, kMaxTargetDim, M>;
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
  std::vector<std::int32_t> NOff, NIdx; // one-ring neighbours CSR
  std::vector<char> Interior;           // regulariser rows
  std::vector<std::int32_t> Reduced;    // vertex -> unknown index, -1 when pinned
  std::vector<double> X;                // NP x MB row-major: the embedding
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
  Eigen::MatrixXd LastRhs;                            // right-hand sides of the last global step
  EmbeddingEnergy Energy;
  double SetupSeconds = 0.0, FactorSeconds = 0.0;
  mutable double LocalSeconds = 0.0, SolveSeconds = 0.0;
  std::size_t FactorNonZeros = 0;
  bool Ran = false;

  void Validate(const SimplexMesh& mesh, const MetricField& metric);
  void BuildElements(const SimplexMesh& mesh, const MetricField& metric);
  void BuildTopology(const SimplexMesh& mesh);
  /// Lower triangle of K, column by column; Values = false: the pattern only (needs only the
  /// topology, so the ordering can be computed while the element operators are built).
  void AssembleLower(bool values, Eigen::SparseMatrix<double>& kmat, std::vector<double>* vals);
  void Factor(Eigen::SparseMatrix<double>& kmat, const std::vector<double>& vals, double analyseSeconds);
  void Initialise(const SimplexMesh& mesh);

  EmbeddingEnergy LocalStep();
  template <int MBT, int MT, int KT>
  double LocalStepT();
  double RegulariserEnergy() const;
  Eigen::MatrixXd GlobalStep();
  Eigen::MatrixXd RedoGlobalStepInDouble();
  Eigen::MatrixXd GetFree() const;
  void SetFree(const Eigen::MatrixXd& xr);
};

void EmbeddingSolver::Internals::Validate(const SimplexMesh& mesh, const MetricField& metric)
{
  const EmbeddingOptions& o = this->Options;
  if (!((mesh.AmbientDim == 2 && mesh.SimplexDim == 2) ||
        (mesh.AmbientDim == 3 && (mesh.SimplexDim == 3 || mesh.SimplexDim == 2))))
  {
    throw InputError("embedding: unsupported mesh (AmbientDim " + std::to_string(mesh.AmbientDim) +
      ", SimplexDim " + std::to_string(mesh.SimplexDim) +
      "); expected a 2D triangle mesh, a 3D tetrahedral mesh or a triangle surface in 3D");
  }
  if (mesh.NumPoints() == 0 || mesh.NumCells() == 0)
  {
    throw InputError("embedding: the input mesh is empty (" + std::to_string(mesh.NumPoints()) +
      " points, " + std::to_string(mesh.NumCells()) + " cells)");
  }
  if (mesh.Points.size() != mesh.NumPoints() * mesh.AmbientDim ||
    mesh.Cells.size() != mesh.NumCells() * mesh.VerticesPerCell())
  {
    throw InputError("embedding: point or cell array size is not a multiple of its tuple size");
  }
  if (mesh.NumPoints() > static_cast<std::size_t>(INT32_MAX / 64))
  {
    throw InputError("embedding: mesh too large");
  }
  if (o.TargetDim < mesh.AmbientDim + 1 || o.TargetDim > kMaxTargetDim)
  {
    throw InputError("embedding: target dimension " + std::to_string(o.TargetDim) +
      " out of range; it must be in [" + std::to_string(mesh.AmbientDim + 1) + ", " +
      std::to_string(kMaxTargetDim) + "] for a mesh in " + std::to_string(mesh.AmbientDim) + "D");
  }
  if (o.Iterations < 0 || !(o.Mu >= 0.0) || !std::isfinite(o.Mu) || o.AndersonWindow < 0 ||
    o.AndersonWindow > 50 || !(o.RelativeEnergyTolerance >= 0.0) || !std::isfinite(o.InitialAmplitude))
  {
    throw InputError("embedding: invalid options (need Iterations >= 0, finite Mu >= 0, "
                     "AndersonWindow in [0, 50], RelativeEnergyTolerance >= 0)");
  }
  if (metric.Values.size() != 6 * mesh.NumPoints())
  {
    throw InputError("embedding: metric has " + std::to_string(metric.Values.size()) +
      " values; expected 6 per point (" + std::to_string(6 * mesh.NumPoints()) + ")");
  }
  if (!AllFinite(mesh.Points.data(), static_cast<int>(mesh.Points.size())))
  {
    throw InputError("embedding: the input points contain NaN or Inf");
  }
  const std::int32_t np = static_cast<std::int32_t>(mesh.NumPoints());
  for (std::int32_t id : mesh.Cells)
  {
    if (id < 0 || id >= np)
    {
      throw InputError("embedding: cell refers to point " + std::to_string(id) + ", mesh has " +
        std::to_string(np) + " points");
    }
  }
  // Metric: finite, SPD (volumes, 2D) or PSD (surfaces). Report the first bad vertex.
  for (std::size_t i = 0; i < mesh.NumPoints(); ++i)
  {
    const double* v = metric.At(i);
    if (!AllFinite(v, 6))
    {
      throw InputError("embedding: metric at point " + std::to_string(i) + " contains NaN or Inf");
    }
    bool ok;
    if (mesh.AmbientDim == 2)
    {
      ok = IsPositiveDefinite(UnpackSymmetric2(v));
    }
    else if (mesh.SimplexDim == 3)
    {
      ok = IsPositiveDefinite(UnpackSymmetric(v));
    }
    else
    {
      ok = IsPositiveSemiDefinite(UnpackSymmetric(v));
    }
    if (!ok)
    {
      throw InputError("embedding: metric at point " + std::to_string(i) + " is not " +
        (mesh.SimplexDim == 2 && mesh.AmbientDim == 3 ? "positive semi-definite"
                                                      : "symmetric positive definite") +
        "; convert/clamp the tensor field into a metric first");
    }
  }
  // Elements: non-degenerate, and (volumes, 2D) consistently oriented.
  std::size_t positive = 0, negative = 0, firstNeg = 0, firstPos = 0;
  for (std::size_t c = 0; c < mesh.NumCells(); ++c)
  {
    const std::int32_t* cell = mesh.Cell(c);
    double h2 = 0.0;
    for (int a = 0; a < mesh.VerticesPerCell(); ++a)
    {
      for (int b = a + 1; b < mesh.VerticesPerCell(); ++b)
      {
        double s = 0.0;
        for (int d = 0; d < mesh.AmbientDim; ++d)
        {
          const double e = mesh.Point(cell[b])[d] - mesh.Point(cell[a])[d];
          s += e * e;
        }
        h2 = std::max(h2, s);
      }
    }
    const double meas = CellMeasure(mesh, c);
    const double scale = mesh.SimplexDim == 3 ? h2 * std::sqrt(h2) : h2;
    if (!(std::abs(meas) > 1e-12 * scale))
    {
      throw InputError("embedding: cell " + std::to_string(c) +
        " is degenerate (zero or near-zero " + (mesh.SimplexDim == 3 ? "volume" : "area") +
        "; repeated or collinear/coplanar vertices)");
    }
    if (meas > 0)
    {
      if (positive++ == 0)
      {
        firstPos = c;
      }
    }
    else if (negative++ == 0)
    {
      firstNeg = c;
    }
  }
  if (positive > 0 && negative > 0)
  {
    const std::size_t bad = positive >= negative ? firstNeg : firstPos;
    throw InputError("embedding: cell " + std::to_string(bad) + " is inverted (" +
      std::to_string(std::min(positive, negative)) + " of " + std::to_string(mesh.NumCells()) +
      " cells have the opposite orientation of the others)");
  }
}

void EmbeddingSolver::Internals::BuildElements(const SimplexMesh& mesh, const MetricField& metric)
{
  const int m = this->M, k = this->K, nv = k + 1;
  this->Cells = mesh.Cells;
  this->Gt.assign(this->NE * nv * m, 0.0);
  this->A.assign(this->NE * m * m, 0.0);
  this->W.assign(this->NE, 1.0);
  std::vector<double> measure(this->NE);
  tbb::parallel_for(std::size_t(0), this->NE, [&](std::size_t j) {
    const std::int32_t* cell = mesh.Cell(j);
    // W = edge vectors (m x k); W+ = pseudo-inverse (k x m); Gt = D W+ with D the (k+1) x k
    // difference operator (row 0 = -1, row l = e_l).
    Eigen::Matrix3d wm = Eigen::Matrix3d::Zero();
    for (int l = 0; l < k; ++l)
    {
      for (int d = 0; d < m; ++d)
      {
        wm(d, l) = mesh.Point(cell[l + 1])[d] - mesh.Point(cell[0])[d];
      }
    }
    using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3>; // no heap
    Small wp; // k x m
    if (k == m)
    {
      wp = Small(wm.topLeftCorner(m, m)).inverse();
    }
    else
    {
      const Small w = wm.topLeftCorner(m, k);
      const Small wtw = w.transpose() * w;
      wp = wtw.inverse() * w.transpose();
    }
    double* g = this->Gt.data() + j * nv * m;
    for (int d = 0; d < m; ++d)
    {
      double s = 0.0;
      for (int l = 0; l < k; ++l)
      {
        g[(l + 1) * m + d] = wp(l, d);
        s += wp(l, d);
      }
      g[d] = -s;
    }
    // Element metric: average of the vertex metrics; A = its symmetric square root.
    double* a = this->A.data() + j * m * m;
    if (m == 2)
    {
      Eigen::Matrix2d mm = Eigen::Matrix2d::Zero();
      for (int l = 0; l < nv; ++l)
      {
        mm += UnpackSymmetric2(metric.At(cell[l]));
      }
      Eigen::Map<Eigen::Matrix2d> am(a);
      am = SymmetricSqrt(Eigen::Matrix2d(mm / nv));
    }
    else
    {
      Eigen::Matrix3d mm = Eigen::Matrix3d::Zero();
      for (int l = 0; l < nv; ++l)
      {
        mm += UnpackSymmetric(metric.At(cell[l]));
      }
      Eigen::Map<Eigen::Matrix3d> am(a);
      am = SymmetricSqrt(Eigen::Matrix3d(mm / nv));
    }
    measure[j] = std::abs(CellMeasure(mesh, j));
  });
  if (this->Options.ElementMeasureWeighting)
  {
    const double mean = std::accumulate(measure.begin(), measure.end(), 0.0) / this->NE;
    for (std::size_t j = 0; j < this->NE; ++j)
    {
      this->W[j] = measure[j] / mean;
    }
  }
}

void EmbeddingSolver::Internals::BuildTopology(const SimplexMesh& mesh)
{
  const int nv = this->K + 1;
  const std::size_t np = this->NP;
  // Vertex -> incident (element, local vertex).
  this->VOff.assign(np + 1, 0);
  for (std::int32_t v : this->Cells)
  {
    ++this->VOff[v + 1];
  }
  std::partial_sum(this->VOff.begin(), this->VOff.end(), this->VOff.begin());
  this->VInc.resize(this->Cells.size());
  {
    std::vector<std::int32_t> fill(this->VOff.begin(), this->VOff.end() - 1);
    for (std::size_t i = 0; i < this->Cells.size(); ++i)
    {
      this->VInc[fill[this->Cells[i]]++] = static_cast<std::int32_t>(i); // i = j * nv + l
    }
  }
  // One-ring neighbours from the unique edges.
  const std::vector<std::int32_t> edges = UniqueEdges(mesh);
  this->NOff.assign(np + 1, 0);
  for (std::int32_t v : edges)
  {
    ++this->NOff[v + 1];
  }
  std::partial_sum(this->NOff.begin(), this->NOff.end(), this->NOff.begin());
  this->NIdx.resize(edges.size());
  {
    std::vector<std::int32_t> fill(this->NOff.begin(), this->NOff.end() - 1);
    for (std::size_t e = 0; e < edges.size(); e += 2)
    {
      this->NIdx[fill[edges[e]]++] = edges[e + 1];
      this->NIdx[fill[edges[e + 1]]++] = edges[e];
    }
  }
  for (std::size_t i = 0; i < np; ++i)
  {
    std::sort(this->NIdx.begin() + this->NOff[i], this->NIdx.begin() + this->NOff[i + 1]);
  }
  const std::vector<char> boundary = BoundaryVertexMask(mesh);
  this->Interior.resize(np);
  for (std::size_t i = 0; i < np; ++i)
  {
    this->Interior[i] = !boundary[i] && this->NOff[i + 1] > this->NOff[i];
  }
  // Connected components (union-find over cells): pin the first vertex of each one, which
  // removes the constant null space of every free dimension (the paper fixes v_1).
  std::vector<std::int32_t> parent(np);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](std::int32_t x) {
    while (parent[x] != x)
    {
      parent[x] = parent[parent[x]];
      x = parent[x];
    }
    return x;
  };
  for (std::size_t j = 0; j < this->NE; ++j)
  {
    const std::int32_t r0 = find(this->Cells[j * nv]);
    for (int l = 1; l < nv; ++l)
    {
      const std::int32_t r = find(this->Cells[j * nv + l]);
      if (r != r0)
      {
        parent[std::max(r, r0)] = std::min(r, r0);
      }
    }
  }
  this->Reduced.assign(np, -1);
  std::int32_t next = 0;
  for (std::size_t i = 0; i < np; ++i)
  {
    // The root of a component is its smallest vertex id: pin it.
    if (find(static_cast<std::int32_t>(i)) != static_cast<std::int32_t>(i))
    {
      this->Reduced[i] = next++;
    }
  }
  this->NR = static_cast<std::size_t>(next);
}

void EmbeddingSolver::Internals::AssembleLower(
  bool values, Eigen::SparseMatrix<double>& kmat, std::vector<double>* valsOut)
{
  // Lower triangle of K = sum_j w_j Gt_j Gt_j^T + Mu L^T L, column by column (column c holds
  // rows r >= c), assembled in parallel blocks with a dense scatter array per block. Both passes
  // visit the same entries in the same order, so the values line up with the pattern.
  const int m = this->M, nv = this->K + 1;
  const double mu = this->Options.Mu;
  const std::size_t np = this->NP;
  const std::size_t blockSize = 4096;
  const std::size_t nblocks = (np + blockSize - 1) / blockSize;
  std::vector<std::vector<std::int32_t>> bRows(nblocks);
  std::vector<std::vector<double>> bVals(nblocks);
  std::vector<std::int32_t> colCount(np, 0);
  tbb::parallel_for(std::size_t(0), nblocks, [&](std::size_t blk) {
    std::vector<double> acc(np, 0.0);
    std::vector<char> mark(np, 0);
    std::vector<std::int32_t> touched;
    touched.reserve(256);
    auto add = [&](std::int32_t r, double v) {
      if (!mark[r])
      {
        mark[r] = 1;
        touched.push_back(r);
      }
      acc[r] += v;
    };
    std::vector<std::int32_t>& rows = bRows[blk];
    std::vector<double>& vals = bVals[blk];
    const std::size_t c0 = blk * blockSize, c1 = std::min(np, c0 + blockSize);
    for (std::size_t c = c0; c < c1; ++c)
    {
      if (this->Reduced[c] < 0)
      {
        continue;
      }
      const std::int32_t ci = static_cast<std::int32_t>(c);
      for (std::int32_t q = this->VOff[c]; q < this->VOff[c + 1]; ++q)
      {
        const std::size_t j = this->VInc[q] / nv;
        const int l = this->VInc[q] % nv;
        for (int l2 = 0; l2 < nv; ++l2)
        {
          const std::int32_t r = this->Cells[j * nv + l2];
          if (r >= ci && this->Reduced[r] >= 0)
          {
            double s = 0.0;
            if (values)
            {
              const double* g = this->Gt.data() + j * nv * m;
              for (int d = 0; d < m; ++d)
              {
                s += g[l * m + d] * g[l2 * m + d];
              }
              s *= this->W[j];
            }
            add(r, s);
          }
        }
      }
      if (mu > 0.0)
      {
        // Regulariser rows i with c in {i} U N(i), i.e. i in {c} U N(c).
        auto addRow = [&](std::int32_t i) {
          if (!this->Interior[i])
          {
            return;
          }
          const double inv = 1.0 / (this->NOff[i + 1] - this->NOff[i]);
          const double lc = (i == ci) ? -1.0 : inv;
          if (i >= ci && this->Reduced[i] >= 0)
          {
            add(i, -mu * lc);
          }
          for (std::int32_t q = this->NOff[i]; q < this->NOff[i + 1]; ++q)
          {
            const std::int32_t r = this->NIdx[q];
            if (r >= ci && this->Reduced[r] >= 0)
            {
              add(r, mu * lc * inv);
            }
          }
        };
        addRow(ci);
        for (std::int32_t q = this->NOff[c]; q < this->NOff[c + 1]; ++q)
        {
          addRow(this->NIdx[q]);
        }
      }
      std::sort(touched.begin(), touched.end());
      for (std::int32_t r : touched)
      {
        rows.push_back(this->Reduced[r]);
        vals.push_back(acc[r]);
        acc[r] = 0.0;
        mark[r] = 0;
      }
      colCount[c] = static_cast<std::int32_t>(touched.size());
      touched.clear();
    }
  });
  const std::size_t nr = this->NR;
  std::vector<std::int64_t> offset(nblocks + 1, 0);
  for (std::size_t b = 0; b < nblocks; ++b)
  {
    offset[b + 1] = offset[b] + static_cast<std::int64_t>(bRows[b].size());
  }
  if (!values)
  {
    kmat.resize(static_cast<Eigen::Index>(nr), static_cast<Eigen::Index>(nr));
    kmat.resizeNonZeros(static_cast<Eigen::Index>(offset[nblocks]));
    int* outer = kmat.outerIndexPtr();
    std::int64_t pos = 0;
    for (std::size_t c = 0; c < np; ++c)
    {
      if (this->Reduced[c] >= 0)
      {
        outer[this->Reduced[c]] = static_cast<int>(pos);
        pos += colCount[c];
      }
    }
    outer[nr] = static_cast<int>(pos);
    std::fill(kmat.valuePtr(), kmat.valuePtr() + offset[nblocks], 0.0);
  }
  else
  {
    valsOut->resize(static_cast<std::size_t>(offset[nblocks]));
  }
  tbb::parallel_for(std::size_t(0), nblocks, [&](std::size_t b) {
    if (values)
    {
      std::copy(bVals[b].begin(), bVals[b].end(), valsOut->data() + offset[b]);
    }
    else
    {
      std::copy(bRows[b].begin(), bRows[b].end(), kmat.innerIndexPtr() + offset[b]);
    }
  });
}

void EmbeddingSolver::Internals::Factor(
  Eigen::SparseMatrix<double>& kmat, const std::vector<double>& vals, double analyseSeconds)
{
  const auto t0 = Clock::now();
  std::copy(vals.begin(), vals.end(), kmat.valuePtr());
  if (this->Chol.Factor())
  {
    this->Chol.factorize(kmat);
  }
  else
  {
    this->Chol.compute(kmat); // the analysis failed: one more try inside compute
  }
  if (this->Chol.info() != Eigen::Success)
  {
    // Retry with CHOLMOD's default ordering choice before giving up.
    this->Chol.cholmod().nmethods = 0;
    this->Chol.compute(kmat);
  }
  if (this->Chol.info() != Eigen::Success)
  {
    throw InputError("embedding: the linear system is not positive definite (the mesh is "
                     "probably not a valid manifold simplicial complex)");
  }
  this->FactorNonZeros = this->Chol.FactorSize();
  const cholmod_factor* factor = this->Chol.Factor();
  if (this->Options.SinglePrecisionSolve && factor && factor->is_super && this->F > 0)
  {
    this->FloatSolver.reset(new FloatSupernodalSolver(*factor));
  }
  this->FactorSeconds = analyseSeconds + Since(t0);
}

void EmbeddingSolver::Internals::Initialise(const SimplexMesh& mesh)
{
  const int m = this->M, mb = this->MB;
  const std::size_t np = this->NP;
  this->X.assign(np * mb, 0.0);
  double lo[3] = { 1e300, 1e300, 1e300 }, hi[3] = { -1e300, -1e300, -1e300 };
  for (std::size_t i = 0; i < np; ++i)
  {
    for (int d = 0; d < m; ++d)
    {
      this->X[i * mb + d] = mesh.Point(i)[d];
      lo[d] = std::min(lo[d], mesh.Point(i)[d]);
      hi[d] = std::max(hi[d], mesh.Point(i)[d]);
    }
  }
  double ext = 0.0;
  for (int d = 0; d < m; ++d)
  {
    ext = std::max(ext, hi[d] - lo[d]);
  }
  const bool smooth = this->Options.Initialisation == EmbeddingInitialisation::Smooth;
  const double amp = ext *
    (this->Options.InitialAmplitude > 0.0 ? this->Options.InitialAmplitude : (smooth ? 0.2 : 1e-3));
  std::mt19937_64 rng(this->Options.Seed);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  if (smooth)
  {
    // Per free dimension: sum of 3 plane waves, random direction, 0.25..1 periods over the
    // domain, random phase and weight.
    constexpr int nw = 3;
    const double pi = 3.14159265358979323846;
    for (int f = 0; f < this->F; ++f)
    {
      double dir[nw][3], phase[nw], wt[nw];
      for (int w = 0; w < nw; ++w)
      {
        double n2 = 0.0;
        do
        {
          n2 = 0.0;
          for (int d = 0; d < 3; ++d)
          {
            dir[w][d] = d < m ? uni(rng) : 0.0;
            n2 += dir[w][d] * dir[w][d];
          }
        } while (n2 < 1e-4 || n2 > 1.0);
        const double freq = 2.0 * pi * (0.25 + 0.375 * (uni(rng) + 1.0)) / (ext * std::sqrt(n2));
        for (int d = 0; d < 3; ++d)
        {
          dir[w][d] *= freq;
        }
        phase[w] = pi * uni(rng);
        wt[w] = uni(rng);
      }
      for (std::size_t i = 0; i < np; ++i)
      {
        double s = 0.0;
        for (int w = 0; w < nw; ++w)
        {
          double arg = phase[w];
          for (int d = 0; d < m; ++d)
          {
            arg += dir[w][d] * (mesh.Point(i)[d] - lo[d]);
          }
          s += wt[w] * std::sin(arg);
        }
        this->X[i * mb + m + f] = amp * s;
      }
    }
  }
  else
  {
    for (std::size_t i = 0; i < np; ++i)
    {
      for (int f = 0; f < this->F; ++f)
      {
        this->X[i * mb + m + f] = amp * uni(rng);
      }
    }
  }
  // Shift each component so that its pinned vertex sits at 0 in the free dimensions (constants
  // do not change the energy; the reduced system then needs no pinned-value correction).
  std::vector<std::int32_t> pinOf(np, -1);
  {
    // Components are numbered by their pinned (smallest) vertex: propagate via elements.
    std::vector<std::int32_t> root(np);
    std::iota(root.begin(), root.end(), 0);
    auto find = [&](std::int32_t x) {
      while (root[x] != x)
      {
        root[x] = root[root[x]];
        x = root[x];
      }
      return x;
    };
    const int nv = this->K + 1;
    for (std::size_t j = 0; j < this->NE; ++j)
    {
      const std::int32_t r0 = find(this->Cells[j * nv]);
      for (int l = 1; l < nv; ++l)
      {
        const std::int32_t r = find(this->Cells[j * nv + l]);
        if (r != r0)
        {
          root[std::max(r, r0)] = std::min(r, r0);
        }
      }
    }
    for (std::size_t i = 0; i < np; ++i)
    {
      pinOf[i] = find(static_cast<std::int32_t>(i));
    }
  }
  for (std::size_t i = np; i-- > 0;)
  {
    const std::size_t p = static_cast<std::size_t>(pinOf[i]);
    if (p != i)
    {
      for (int f = 0; f < this->F; ++f)
      {
        this->X[i * mb + m + f] -= this->X[p * mb + m + f];
      }
    }
  }
  for (std::size_t i = 0; i < np; ++i)
  {
    if (static_cast<std::size_t>(pinOf[i]) == i)
    {
      for (int f = 0; f < this->F; ++f)
      {
        this->X[i * mb + m + f] = 0.0;
      }
    }
  }
  this->C.assign(this->NE * (this->K + 1) * this->F, 0.0);
}

template <int MBT, int MT, int KT>
double EmbeddingSolver::Internals::LocalStepT()
{
  constexpr int NV = KT + 1;
  constexpr int MaxRows = MBT == Eigen::Dynamic ? kMaxTargetDim : MBT;
  using MatB = Eigen::Matrix<double, MBT, MT, 0, MaxRows, MT>;
  using VecB = Eigen::Matrix<double, MBT, 1, 0, MaxRows, 1>;
  using MatG = Eigen::Matrix<double, NV, MT, Eigen::RowMajor>;
  using MatM = Eigen::Matrix<double, MT, MT>;
  using MatC = Eigen::Matrix<double, NV, Eigen::Dynamic, Eigen::RowMajor, NV, kMaxTargetDim>;
  constexpr bool kFastVolume = MT == 3 && KT == 3 && MBT != Eigen::Dynamic;
  constexpr int FT = kFastVolume ? MBT - MT : 1; // free dimensions (compile time)
  using MatF = Eigen::Matrix<double, FT, MT>;
  using VecF = Eigen::Matrix<double, FT, 1>;
  using MatCF = Eigen::Matrix<double, NV, FT, FT == 1 ? Eigen::ColMajor : Eigen::RowMajor>;
  const int mb = this->MB, nf = this->F;
  const std::size_t ne = this->NE;
  const std::size_t nchunks = (ne + kChunk - 1) / kChunk;
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
    const std::size_t j0 = ch * kChunk, j1 = std::min(ne, j0 + kChunk);
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
      PolarFactor<MT, (KT < MT)>(b, v);
      r.noalias() = v * a;
      const double w = this->W[j];
      e += w * (t - r).squaredNorm();
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

double EmbeddingSolver::Internals::RegulariserEnergy() const
{
  const int mb = this->MB, m = this->M;
  const std::size_t np = this->NP;
  const std::size_t nchunks = (np + kChunk - 1) / kChunk;
  std::vector<double> partial(nchunks, 0.0);
  tbb::parallel_for(std::size_t(0), nchunks, [&](std::size_t ch) {
    double e = 0.0;
    double lap[kMaxTargetDim];
    for (std::size_t i = ch * kChunk; i < std::min(np, (ch + 1) * kChunk); ++i)
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
  return sum;
}

EmbeddingEnergy EmbeddingSolver::Internals::LocalStep()
{
  const auto t0 = Clock::now();
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
  e.Regularisation = this->RegulariserEnergy();
  e.Total = e.Embedding + this->Options.Mu * e.Regularisation;
  this->Energy = e;
  this->LocalSeconds += Since(t0);
  return e;
}

Eigen::MatrixXd EmbeddingSolver::Internals::GlobalStep()
{
  // Right-hand side: gather the per-element contributions of every vertex (no races).
  const int nv = this->K + 1, nf = this->F;
  Eigen::MatrixXd& rhs = this->LastRhs;
  rhs.resize(static_cast<Eigen::Index>(this->NR), nf);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, this->NP, 1024),
    [&](const tbb::blocked_range<std::size_t>& range) {
      double s[kMaxTargetDim];
      for (std::size_t i = range.begin(); i != range.end(); ++i)
      {
        const std::int32_t ri = this->Reduced[i];
        if (ri < 0)
        {
          continue;
        }
        std::fill(s, s + nf, 0.0);
        for (std::int32_t q = this->VOff[i]; q < this->VOff[i + 1]; ++q)
        {
          const double* c = this->C.data() + static_cast<std::size_t>(this->VInc[q]) * nf;
          for (int d = 0; d < nf; ++d)
          {
            s[d] += c[d];
          }
        }
        for (int d = 0; d < nf; ++d)
        {
          rhs(ri, d) = s[d];
        }
      }
    });
  (void)nv;
  const auto t0 = Clock::now();
  Eigen::MatrixXd sol;
  if (this->FloatSolver)
  {
    sol.resize(rhs.rows(), rhs.cols());
    this->FloatSolver->Solve(rhs.data(), sol.data(), static_cast<int>(rhs.cols()));
  }
  else
  {
    sol = this->Chol.solve(rhs);
  }
  this->SolveSeconds += Since(t0);
  return sol;
}

Eigen::MatrixXd EmbeddingSolver::Internals::RedoGlobalStepInDouble()
{
  const auto t0 = Clock::now();
  Eigen::MatrixXd sol = this->Chol.solve(this->LastRhs);
  this->SolveSeconds += Since(t0);
  return sol;
}

Eigen::MatrixXd EmbeddingSolver::Internals::GetFree() const
{
  Eigen::MatrixXd xr(static_cast<Eigen::Index>(this->NR), this->F);
  for (std::size_t i = 0; i < this->NP; ++i)
  {
    if (this->Reduced[i] >= 0)
    {
      for (int d = 0; d < this->F; ++d)
      {
        xr(this->Reduced[i], d) = this->X[i * this->MB + this->M + d];
      }
    }
  }
  return xr;
}

void EmbeddingSolver::Internals::SetFree(const Eigen::MatrixXd& xr)
{
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, this->NP, 4096),
    [&](const tbb::blocked_range<std::size_t>& range) {
      for (std::size_t i = range.begin(); i != range.end(); ++i)
      {
        if (this->Reduced[i] >= 0)
        {
          for (int d = 0; d < this->F; ++d)
          {
            this->X[i * this->MB + this->M + d] = xr(this->Reduced[i], d);
          }
        }
      }
    });
}

EmbeddingSolver::EmbeddingSolver(
  const SimplexMesh& mesh, const MetricField& metric, const EmbeddingOptions& options)
  : P(new Internals)
{
  const auto t0 = Clock::now();
  Internals& p = *this->P;
  p.Options = options;
  p.Validate(mesh, metric);
  p.M = mesh.AmbientDim;
  p.K = mesh.SimplexDim;
  p.MB = options.TargetDim;
  p.F = p.MB - p.M;
  p.NP = mesh.NumPoints();
  p.NE = mesh.NumCells();
  p.Cells = mesh.Cells;
  p.BuildTopology(mesh);
  // The fill-reducing ordering and symbolic analysis (single-threaded, ~0.7 s on cube2) need
  // only the pattern: they run on their own thread while the element operators, the values of
  // K and the initial state are computed.
  Eigen::SparseMatrix<double> kmat;
  p.AssembleLower(false, kmat, nullptr);
  // Nested dissection keeps the fill of the two-ring stencil (L^T L) well below AMD's
  // (cube2 101x21x21: 38.6M entries with NESDIS, 39.4M METIS, 47.7M AMD).
  p.Chol.cholmod().nmethods = 1;
  p.Chol.cholmod().method[0].ordering = CHOLMOD_NESDIS;
  double analyseSeconds = 0.0;
  std::thread analyser([&p, &kmat, &analyseSeconds]() {
    const auto ta = Clock::now();
    p.Chol.analyzePattern(kmat);
    analyseSeconds = Since(ta);
  });
  std::vector<double> values;
  try
  {
    p.BuildElements(mesh, metric);
    p.AssembleLower(true, kmat, &values);
    p.Initialise(mesh);
  }
  catch (...)
  {
    analyser.join();
    throw;
  }
  const auto tw = Clock::now();
  analyser.join();
  const double waited = Since(tw);
  p.Factor(kmat, values, waited);
  // FactorSeconds: the factorisation's share of the wall time (the analysis it waited for plus
  // the numeric factorisation); the overlapped part of the analysis counts as setup.
  p.SetupSeconds = Since(t0) - p.FactorSeconds;
  (void)analyseSeconds;
}

EmbeddingSolver::~EmbeddingSolver() = default;

Embedding EmbeddingSolver::CurrentEmbedding() const
{
  Embedding e;
  e.Dim = this->P->MB;
  e.Coords = this->P->X;
  return e;
}

EmbeddingEnergy EmbeddingSolver::CurrentEnergy() const
{
  return this->P->Energy;
}

namespace
{
/// out[a] = <vs[a], u> (Frobenius) for every a, in one parallel pass over the rows with fixed
/// chunks summed in order (deterministic).
void FusedDots(const std::vector<Eigen::MatrixXd>& vs, const Eigen::MatrixXd& u, double* out)
{
  const std::size_t h = vs.size(), n = static_cast<std::size_t>(u.size());
  constexpr std::size_t chunk = 16384;
  const std::size_t nchunks = (n + chunk - 1) / chunk;
  std::vector<double> partial(nchunks * h, 0.0);
  tbb::parallel_for(std::size_t(0), nchunks, [&](std::size_t c) {
    const std::size_t i0 = c * chunk, i1 = std::min(n, i0 + chunk);
    const double* pu = u.data();
    for (std::size_t a = 0; a < h; ++a)
    {
      const double* pv = vs[a].data();
      double sum = 0.0;
      for (std::size_t i = i0; i < i1; ++i)
      {
        sum += pv[i] * pu[i];
      }
      partial[c * h + a] = sum;
    }
  });
  for (std::size_t a = 0; a < h; ++a)
  {
    double sum = 0.0;
    for (std::size_t c = 0; c < nchunks; ++c)
    {
      sum += partial[c * h + a];
    }
    out[a] = sum;
  }
}

/// xa = g - sum_a theta(a) dG[a], one parallel pass.
void CombineAnderson(const Eigen::MatrixXd& g, const std::vector<Eigen::MatrixXd>& dG,
  const Eigen::VectorXd& theta, Eigen::MatrixXd& xa)
{
  xa.resize(g.rows(), g.cols());
  const std::size_t n = static_cast<std::size_t>(g.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16384),
    [&](const tbb::blocked_range<std::size_t>& r) {
      double* px = xa.data();
      const double* pg = g.data();
      for (std::size_t i = r.begin(); i != r.end(); ++i)
      {
        px[i] = pg[i];
      }
      for (std::size_t a = 0; a < dG.size(); ++a)
      {
        const double t = theta(static_cast<Eigen::Index>(a));
        const double* pd = dG[a].data();
        for (std::size_t i = r.begin(); i != r.end(); ++i)
        {
          px[i] -= t * pd[i];
        }
      }
    });
}
} // namespace

EmbeddingResult EmbeddingSolver::Run()
{
  Internals& p = *this->P;
  if (p.Ran)
  {
    throw InputError("embedding: EmbeddingSolver::Run() may be called only once");
  }
  p.Ran = true;
  EmbeddingResult res;
  res.SetupSeconds = p.SetupSeconds;
  res.FactorSeconds = p.FactorSeconds;
  res.FactorNonZeros = p.FactorNonZeros;
  const auto t0 = Clock::now();
  const EmbeddingOptions& o = p.Options;

  EmbeddingEnergy cur = p.LocalStep();
  res.EnergyHistory.push_back(cur);
  Eigen::MatrixXd x = p.GetFree();

  // Anderson acceleration (type II) on the fixed-point map x -> G(x) = global(local(x)), with the
  // energy safeguard of Peng et al. 2018: keep the accelerated iterate only if it lowers E_total.
  // The Gram matrix of the residual differences is updated one row per iteration, and the dot
  // products / combinations are fused parallel passes (they were memory-bound serial loops).
  const int window = o.AndersonWindow;
  std::vector<Eigen::MatrixXd> dG, dF;
  Eigen::MatrixXd gPrev, fPrev, f, xa;
  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(std::max(window, 1), std::max(window, 1));
  std::vector<double> dots(static_cast<std::size_t>(std::max(window, 1)));
  int head = 0;
  for (int it = 1; it <= o.Iterations; ++it)
  {
    Eigen::MatrixXd g = p.GlobalStep();
    bool accepted = false;
    if (window > 0)
    {
      f = g - x;
      if (gPrev.size() > 0)
      {
        int slot = head;
        if (static_cast<int>(dG.size()) < window)
        {
          slot = static_cast<int>(dG.size());
          dG.emplace_back();
          dF.emplace_back();
        }
        else
        {
          head = (head + 1) % window;
        }
        dG[slot] = g - gPrev;
        dF[slot] = f - fPrev;
        FusedDots(dF, dF[slot], dots.data());
        for (std::size_t b = 0; b < dF.size(); ++b)
        {
          gram(slot, static_cast<Eigen::Index>(b)) = gram(static_cast<Eigen::Index>(b), slot) = dots[b];
        }
      }
      gPrev = g;
      fPrev = f;
      const int h = static_cast<int>(dF.size());
      if (h > 0)
      {
        FusedDots(dF, f, dots.data());
        const Eigen::VectorXd rhs = Eigen::Map<const Eigen::VectorXd>(dots.data(), h);
        // Tikhonov guard against (nearly) dependent differences.
        Eigen::MatrixXd gh = gram.topLeftCorner(h, h);
        gh.diagonal().array() += 1e-10 * gh.diagonal().maxCoeff() + 1e-300;
        const Eigen::VectorXd theta = gh.ldlt().solve(rhs);
        if (theta.allFinite())
        {
          CombineAnderson(g, dG, theta, xa);
          p.SetFree(xa);
          const EmbeddingEnergy ea = p.LocalStep();
          if (ea.Total < cur.Total)
          {
            accepted = true;
            cur = ea;
            std::swap(x, xa);
            ++res.AndersonAccepted;
          }
          else
          {
            ++res.AndersonRejected;
          }
        }
      }
    }
    if (!accepted)
    {
      p.SetFree(g);
      EmbeddingEnergy eg = p.LocalStep();
      if (p.FloatSolver && eg.Total > cur.Total)
      {
        // The exact global step cannot raise the energy; the float one did: redo it in double.
        g = p.RedoGlobalStepInDouble();
        p.SetFree(g);
        eg = p.LocalStep();
        ++res.DoublePrecisionRetries;
      }
      cur = eg;
      x = std::move(g);
    }
    res.EnergyHistory.push_back(cur);
    res.IterationsDone = it;
    if (o.Progress)
    {
      EmbeddingProgress pr;
      pr.Iteration = it;
      pr.Iterations = o.Iterations;
      pr.Energy = cur;
      pr.Solver = this;
      if (!o.Progress(pr))
      {
        res.Aborted = true;
        break;
      }
    }
    const double prev = res.EnergyHistory[res.EnergyHistory.size() - 2].Total;
    if (o.RelativeEnergyTolerance > 0.0 && prev > 0.0 &&
      (prev - cur.Total) / prev < o.RelativeEnergyTolerance)
    {
      break;
    }
  }
  res.IterationSeconds = Since(t0);
  res.LocalStepSeconds = p.LocalSeconds;
  res.SolveSeconds = p.SolveSeconds;
  res.Embedded = this->CurrentEmbedding();
  return res;
}

EmbeddingResult ComputeEmbedding(
  const SimplexMesh& mesh, const MetricField& metric, const EmbeddingOptions& options)
{
  EmbeddingSolver solver(mesh, metric, options);
  return solver.Run();
}

} // namespace av
