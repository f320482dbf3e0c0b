// SPDX-License-Identifier: BSD-3-Clause
// GaussianKernel: the vectorized repulsion kernel exp(-d^2 / (4 sigma^2)) of the particle
// sampler, over chunks of squared distances (internal to the sampler).
#ifndef av_GaussianKernel_h
#define av_GaussianKernel_h

#include <cstddef>

namespace av
{
namespace sampling
{

/// Largest chunk of GaussianKernel: the energy loop evaluates the kernel this many pairs at once.
constexpr std::size_t kExpChunk = 32;

/**
 * w[j] = exp(-d2[j] * inv4s2) where d2[j] < rc2, else 0 (j < m <= kExpChunk; d2 >= 0), within a
 * few ulp of std::exp and vectorized (an AVX2/FMA clone where the CPU has it).
 */
void GaussianKernel(const double* d2, double* w, std::size_t m, double inv4s2, double rc2);

} // namespace sampling
} // namespace av

#endif
