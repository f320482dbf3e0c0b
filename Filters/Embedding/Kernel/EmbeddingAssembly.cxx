// SPDX-License-Identifier: BSD-3-Clause
// EmbeddingSolver assembly: the global matrix K = Σ w_j G_j G_jᵀ + μ LᵀL (lower triangle), its
// Cholesky factorization and the per-iteration right-hand sides.
#include "EmbeddingSolverInternals.h"
#include "MemoryBudget.h"

#include "Stopwatch.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace av
{

/// Dense scatter array of one block of columns: the entries of the current column by row,
/// emitted in row order.
struct EmbeddingSolver::Internals::ColumnScatter
{
  std::vector<double> Acc;
  std::vector<char> Mark;
  std::vector<std::int32_t> Touched;

  explicit ColumnScatter(std::size_t np)
    : Acc(np, 0.0)
    , Mark(np, 0)
  {
    this->Touched.reserve(256);
  }

  void Add(std::int32_t r, double v)
  {
    if (!this->Mark[r])
    {
      this->Mark[r] = 1;
      this->Touched.push_back(r);
    }
    this->Acc[r] += v;
  }

  /// Appends the column's (reduced row, value) pairs in row order, clears it and returns the
  /// number of entries.
  std::int32_t Flush(const std::vector<std::int32_t>& reduced, std::vector<std::int32_t>& rows,
    std::vector<double>& vals)
  {
    std::sort(this->Touched.begin(), this->Touched.end());
    for (std::int32_t r : this->Touched)
    {
      rows.push_back(reduced[r]);
      vals.push_back(this->Acc[r]);
      this->Acc[r] = 0.0;
      this->Mark[r] = 0;
    }
    const std::int32_t count = static_cast<std::int32_t>(this->Touched.size());
    this->Touched.clear();
    return count;
  }
};

void EmbeddingSolver::Internals::AddElementEntries(
  std::size_t c, bool values, ColumnScatter& scatter) const
{
  const int m = this->M, nv = this->K + 1;
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
        scatter.Add(r, s);
      }
    }
  }
}

void EmbeddingSolver::Internals::AddRegularizerEntries(std::size_t c, ColumnScatter& scatter) const
{
  // Regularizer rows i with c in {i} U N(i), i.e. i in {c} U N(c).
  const double mu = this->Options.Mu * this->RegularizerScale;
  const std::int32_t ci = static_cast<std::int32_t>(c);
  auto addRow = [&](std::int32_t i) {
    if (!this->Interior[i])
    {
      return;
    }
    const double inv = 1.0 / (this->NOff[i + 1] - this->NOff[i]);
    const double lc = (i == ci) ? -1.0 : inv;
    if (i >= ci && this->Reduced[i] >= 0)
    {
      scatter.Add(i, -mu * lc);
    }
    for (std::int32_t q = this->NOff[i]; q < this->NOff[i + 1]; ++q)
    {
      const std::int32_t r = this->NIdx[q];
      if (r >= ci && this->Reduced[r] >= 0)
      {
        scatter.Add(r, mu * lc * inv);
      }
    }
  };
  addRow(ci);
  for (std::int32_t q = this->NOff[c]; q < this->NOff[c + 1]; ++q)
  {
    addRow(this->NIdx[q]);
  }
}

