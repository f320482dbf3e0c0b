// SPDX-License-Identifier: BSD-3-Clause
// BlockRowOps: row-parallel loops and deterministic column dot products on blocks of k vectors
// stored row-major (row i holds the k entries i*k .. i*k+k-1), for the iterative global step.
#ifndef av_BlockRowOps_h
#define av_BlockRowOps_h

#include <cstddef>
#include <functional>

namespace av
{
namespace blockrows
{

/// The widest block the kernels take (the solver splits wider right-hand sides).
constexpr int kMaxColumns = 8;

/// Calls fn(begin, end) over [0, rows) in chunks, on all threads of the caller's TBB arena when
/// rows * work (about the flops of one row) is large enough to pay for the tasks.
void ForRows(std::size_t rows,
  std::size_t work,
  const std::function<void(std::size_t, std::size_t)>& fn);

/// out[c] = sum over rows of a[i*k+c] * b[i*k+c], c < k <= kMaxColumns. Deterministic: fixed
/// chunks, whatever the thread count, summed in order.
void ColumnDots(const double* a, const double* b, std::size_t rows, int k, double* out);

} // namespace blockrows
} // namespace av

#endif
