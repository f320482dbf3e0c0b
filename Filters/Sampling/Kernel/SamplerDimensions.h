// SPDX-License-Identifier: BSD-3-Clause
// SamplerDimensions: the embedding dimensions of the particle sampler and its fixed-capacity
// Eigen vector type (no heap allocation per particle, whatever the dimension).
#ifndef av_SamplerDimensions_h
#define av_SamplerDimensions_h

#include <Eigen/Core>

namespace av
{
namespace sampling
{

constexpr int kMaxDim = 20; ///< largest embedding dimension the sampler accepts

/// Storage bound of a D-vector: D itself, or kMaxDim for the runtime dimension (Eigen::Dynamic).
template <int D>
constexpr int MaxDimOf = D == Eigen::Dynamic ? kMaxDim : D;

/// A point of R^D (D = Eigen::Dynamic: runtime size, stack storage up to kMaxDim).
template <int D>
using PointVector = Eigen::Matrix<double, D, 1, Eigen::ColMajor, MaxDimOf<D>, 1>;

/// Three principal axes of R^D as rows.
template <int D>
using AxesMatrix = Eigen::Matrix<double, 3, D, Eigen::RowMajor, 3, MaxDimOf<D>>;

} // namespace sampling
} // namespace av

#endif
