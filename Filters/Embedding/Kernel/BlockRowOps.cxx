// SPDX-License-Identifier: BSD-3-Clause
#include "BlockRowOps.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <vector>

namespace av
{
namespace blockrows
{

namespace
{
// Chunk of the dot products: fixed so that the sums do not depend on the thread count.
constexpr std::size_t kDotChunk = 4096;
// Below this much work a loop runs on the calling thread (task overhead is a few µs).
constexpr std::size_t kParallelWork = 1 << 15;
}

void ForRows(std::size_t rows,
  std::size_t work,
  const std::function<void(std::size_t, std::size_t)>& fn)
{
  if (rows * work < kParallelWork)
  {
    if (rows > 0)
    {
      fn(0, rows);
    }
    return;
  }
  const std::size_t grain =
    std::max<std::size_t>(256, kParallelWork / std::max<std::size_t>(work, 1));
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows, grain),
    [&](const tbb::blocked_range<std::size_t>& r) { fn(r.begin(), r.end()); });
}

void ColumnDots(const double* a, const double* b, std::size_t rows, int k, double* out)
{
  const std::size_t chunks = (rows + kDotChunk - 1) / kDotChunk;
  std::vector<double> partial(chunks * kMaxColumns, 0.0);
  const auto chunkSums = [&](std::size_t c0, std::size_t c1)
  {
    for (std::size_t c = c0; c < c1; ++c)
    {
      double s[kMaxColumns] = { 0 };
      const std::size_t end = std::min(rows, (c + 1) * kDotChunk);
      for (std::size_t i = c * kDotChunk; i < end; ++i)
      {
        for (int j = 0; j < k; ++j)
        {
          s[j] += a[i * k + j] * b[i * k + j];
        }
      }
      for (int j = 0; j < k; ++j)
      {
        partial[c * kMaxColumns + j] = s[j];
      }
    }
  };
  if (chunks > 1 && rows * k >= kParallelWork)
  {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1),
      [&](const tbb::blocked_range<std::size_t>& r) { chunkSums(r.begin(), r.end()); });
  }
  else
  {
    chunkSums(0, chunks);
  }
  for (int j = 0; j < k; ++j)
  {
    out[j] = 0.0;
  }
  for (std::size_t c = 0; c < chunks; ++c)
  {
    for (int j = 0; j < k; ++j)
    {
      out[j] += partial[c * kMaxColumns + j];
    }
  }
}

} // namespace blockrows
} // namespace av
