// SPDX-License-Identifier: BSD-3-Clause
// CsrMatrix: a sparse matrix in compressed rows, multiplied into blocks of up to eight vectors
// at once (the iterative global step's CG and V-cycle).
#ifndef av_CsrMatrix_h
#define av_CsrMatrix_h

#include <Eigen/SparseCore>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{

/**
 * Compressed sparse rows with 32-bit column indices. Multiply() reads the matrix once for all k
 * vectors of a row-major block (k <= 8: one pass instead of k, the products are memory bound)
 * and splits the rows over the caller's TBB threads; each output row is written by one task,
 * so the result does not depend on the thread count.
 */
class CsrMatrix
{
public:
  CsrMatrix() = default;
  /// rows x cols from CSR arrays (start: rows + 1 offsets).
  CsrMatrix(int rows,
    int cols,
    std::vector<std::int64_t> start,
    std::vector<int> column,
    std::vector<double> value);

  /// The full symmetric matrix whose lower triangle (column major, rows >= column) is given.
  static CsrMatrix SymmetricFromLower(const Eigen::SparseMatrix<double>& lower);

  int Rows() const { return this->NumRows; }
  int Cols() const { return this->NumCols; }
  std::int64_t NonZeros() const { return this->Start.empty() ? 0 : this->Start.back(); }
  const std::vector<std::int64_t>& RowStart() const { return this->Start; }
  const std::vector<int>& Column() const { return this->Col; }
  const std::vector<double>& Value() const { return this->Val; }

  /// y = A x for k vectors: x is Cols() x k, y is Rows() x k, both row-major; 1 <= k <= 8.
  void Multiply(const double* x, double* y, int k) const;

  CsrMatrix Transposed() const;
  /// The diagonal entries (0 where a row has none).
  std::vector<double> Diagonal() const;

private:
  int NumRows = 0, NumCols = 0;
  std::vector<std::int64_t> Start;
  std::vector<int> Col;
  std::vector<double> Val;
};

} // namespace av

#endif