void EmbeddingSolver::Internals::AssembleLower(
  bool values, Eigen::SparseMatrix<double>& kmat, std::vector<double>* valsOut)
{
  // Lower triangle of K column by column (column c holds rows r >= c), assembled in parallel
  // blocks with a dense scatter array per block. Both passes visit the same entries in the same
  // order, so the values line up with the pattern.
  const std::size_t np = this->NP;
  const std::size_t blockSize = 4096;
  const std::size_t nblocks = (np + blockSize - 1) / blockSize;
  std::vector<std::vector<std::int32_t>> bRows(nblocks);
  std::vector<std::vector<double>> bVals(nblocks);
  std::vector<std::int32_t> colCount(np, 0);
  // One scatter array per thread, not per block: a block's array is np long, so one per block
  // would allocate and zero np^2 / blockSize entries (2.2 GB per pass at 1M vertices). Flush()
  // leaves it clean for the next column.
  tbb::enumerable_thread_specific<ColumnScatter> scatters([np] { return ColumnScatter(np); });
  tbb::parallel_for(std::size_t(0), nblocks, [&](std::size_t blk) {
    ColumnScatter& scatter = scatters.local();
    const std::size_t c0 = blk * blockSize, c1 = std::min(np, c0 + blockSize);
    for (std::size_t c = c0; c < c1; ++c)
    {
      if (this->Reduced[c] < 0)
      {
        continue;
      }
      this->AddElementEntries(c, values, scatter);
      if (this->Options.Mu > 0.0)
      {
        this->AddRegularizerEntries(c, scatter);
      }
      colCount[c] = scatter.Flush(this->Reduced, bRows[blk], bVals[blk]);
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

namespace
{
/// CHOLMOD's status code in words (cholmod_core.h), for the error messages.
std::string CholmodStatusText(int status)
{
  switch (status)
  {
    case CHOLMOD_NOT_INSTALLED: return "method not installed";
    case CHOLMOD_OUT_OF_MEMORY: return "out of memory";
    case CHOLMOD_TOO_LARGE: return "problem too large for CHOLMOD's 32-bit integer interface";
    case CHOLMOD_INVALID: return "invalid input";
    case CHOLMOD_GPU_PROBLEM: return "GPU problem";
    case CHOLMOD_NOT_POSDEF: return "matrix not positive definite";
    case CHOLMOD_DSMALL: return "tiny diagonal entry";
    default: return "status " + std::to_string(status);
  }
}
} // namespace

void EmbeddingSolver::Internals::RequireAnalysis(const Eigen::SparseMatrix<double>& kmat)
{
  if (this->Chol.Factor())
  {
    return;
  }
  // Eigen's factorize() dereferences the factor: a failed analysis must stop here (a 1M-vertex
  // cube1 once segfaulted on "problem too large").
  const int status = this->Chol.cholmod().status;
  const double entries = this->Chol.cholmod().lnz;
  std::string estimate;
  if (entries > 0.0)
  {
    estimate = " (the factor would hold about " + std::to_string(static_cast<long long>(entries)) +
      " entries, " + FormatBytes(8.0 * entries) + ")";
  }
  throw InputError("embedding: the symbolic analysis of the " + std::to_string(kmat.rows()) +
    "-unknown linear system failed: " + CholmodStatusText(status) + estimate +
    "; use a coarser input mesh");
}

void EmbeddingSolver::Internals::FactorOnce(const Eigen::SparseMatrix<double>& kmat)
{
  this->RequireAnalysis(kmat);
  // The numeric factor fills the supernodal storage sized by the analysis (xsize doubles), and
  // the single-precision solve copies it into floats: refuse early when that cannot fit.
  const double reals = static_cast<double>(this->Chol.FactorSize());
  const double bytes = reals * (this->Options.SinglePrecisionSolve ? 12.0 : 8.0);
  RequireMemory(bytes, "embedding: the Cholesky factor of the " + std::to_string(kmat.rows()) +
      "-unknown linear system (" + std::to_string(static_cast<long long>(reals)) + " entries)");
  this->Chol.factorize(kmat);
  const int status = this->Chol.cholmod().status;
  if (status < CHOLMOD_OK)
  {
    throw InputError("embedding: the Cholesky factorization failed: " + CholmodStatusText(status));
  }
}

void EmbeddingSolver::Internals::Factor(
  Eigen::SparseMatrix<double>& kmat, const std::vector<double>& vals, double analyseSeconds)
{
  const Stopwatch clock;
  std::copy(vals.begin(), vals.end(), kmat.valuePtr());
  if (!this->Chol.Factor() && this->Chol.cholmod().status != CHOLMOD_TOO_LARGE)
  {
    this->Chol.analyzePattern(kmat); // the analysis failed: one more try
  }
  this->FactorOnce(kmat);
  if (this->Chol.info() != Eigen::Success)
  {
    // Retry with CHOLMOD's default ordering choice before giving up.
    this->Chol.cholmod().nmethods = 0;
    this->Chol.analyzePattern(kmat);
    this->FactorOnce(kmat);
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
  this->FactorSeconds = analyseSeconds + clock.Seconds();
}

Eigen::SparseMatrix<double> EmbeddingSolver::Internals::ElementAdjacentPart(
  const Eigen::SparseMatrix<double>& kmat) const
{
  // Entries of K between vertices that share no element come from the regularizer's L^T L only
  // (positive (1/n_j)^2 products through a common neighbour j). Dropping the pair a at (i, k),
  // (k, i) and adding |a| to both diagonals adds |a| (e_i -+ e_k)(e_i -+ e_k)^T >= 0: P >= K stays
  // SPD, and for a > 0 the row sums (the constants AMG must keep) are unchanged.
  const int nv = this->K + 1;
  std::vector<std::int32_t> full(this->NR);
  for (std::size_t v = 0; v < this->NP; ++v)
  {
    if (this->Reduced[v] >= 0)
    {
      full[static_cast<std::size_t>(this->Reduced[v])] = static_cast<std::int32_t>(v);
    }
  }
  const Eigen::Index nnz = kmat.nonZeros();
  std::vector<char> keep(static_cast<std::size_t>(nnz), 0);
  const std::size_t blockSize = 4096;
  const std::size_t nblocks = (this->NR + blockSize - 1) / blockSize;
  // One stamp array per thread: column rc marks its element neighbours with rc.
  tbb::enumerable_thread_specific<std::vector<std::int32_t>> stamps(
    [&] { return std::vector<std::int32_t>(this->NR, -1); });
  tbb::parallel_for(std::size_t(0), nblocks, [&](std::size_t blk) {
    std::vector<std::int32_t>& stamp = stamps.local();
    const std::size_t c0 = blk * blockSize, c1 = std::min(this->NR, c0 + blockSize);
    for (std::size_t rc = c0; rc < c1; ++rc)
    {
      const std::int32_t fc = full[rc];
      for (std::int32_t q = this->VOff[fc]; q < this->VOff[fc + 1]; ++q)
      {
        const std::size_t j = this->VInc[q] / nv;
        for (int l = 0; l < nv; ++l)
        {
          const std::int32_t r = this->Reduced[this->Cells[j * nv + l]];
          if (r >= 0)
          {
            stamp[static_cast<std::size_t>(r)] = static_cast<std::int32_t>(rc);
          }
        }
      }
      for (Eigen::Index e = kmat.outerIndexPtr()[rc]; e < kmat.outerIndexPtr()[rc + 1]; ++e)
      {
        const std::int32_t r = kmat.innerIndexPtr()[e];
        keep[static_cast<std::size_t>(e)] = stamp[static_cast<std::size_t>(r)] ==
          static_cast<std::int32_t>(rc);
      }
    }
  });
  std::vector<double> compensation(this->NR, 0.0);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(nnz) / 2);
  for (Eigen::Index c = 0; c < kmat.outerSize(); ++c)
  {
    for (Eigen::Index e = kmat.outerIndexPtr()[c]; e < kmat.outerIndexPtr()[c + 1]; ++e)
    {
      const Eigen::Index r = kmat.innerIndexPtr()[e];
      const double v = kmat.valuePtr()[e];
      if (keep[static_cast<std::size_t>(e)])
      {
        entries.emplace_back(static_cast<int>(r), static_cast<int>(c), v);
      }
      else
      {
        compensation[static_cast<std::size_t>(r)] += std::abs(v);
        compensation[static_cast<std::size_t>(c)] += std::abs(v);
      }
    }
  }
  for (std::size_t i = 0; i < this->NR; ++i)
  {
    if (compensation[i] != 0.0)
    {
      entries.emplace_back(static_cast<int>(i), static_cast<int>(i), compensation[i]);
    }
  }
  Eigen::SparseMatrix<double> p(kmat.rows(), kmat.cols());
  p.setFromTriplets(entries.begin(), entries.end()); // sums the compensation into the diagonal
  return p;
}

void EmbeddingSolver::Internals::SetupIterative(
  Eigen::SparseMatrix<double>& kmat, const std::vector<double>& vals)
{
  const Stopwatch clock;
  std::copy(vals.begin(), vals.end(), kmat.valuePtr());
  if (this->F > 0 && this->NR > 0)
  {
    // A few hundred CG iterations at most: AMG-preconditioned CG on these systems takes tens.
    if (this->Options.SparsePreconditioner && this->Options.Mu > 0.0)
    {
      const Eigen::SparseMatrix<double> p = this->ElementAdjacentPart(kmat);
      this->Iterative.reset(new IterativeGlobalSolver(kmat, 500, &p));
    }
    else
    {
      this->Iterative.reset(new IterativeGlobalSolver(kmat, 500));
    }
  }
  this->FactorSeconds = clock.Seconds();
}

void EmbeddingSolver::Internals::GatherRightHandSides()
{
  // Gather the per-element contributions of every vertex (no races).
  const int nf = this->F;
  Eigen::MatrixXd& rhs = this->LastRhs;
  rhs.resize(static_cast<Eigen::Index>(this->NR), nf);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, this->NP, 1024),
    [&](const tbb::blocked_range<std::size_t>& range) {
      double s[kEmbeddingMaxTargetDim];
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
}

} // namespace av
