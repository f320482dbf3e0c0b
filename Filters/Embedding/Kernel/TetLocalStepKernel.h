// SPDX-License-Identifier: BSD-3-Clause
// TetLocalStepKernel: the embedding's local step for tetrahedra, four elements per SIMD vector.
#ifndef av_TetLocalStepKernel_h
#define av_TetLocalStepKernel_h

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{

/// Per-element data of the local step (layouts of EmbeddingSolver's internals).
struct TetLocalStepData
{
  const std::int32_t* Cells = nullptr; ///< NE x 4 vertex ids
  const double* Gt = nullptr;          ///< NE x 4 x 3 gradient operator rows
  const double* A = nullptr;           ///< NE x 3 x 3 symmetric square root of the metric
  const double* W = nullptr;           ///< NE element weights
  const double* X = nullptr;           ///< NP x Stride embedding (first 3 columns = input points)
  int Stride = 8;                      ///< target dimension m̄
  double* C = nullptr;                 ///< out: NE x 4 x (Stride - 3) right-hand side parts
};

/// True when TetLocalStepRange has a vector kernel for this target dimension (4, 5, 6, 8, 10).
bool HasTetLocalStepKernel(int targetDim);

/**
 * Local step for elements [j0, j1) of a tet mesh: with T_f the free rows of the element map
 * (its first 3 rows are the identity), BᵀB = A (I + T_fᵀT_f) A, N = A (BᵀB)^{-1/2} A and
 * R_f = T_f N; writes C_j = w_j G_j R_fᵀ and returns Σ w_j (‖I − N‖² + ‖T_f − R_f‖²).
 * (BᵀB)^{-1/2} by Cayley–Hamilton from the invariants of its square root, whose trace is the
 * Newton root of a quartic (see Filters/Embedding/README.md). Four elements per vector (AVX2
 * clone chosen at load time). Elements whose BᵀB is too ill-conditioned for this route are
 * appended to `failed` (nothing written for them) for the caller's general path.
 */
double TetLocalStepRange(
  const TetLocalStepData& d, std::size_t j0, std::size_t j1, std::vector<std::int32_t>& failed);

} // namespace av

#endif
