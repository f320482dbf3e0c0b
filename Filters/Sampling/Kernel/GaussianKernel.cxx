// SPDX-License-Identifier: BSD-3-Clause
// GaussianKernel: a branch-free exp for non-positive arguments and the chunked kernel built on it.
#include "GaussianKernel.h"

#include "SimdClones.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace av
{
namespace sampling
{
namespace
{

/// exp(x) for x in [-700, 0], within a few ulp of std::exp; inline and branch-free so that
/// loops over it vectorize (glibc's exp is a call per value).
inline double ExpNonPositive(double x)
{
  // k = round(x / ln 2) by the 1.5 * 2^52 trick: the low bits of t hold k.
  const double magic = 0x1.8p52;
  const double t = x * 1.4426950408889634 + magic;
  const double k = t - magic;
  const double r = (x - k * 0x1.62e42fefa39efp-1) - k * 0x1.abc9e3b39803fp-56; // |r| <= ln2 / 2
  // Taylor series to degree 13 (truncation error < 1e-17 relative).
  double p = 1.0 / 6227020800.0;
  p = p * r + 1.0 / 479001600.0;
  p = p * r + 1.0 / 39916800.0;
  p = p * r + 1.0 / 3628800.0;
  p = p * r + 1.0 / 362880.0;
  p = p * r + 1.0 / 40320.0;
  p = p * r + 1.0 / 5040.0;
  p = p * r + 1.0 / 720.0;
  p = p * r + 1.0 / 120.0;
  p = p * r + 1.0 / 24.0;
  p = p * r + 1.0 / 6.0;
  p = p * r + 0.5;
  p = p * r + 1.0;
  p = p * r + 1.0;
  std::uint64_t bits;
  std::memcpy(&bits, &t, sizeof bits);
  bits = (bits + 1023) << 52; // 2^k (k >= -1010: a normal number)
  double scale;
  std::memcpy(&scale, &bits, sizeof scale);
  return p * scale;
}

} // namespace

// The comparisons are on the bit patterns (ordered like the values for non-negative doubles):
// floating-point selects would keep GCC from vectorizing the loop.
AV_SIMD_CLONES void GaussianKernel(const double* d2,
  double* w,
  std::size_t m,
  double inv4s2,
  double rc2)
{
  const double clampD2 = std::min(rc2, 700.0 / inv4s2); // exp's argument stays >= -700
  std::int64_t bRc2, bClamp;
  std::memcpy(&bRc2, &rc2, sizeof bRc2);
  std::memcpy(&bClamp, &clampD2, sizeof bClamp);
  for (std::size_t j = 0; j < m; ++j)
  {
    std::int64_t b;
    std::memcpy(&b, d2 + j, sizeof b);
    const std::uint64_t keep = b < bRc2 ? ~0ull : 0ull;
    b = std::min(b, bClamp);
    double d;
    std::memcpy(&d, &b, sizeof d);
    const double v = ExpNonPositive(-d * inv4s2);
    std::uint64_t vb;
    std::memcpy(&vb, &v, sizeof vb);
    vb &= keep;
    std::memcpy(w + j, &vb, sizeof vb);
  }
}

} // namespace sampling
} // namespace av
