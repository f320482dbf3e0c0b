// SPDX-License-Identifier: BSD-3-Clause
#include "CsrMatrix.h"

#include "BlockRowOps.h"

#include <numeric>
#include <stdexcept>
#include <utility>

namespace av
{

namespace
{
/// Rows [r0, r1) of y = A x with the block width K known at compile time (kept in registers).
template <int K>
void MultiplyRows(const std::int64_t* start,
  const int* col,
  const double* val,
  const double* x,
  double* y,
  std::size_t r0,
  std::size_t r1)
{
  for (std::size_t i = r0; i < r1; ++i)
  {
    double acc[K] = { 0 };
    for (std::int64_t e = start[i]; e < start[i + 1]; ++e)
    {
      const double v = val[e];
      const double* xr = x + static_cast<std::size_t>(col[e]) * K;
      for (int c = 0; c < K; ++c)
      {
        acc[c] += v * xr[c];
      }
    }
    double* yr = y + i * K;
    for (int c = 0; c < K; ++c)
    {
      yr[c] = acc[c];
    }
  }
}
} // namespace

CsrMatrix::CsrMatrix(int rows,
  int cols,
  std::vector<std::int64_t> start,
  std::vector<int> column,
  std::vector<double> value)
  : NumRows(rows)
  , NumCols(cols)
  , Start(std::move(start))
  , Col(std::move(column))
  , Val(std::move(value))
{
  if (rows < 0 || cols < 0 || this->Start.size() != static_cast<std::size_t>(rows) + 1 ||
    this->Col.size() != this->Val.size() ||
    static_cast<std::int64_t>(this->Col.size()) != this->Start.back())
  {
    throw std::invalid_argument("CsrMatrix: inconsistent CSR arrays");
  }
}

CsrMatrix CsrMatrix::SymmetricFromLower(const Eigen::SparseMatrix<double>& lower)
{
  const int n = static_cast<int>(lower.rows());
  // Column c of the lower triangle is the upper part of row c; each off-diagonal (r, c) is also
  // entry c of row r.
  std::vector<std::int64_t> start(static_cast<std::size_t>(n) + 1, 0);
  for (Eigen::Index c = 0; c < lower.outerSize(); ++c)
  {
    for (Eigen::SparseMatrix<double>::InnerIterator it(lower, c); it; ++it)
    {
      ++start[it.row() + 1];
      if (it.row() != c)
      {
        ++start[c + 1];
      }
    }
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<int> col(static_cast<std::size_t>(start.back()));
  std::vector<double> val(col.size());
  std::vector<std::int64_t> fill(start.begin(), start.end() - 1);
  // Columns in increasing order: row r receives its entries sorted by column.
  for (Eigen::Index c = 0; c < lower.outerSize(); ++c)
  {
    for (Eigen::SparseMatrix<double>::InnerIterator it(lower, c); it; ++it)
    {
      const std::size_t r = static_cast<std::size_t>(it.row());
      col[fill[r]] = static_cast<int>(c);
      val[fill[r]++] = it.value();
      if (it.row() != c)
      {
        col[fill[c]] = static_cast<int>(r);
        val[fill[c]++] = it.value();
      }
    }
  }
  return CsrMatrix(n, n, std::move(start), std::move(col), std::move(val));
}

void CsrMatrix::Multiply(const double* x, double* y, int k) const
{
  const std::int64_t* s = this->Start.data();
  const int* c = this->Col.data();
  const double* v = this->Val.data();
  const std::size_t work =
    this->NumRows > 0 ? static_cast<std::size_t>(this->NonZeros() / this->NumRows + 1) * k : 0;
  const auto rows = [&](std::size_t r0, std::size_t r1)
  {
    switch (k)
    {
      case 1:
        MultiplyRows<1>(s, c, v, x, y, r0, r1);
        break;
      case 2:
        MultiplyRows<2>(s, c, v, x, y, r0, r1);
        break;
      case 3:
        MultiplyRows<3>(s, c, v, x, y, r0, r1);
        break;
      case 4:
        MultiplyRows<4>(s, c, v, x, y, r0, r1);
        break;
      case 5:
        MultiplyRows<5>(s, c, v, x, y, r0, r1);
        break;
      case 6:
        MultiplyRows<6>(s, c, v, x, y, r0, r1);
        break;
      case 7:
        MultiplyRows<7>(s, c, v, x, y, r0, r1);
        break;
      case 8:
        MultiplyRows<8>(s, c, v, x, y, r0, r1);
        break;
      default:
        throw std::invalid_argument("CsrMatrix::Multiply: block width must be 1..8");
    }
  };
  if (k < 1 || k > blockrows::kMaxColumns)
  {
    throw std::invalid_argument("CsrMatrix::Multiply: block width must be 1..8");
  }
  blockrows::ForRows(static_cast<std::size_t>(this->NumRows), work, rows);
}

CsrMatrix CsrMatrix::Transposed() const
{
  std::vector<std::int64_t> start(static_cast<std::size_t>(this->NumCols) + 1, 0);
  for (const int c : this->Col)
  {
    ++start[static_cast<std::size_t>(c) + 1];
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<int> col(this->Col.size());
  std::vector<double> val(this->Val.size());
  std::vector<std::int64_t> fill(start.begin(), start.end() - 1);
  for (int r = 0; r < this->NumRows; ++r)
  {
    for (std::int64_t e = this->Start[r]; e < this->Start[r + 1]; ++e)
    {
      const std::int64_t to = fill[this->Col[e]]++;
      col[to] = r;
      val[to] = this->Val[e];
    }
  }
  return CsrMatrix(this->NumCols, this->NumRows, std::move(start), std::move(col), std::move(val));
}

std::vector<double> CsrMatrix::Diagonal() const
{
  std::vector<double> d(static_cast<std::size_t>(this->NumRows), 0.0);
  for (int r = 0; r < this->NumRows; ++r)
  {
    for (std::int64_t e = this->Start[r]; e < this->Start[r + 1]; ++e)
    {
      if (this->Col[e] == r)
      {
        d[r] += this->Val[e];
      }
    }
  }
  return d;
}

} // namespace av
