// SPDX-License-Identifier: BSD-3-Clause
// FloatSupernodalSolver: triangular solves with a single-precision, tree-parallel copy of a
// CHOLMOD supernodal Cholesky factor.
#ifndef av_FloatSupernodalSolver_h
#define av_FloatSupernodalSolver_h

#include <cstddef>
#include <cstdint>
#include <vector>

struct cholmod_factor_struct;

namespace av
{

/**
 * Solves K X = B given CHOLMOD's supernodal factor L Lᵀ = P K Pᵀ.
 *
 * Why: a solve reads the whole factor twice and is bound by memory bandwidth (the embedding's
 * cube2 factor holds 38.6 M entries, 309 MB in double). This class keeps a float copy (half the
 * bytes) and runs independent subtrees of the supernodal elimination tree on all threads (TBB),
 * where CHOLMOD's solve streams the factor on one. Right-hand sides are processed eight at a
 * time (one 8-float vector per row). The result carries the factor's single-precision rounding,
 * relative error ≈ κ(K)·6e-8; callers that need more keep the double factor as a fallback.
 *
 * Deterministic: the task split depends on the factor only (not on the thread count) and the
 * updates that tasks make to shared ancestors are summed in a fixed order.
 */
class FloatSupernodalSolver
{
public:
  FloatSupernodalSolver() = default;

  /**
   * Copies `factor`, which must be a real supernodal LLᵀ factor (what cholmod_factorize gives
   * with the supernodal method). `taskWork`: subtrees with more factor entries than this are
   * split further (0: about 1/16 of the factor); tests use small values to exercise the split.
   * Throws std::invalid_argument for any other kind of factor.
   */
  explicit FloatSupernodalSolver(const cholmod_factor_struct& factor, std::size_t taskWork = 0);

  /// Number of rows (0 when default-constructed).
  std::size_t Rows() const { return this->N; }

  /// Stored factor entries.
  std::size_t FactorEntries() const { return this->Lx.size(); }

  /// Number of parallel subtree tasks and supernodes left to the sequential top of the tree.
  std::size_t NumTasks() const { return this->Tasks.size(); }
  std::size_t NumTopSupernodes() const { return this->Top.size(); }
  /// Factor entries inside the parallel subtree tasks (the rest is the top of the tree).
  std::size_t TaskEntries() const { return this->TaskEntryCount; }

  /**
   * X = K⁻¹ B for `nrhs` right-hand sides; `b` and `x` are Rows() x nrhs, column-major with
   * leading dimension Rows(); they may be the same array. Not thread-safe (uses internal
   * work buffers).
   */
  void Solve(const double* b, double* x, int nrhs) const;

private:
  struct Task
  {
    std::int32_t FirstSuper = 0, LastSuper = 0; // supernodes [First, Last] (a subtree)
    std::int64_t FirstSlot = 0, NumSlots = 0;   // its private rows for shared-ancestor updates
  };
  // Eight right-hand-side values of one row; storage is plain floats, so no alignment is assumed.
  typedef float Vec8 __attribute__((vector_size(32), aligned(4)));

  void SolveBlock(Vec8* w) const; // all eight columns of w (permuted order)
  /// Indices, float values and inverse diagonal of the factor.
  void CopyFactor(const cholmod_factor_struct& factor);
  /// One task per subtree root (subtree [first[root], root]) with its slots and destinations.
  void AddTasks(const std::vector<std::int32_t>& taskRoots, const std::vector<std::int32_t>& first,
    const std::vector<std::int64_t>& subtreeWork);

  std::size_t N = 0;
  std::vector<std::int32_t> Super; // nsuper + 1: first column of each supernode
  std::vector<std::int64_t> Pi;    // nsuper + 1: into S / Dest
  std::vector<std::int64_t> Px;    // nsuper + 1: into Lx
  std::vector<std::int32_t> S;     // row indices
  std::vector<std::int32_t> Dest;  // per row entry: row of W (>= 0) or -(1 + slot)
  std::vector<float> Lx;           // values, column-major per supernode
  std::vector<float> InvDiag;      // 1 / L(j, j)
  std::vector<std::int32_t> Perm;  // row k of the factor is row Perm[k] of K
  std::vector<Task> Tasks;
  std::vector<std::int32_t> Top;        // supernodes outside every task, ascending
  std::vector<std::int32_t> SlotRow;    // slot -> row of W it is added to
  std::size_t MaxBelow = 0;             // largest number of off-diagonal rows
  std::size_t TaskEntryCount = 0;
  mutable std::vector<float> W, Slots;  // work buffers, 8 floats per row
};

} // namespace av

#endif
