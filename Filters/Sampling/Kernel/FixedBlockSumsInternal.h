// SPDX-License-Identifier: BSD-3-Clause
// FixedBlockSumsInternal: the particle sampler's deterministic parallel sums (fixed blocks added
// in block order: the same bits for any number of threads) and the vector updates built on them.
#ifndef av_FixedBlockSumsInternal_h
#define av_FixedBlockSumsInternal_h

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

namespace av
{
namespace sampling
{

/// a . b with four interleaved partial sums (a single running sum is one add latency per
/// value; the fixed order keeps the result independent of the thread count).
inline double Dot(const double* a, const double* b, std::size_t n)
{
  double acc[4] = { 0.0, 0.0, 0.0, 0.0 };
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4)
    for (std::size_t k = 0; k < 4; ++k)
      acc[k] += a[i + k] * b[i + k];
  for (; i < n; ++i)
    acc[0] += a[i] * b[i];
  return (acc[0] + acc[1]) + (acc[2] + acc[3]);
}

/// Parallel sums over fixed blocks of kBlock values, with a reused buffer of block partials.
class FixedBlockSums
{
public:
  static constexpr std::size_t kBlock = 4096; ///< values per block of the parallel sums

  /// Sums f(i0, i1, out) (out: M partial sums of [i0, i1)) over fixed blocks of [0, n) in
  /// parallel, then adds the blocks' partials in block order.
  template <int M, class F>
  std::array<double, M> Sum(std::size_t n, F&& f)
  {
    const std::size_t blocks = (n + kBlock - 1) / kBlock;
    Partials.resize(blocks * M);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks, 1),
      [&](const tbb::blocked_range<std::size_t>& r)
      {
        for (std::size_t b = r.begin(); b != r.end(); ++b)
          f(b * kBlock, std::min(n, (b + 1) * kBlock), Partials.data() + b * M);
      });
    std::array<double, M> sum{};
    for (std::size_t b = 0; b < blocks; ++b)
      for (int m = 0; m < M; ++m)
        sum[static_cast<std::size_t>(m)] += Partials[b * M + static_cast<std::size_t>(m)];
    return sum;
  }

  /// y = s y + a x (s == 0: y = a x; x null: no a x term), then returns z . y (z null: 0);
  /// one parallel pass over the n values.
  double ScaleAddDot(std::size_t n, double s, double a, const double* x, double* y, const double* z)
  {
    return Sum<1>(n,
      [&](std::size_t i0, std::size_t i1, double* out)
      {
        if (s == 0.0)
          for (std::size_t i = i0; i < i1; ++i)
            y[i] = x ? a * x[i] : 0.0;
        else if (x)
          for (std::size_t i = i0; i < i1; ++i)
            y[i] = s * y[i] + a * x[i];
        else if (s != 1.0)
          for (std::size_t i = i0; i < i1; ++i)
            y[i] *= s;
        out[0] = z ? Dot(z + i0, y + i0, i1 - i0) : 0.0;
      })[0];
  }

private:
  std::vector<double> Partials; ///< per-block partial sums
};

} // namespace sampling
} // namespace av

#endif
