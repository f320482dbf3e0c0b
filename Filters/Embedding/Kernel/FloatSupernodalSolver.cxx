// SPDX-License-Identifier: BSD-3-Clause
#include "FloatSupernodalSolver.h"

#include "SimdClones.h"

#include <cholmod.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <queue>
#include <stdexcept>
#include <utility>


namespace av
{
namespace
{
typedef float Vec8 __attribute__((vector_size(32), aligned(4)));

// Above this many entries the off-diagonal part of a top-of-tree supernode is split over threads.
constexpr std::int64_t kParallelBlockEntries = 1 << 15;
// Rows per chunk of a split off-diagonal block (a stack buffer of this many vectors).
constexpr int kTopRows = 128;

// Columns per block of the dense triangular solves: the off-block part then runs through the
// register-blocked kernels below instead of one load/store per entry.
constexpr int kTriangleBlock = 16;

inline void Scatter(std::int32_t d, const Vec8& a, Vec8* w, Vec8* slots)
{
  if (d >= 0)
  {
    w[d] -= a;
  }
  else
  {
    slots[-d - 1] += a;
  }
}

/// Columns [j0, j1) of a panel: X(j) -= L(r0..r1, j)ᵀ G, G holding rows r0..r1; eight columns at
/// a time (eight independent accumulator chains).
inline __attribute__((always_inline)) void PanelTransposeTimesG(
  const float* l, int ld, int r0, int r1, const Vec8* g, int j0, int j1, Vec8* x)
{
  const int nb = r1 - r0;
  int j = j0;
  for (; j + 8 <= j1; j += 8)
  {
    const float* c = l + static_cast<std::size_t>(j) * ld + r0;
    Vec8 a0 = {}, a1 = {}, a2 = {}, a3 = {}, a4 = {}, a5 = {}, a6 = {}, a7 = {};
    for (int i = 0; i < nb; ++i)
    {
      const Vec8 gi = g[i];
      a0 += c[i] * gi;
      a1 += c[ld + i] * gi;
      a2 += c[2 * ld + i] * gi;
      a3 += c[3 * ld + i] * gi;
      a4 += c[4 * ld + i] * gi;
      a5 += c[5 * ld + i] * gi;
      a6 += c[6 * ld + i] * gi;
      a7 += c[7 * ld + i] * gi;
    }
    x[j] -= a0;
    x[j + 1] -= a1;
    x[j + 2] -= a2;
    x[j + 3] -= a3;
    x[j + 4] -= a4;
    x[j + 5] -= a5;
    x[j + 6] -= a6;
    x[j + 7] -= a7;
  }
  for (; j < j1; ++j)
  {
    const float* c = l + static_cast<std::size_t>(j) * ld + r0;
    Vec8 a = {};
    for (int i = 0; i < nb; ++i)
    {
      a += c[i] * g[i];
    }
    x[j] -= a;
  }
}

/// Diagonal block [j0, j1) of L11: X(j0..j1) = L(j0..j1, j0..j1)⁻¹ X(j0..j1).
AV_SIMD_CLONES void ForwardTriangle(const float* l, int nr, int j0, int j1, const float* invd, Vec8* x)
{
  for (int j = j0; j < j1; ++j)
  {
    const Vec8 xj = x[j] * invd[j];
    x[j] = xj;
    const float* col = l + static_cast<std::size_t>(j) * nr;
    for (int i = j + 1; i < j1; ++i)
    {
      x[i] -= col[i] * xj;
    }
  }
}

/// Rows [i0, i1) of L11 below the block [j0, j1): X(i) -= L(i, j0..j1) X(j0..j1), streaming
/// eight columns at a time.
AV_SIMD_CLONES void ForwardPanel(const float* l, int nr, int j0, int j1, Vec8* x, int i0, int i1)
{
  int j = j0;
  for (; j + 8 <= j1; j += 8)
  {
    const float* c = l + static_cast<std::size_t>(j) * nr;
    const Vec8 x0 = x[j], x1 = x[j + 1], x2 = x[j + 2], x3 = x[j + 3];
    const Vec8 x4 = x[j + 4], x5 = x[j + 5], x6 = x[j + 6], x7 = x[j + 7];
    for (int i = i0; i < i1; ++i)
    {
      x[i] -= ((c[i] * x0 + c[nr + i] * x1) + (c[2 * nr + i] * x2 + c[3 * nr + i] * x3)) +
        ((c[4 * nr + i] * x4 + c[5 * nr + i] * x5) + (c[6 * nr + i] * x6 + c[7 * nr + i] * x7));
    }
  }
  for (; j < j1; ++j)
  {
    const float* c = l + static_cast<std::size_t>(j) * nr;
    const Vec8 xj = x[j];
    for (int i = i0; i < i1; ++i)
    {
      x[i] -= c[i] * xj;
    }
  }
}

/// Rows [i0, i1) of the off-diagonal block: W(row) -= L21(row, :) X. Accumulated in `tmp`
/// (i1 - i0 vectors) eight columns at a time, streaming the columns like the backward kernel
/// (contiguous, prefetch-friendly), then scattered once.
AV_SIMD_CLONES void ForwardBelow(const float* l, int nr, int nc, const Vec8* x,
  const std::int32_t* dest, int i0, int i1, Vec8* w, Vec8* slots, Vec8* tmp)
{
  const int nb = i1 - i0;
  for (int i = 0; i < nb; ++i)
  {
    tmp[i] = Vec8{};
  }
  int j = 0;
  for (; j + 8 <= nc; j += 8)
  {
    const float* c = l + static_cast<std::size_t>(j) * nr + i0;
    const Vec8 x0 = x[j], x1 = x[j + 1], x2 = x[j + 2], x3 = x[j + 3];
    const Vec8 x4 = x[j + 4], x5 = x[j + 5], x6 = x[j + 6], x7 = x[j + 7];
    for (int i = 0; i < nb; ++i)
    {
      tmp[i] += ((c[i] * x0 + c[nr + i] * x1) + (c[2 * nr + i] * x2 + c[3 * nr + i] * x3)) +
        ((c[4 * nr + i] * x4 + c[5 * nr + i] * x5) + (c[6 * nr + i] * x6 + c[7 * nr + i] * x7));
    }
  }
  for (; j < nc; ++j)
  {
    const float* c = l + static_cast<std::size_t>(j) * nr + i0;
    const Vec8 xj = x[j];
    for (int i = 0; i < nb; ++i)
    {
      tmp[i] += c[i] * xj;
    }
  }
  for (int i = 0; i < nb; ++i)
  {
    Scatter(dest[i0 + i], tmp[i], w, slots);
  }
}

/// Columns [c0, c1): X(j) -= L(r0..r1, j)ᵀ G, G holding rows r0..r1 (gathered W rows for the
/// off-diagonal block, or X itself inside L11).
AV_SIMD_CLONES void BackwardPanel(
  const float* l, int nr, int r0, int r1, const Vec8* g, int c0, int c1, Vec8* x)
{
  PanelTransposeTimesG(l, nr, r0, r1, g, c0, c1, x);
}

/// Diagonal block [j0, j1) of L11ᵀ, once every later row has been applied.
AV_SIMD_CLONES void BackwardTriangle(const float* l, int nr, int j0, int j1, const float* invd, Vec8* x)
{
  for (int j = j1 - 1; j >= j0; --j)
  {
    const float* col = l + static_cast<std::size_t>(j) * nr;
    Vec8 s = x[j];
    for (int i = j + 1; i < j1; ++i)
    {
      s -= col[i] * x[i];
    }
    x[j] = s * invd[j];
  }
}

/// X(0..nc) = L11⁻¹ X in column blocks; `parallel`: the panel updates run on all threads (the
/// big separators at the top of the tree, which nothing else runs beside).
void DiagForward(const float* l, int nr, int nc, const float* invd, Vec8* x, bool parallel)
{
  const int block = parallel ? 64 : 16;
  for (int j0 = 0; j0 < nc; j0 += block)
  {
    const int j1 = std::min(j0 + block, nc);
    ForwardTriangle(l, nr, j0, j1, invd, x);
    if (parallel && static_cast<std::int64_t>(nc - j1) * (j1 - j0) > kParallelBlockEntries)
    {
      tbb::parallel_for(tbb::blocked_range<int>(j1, nc, 128), [&](const tbb::blocked_range<int>& r) {
        ForwardPanel(l, nr, j0, j1, x, r.begin(), r.end());
      });
    }
    else
    {
      ForwardPanel(l, nr, j0, j1, x, j1, nc);
    }
  }
}

/// X(0..nc) = L11⁻ᵀ X in column blocks from the last: each block first takes the dot products
/// of its columns below the block with the solved part (long contiguous column segments; split
/// over threads by column when `parallel`), then its triangle.
void DiagBackward(const float* l, int nr, int nc, const float* invd, Vec8* x, bool parallel)
{
  const int block = parallel ? 64 : 16;
  for (int j1 = nc; j1 > 0;)
  {
    const int j0 = std::max(j1 - block, 0);
    if (parallel && static_cast<std::int64_t>(nc - j1) * (j1 - j0) > kParallelBlockEntries)
    {
      tbb::parallel_for(tbb::blocked_range<int>(j0, j1, 8), [&](const tbb::blocked_range<int>& r) {
        BackwardPanel(l, nr, j1, nc, x + j1, r.begin(), r.end(), x);
      });
    }
    else
    {
      BackwardPanel(l, nr, j1, nc, x + j1, j0, j1, x);
    }
    BackwardTriangle(l, nr, j0, j1, invd, x);
    j1 = j0;
  }
}

template <typename I>
void CopyIndices(const void* src, std::size_t n, std::vector<std::int64_t>& dst)
{
  const I* p = static_cast<const I*>(src);
  dst.assign(p, p + n);
}

/// The supernodal elimination tree (the parent holds the first off-diagonal row) with each
/// subtree's first supernode and work (factor entries); Postordered: every subtree is the
/// contiguous range [First, root], which the task split needs.
struct SupernodeTree
{
  std::vector<std::int32_t> Parent, First;
  std::vector<std::int64_t> Work, SubtreeWork;
  bool Postordered = true;
};

SupernodeTree BuildSupernodeTree(std::size_t n, const std::vector<std::int32_t>& super,
  const std::vector<std::int64_t>& pi, const std::vector<std::int32_t>& s, std::size_t& maxBelow)
{
  const std::int32_t nsi = static_cast<std::int32_t>(super.size() - 1);
  const std::size_t ns = static_cast<std::size_t>(nsi);
  SupernodeTree t;
  t.Parent.assign(ns, -1);
  t.Work.resize(ns);
  t.SubtreeWork.resize(ns);
  t.First.resize(ns);
  std::vector<std::int32_t> colSuper(n), size(ns, 1);
  for (std::int32_t k = 0; k < nsi; ++k)
  {
    std::fill(colSuper.begin() + super[k], colSuper.begin() + super[k + 1], k);
  }
  for (std::int32_t k = 0; k < nsi; ++k)
  {
    const std::int64_t nr = pi[k + 1] - pi[k];
    const std::int32_t nc = super[k + 1] - super[k];
    maxBelow = std::max(maxBelow, static_cast<std::size_t>(nr - nc));
    t.Work[k] = nr * nc;
    if (nr > nc)
    {
      t.Parent[k] = colSuper[s[pi[k] + nc]];
      t.Postordered = t.Postordered && t.Parent[k] > k;
    }
  }
  for (std::int32_t k = 0; k < nsi; ++k)
  {
    t.First[k] = k;
    t.SubtreeWork[k] = t.Work[k];
  }
  for (std::int32_t k = 0; t.Postordered && k < nsi; ++k)
  {
    const std::int32_t p = t.Parent[k];
    if (p >= 0)
    {
      t.First[p] = std::min(t.First[p], t.First[k]);
      size[p] += size[k];
      t.SubtreeWork[p] += t.SubtreeWork[k];
    }
  }
  for (std::int32_t k = 0; t.Postordered && k < nsi; ++k)
  {
    t.Postordered = size[k] == k - t.First[k] + 1; // the subtree is a contiguous range
  }
  return t;
}

/// Splits the heaviest subtree until every remaining one holds at most `taskWork` entries
/// (0: about 1/16 of the factor): returns the roots of the tasks, ascending, and appends the
/// split supernodes to `top`, ascending.
std::vector<std::int32_t> SplitIntoSubtrees(
  const SupernodeTree& tree, std::size_t taskWork, std::vector<std::int32_t>& top)
{
  const std::int32_t nsi = static_cast<std::int32_t>(tree.Parent.size());
  const std::size_t ns = tree.Parent.size();
  std::int64_t total = 0;
  for (std::int64_t w : tree.Work)
  {
    total += w;
  }
  const std::int64_t limit =
    taskWork > 0 ? static_cast<std::int64_t>(taskWork) : std::max<std::int64_t>(total / 16, 1);
  std::vector<std::int32_t> childOff(ns + 1, 0), child(ns);
  for (std::int32_t k = 0; k < nsi; ++k)
  {
    if (tree.Parent[k] >= 0)
    {
      ++childOff[tree.Parent[k] + 1];
    }
  }
  for (std::size_t k = 0; k < ns; ++k)
  {
    childOff[k + 1] += childOff[k];
  }
  std::vector<std::int32_t> fill(childOff.begin(), childOff.end() - 1);
  for (std::int32_t k = 0; k < nsi; ++k)
  {
    if (tree.Parent[k] >= 0)
    {
      child[fill[tree.Parent[k]]++] = k;
    }
  }
  std::priority_queue<std::pair<std::int64_t, std::int32_t>> heap;
  for (std::int32_t k = 0; k < nsi; ++k)
  {
    if (tree.Parent[k] < 0)
    {
      heap.emplace(tree.SubtreeWork[k], k);
    }
  }
  while (!heap.empty() && heap.top().first > limit && top.size() < 4096)
  {
    const std::int32_t k = heap.top().second;
    heap.pop();
    top.push_back(k);
    for (std::int32_t c = childOff[k]; c < childOff[k + 1]; ++c)
    {
      heap.emplace(tree.SubtreeWork[child[c]], child[c]);
    }
  }
  std::vector<std::int32_t> taskRoots;
  for (; !heap.empty(); heap.pop())
  {
    taskRoots.push_back(heap.top().second);
  }
  std::sort(taskRoots.begin(), taskRoots.end());
  std::sort(top.begin(), top.end());
  return taskRoots;
}
} // namespace

FloatSupernodalSolver::FloatSupernodalSolver(const cholmod_factor& f, std::size_t taskWork)
{
  if (!f.is_super || !f.is_ll || f.xtype != CHOLMOD_REAL || f.dtype != CHOLMOD_DOUBLE ||
    !f.x || !f.super)
  {
    throw std::invalid_argument("FloatSupernodalSolver: need a real, double, supernodal LL^T factor");
  }
  if (f.n > static_cast<std::size_t>(INT32_MAX))
  {
    throw std::invalid_argument("FloatSupernodalSolver: factor too large");
  }
  this->CopyFactor(f);
  const SupernodeTree tree = BuildSupernodeTree(this->N, this->Super, this->Pi, this->S, this->MaxBelow);
  const std::vector<std::int32_t> taskRoots =
    tree.Postordered ? SplitIntoSubtrees(tree, taskWork, this->Top) : std::vector<std::int32_t>();
  if (!tree.Postordered)
  {
    for (std::int32_t k = 0; k < static_cast<std::int32_t>(tree.Parent.size()); ++k)
    {
      this->Top.push_back(k);
    }
  }
  this->AddTasks(taskRoots, tree.First, tree.SubtreeWork);
}

void FloatSupernodalSolver::CopyFactor(const cholmod_factor& f)
{
  const std::size_t n = f.n, ns = f.nsuper;
  this->N = n;
  std::vector<std::int64_t> super, perm, s;
  if (f.itype == CHOLMOD_LONG)
  {
    CopyIndices<SuiteSparse_long>(f.super, ns + 1, super);
    CopyIndices<SuiteSparse_long>(f.pi, ns + 1, this->Pi);
    CopyIndices<SuiteSparse_long>(f.px, ns + 1, this->Px);
    CopyIndices<SuiteSparse_long>(f.s, f.ssize, s);
    CopyIndices<SuiteSparse_long>(f.Perm, n, perm);
  }
  else
  {
    CopyIndices<int>(f.super, ns + 1, super);
    CopyIndices<int>(f.pi, ns + 1, this->Pi);
    CopyIndices<int>(f.px, ns + 1, this->Px);
    CopyIndices<int>(f.s, f.ssize, s);
    CopyIndices<int>(f.Perm, n, perm);
  }
  this->Super.assign(super.begin(), super.end());
  this->S.assign(s.begin(), s.end());
  this->Perm.assign(perm.begin(), perm.end());

  const double* lx = static_cast<const double*>(f.x);
  this->Lx.resize(f.xsize);
  this->InvDiag.resize(n);
  tbb::parallel_for(std::int32_t(0), static_cast<std::int32_t>(ns), [&](std::int32_t k) {
    const std::int64_t nr = this->Pi[k + 1] - this->Pi[k];
    const std::int32_t nc = this->Super[k + 1] - this->Super[k];
    for (std::int64_t e = this->Px[k]; e < this->Px[k] + nr * nc; ++e)
    {
      this->Lx[e] = static_cast<float>(lx[e]);
    }
    for (std::int32_t j = 0; j < nc; ++j)
    {
      this->InvDiag[this->Super[k] + j] =
        static_cast<float>(1.0 / lx[this->Px[k] + static_cast<std::int64_t>(j) * nr + j]);
    }
  });
}

void FloatSupernodalSolver::AddTasks(const std::vector<std::int32_t>& taskRoots,
  const std::vector<std::int32_t>& first, const std::vector<std::int64_t>& subtreeWork)
{
  // Destinations: a task writes rows of its own subtree directly and sums its updates to the
  // shared ancestors into private slots, added to W afterwards in task order.
  this->Dest.assign(this->S.begin(), this->S.end());
  std::vector<std::int32_t> slotOf(this->N, -1);
  for (std::int32_t root : taskRoots)
  {
    Task t;
    t.FirstSuper = first[root];
    t.LastSuper = root;
    t.FirstSlot = static_cast<std::int64_t>(this->SlotRow.size());
    const std::int32_t colEnd = this->Super[root + 1];
    for (std::int32_t k = t.FirstSuper; k <= root; ++k)
    {
      const std::int32_t nc = this->Super[k + 1] - this->Super[k];
      for (std::int64_t p = this->Pi[k] + nc; p < this->Pi[k + 1]; ++p)
      {
        const std::int32_t r = this->S[p];
        if (r >= colEnd)
        {
          if (slotOf[r] < 0)
          {
            slotOf[r] = static_cast<std::int32_t>(this->SlotRow.size() - t.FirstSlot);
            this->SlotRow.push_back(r);
          }
          this->Dest[p] = -(1 + static_cast<std::int32_t>(t.FirstSlot) + slotOf[r]);
        }
      }
    }
    t.NumSlots = static_cast<std::int64_t>(this->SlotRow.size()) - t.FirstSlot;
    for (std::int64_t q = t.FirstSlot; q < t.FirstSlot + t.NumSlots; ++q)
    {
      slotOf[this->SlotRow[q]] = -1;
    }
    this->Tasks.push_back(t);
    this->TaskEntryCount += static_cast<std::size_t>(subtreeWork[root]);
  }
}

void FloatSupernodalSolver::SolveBlock(Vec8* w) const
{
  // One supernode of each sweep; `top`: a big separator that nothing else runs beside, whose
  // panels split over the threads (then `scratch` is unused for the forward off-diagonal block).
  const auto forward = [this, w](std::int32_t k, Vec8* slots, Vec8* scratch, bool top) {
    const int nr = static_cast<int>(this->Pi[k + 1] - this->Pi[k]);
    const int nc = this->Super[k + 1] - this->Super[k];
    const float* l = this->Lx.data() + this->Px[k];
    Vec8* x = w + this->Super[k];
    const std::int32_t* dest = this->Dest.data() + this->Pi[k];
    DiagForward(l, nr, nc, this->InvDiag.data() + this->Super[k], x, top);
    if (top && static_cast<std::int64_t>(nr - nc) * nc > kParallelBlockEntries)
    {
      tbb::parallel_for(tbb::blocked_range<int>(nc, nr, kTopRows),
        [&](const tbb::blocked_range<int>& r) {
          Vec8 tmp[kTopRows];
          ForwardBelow(l, nr, nc, x, dest, r.begin(), r.end(), w, slots, tmp);
        },
        tbb::simple_partitioner());
    }
    else
    {
      ForwardBelow(l, nr, nc, x, dest, nc, nr, w, slots, scratch);
    }
  };
  const auto backward = [this, w](std::int32_t k, Vec8* scratch, bool top) {
    const int nr = static_cast<int>(this->Pi[k + 1] - this->Pi[k]);
    const int nc = this->Super[k + 1] - this->Super[k];
    const float* l = this->Lx.data() + this->Px[k];
    Vec8* x = w + this->Super[k];
    const std::int32_t* rows = this->S.data() + this->Pi[k] + nc;
    for (int i = 0; i < nr - nc; ++i)
    {
      scratch[i] = w[rows[i]];
    }
    if (top && static_cast<std::int64_t>(nr - nc) * nc > kParallelBlockEntries)
    {
      tbb::parallel_for(tbb::blocked_range<int>(0, nc, 16), [&](const tbb::blocked_range<int>& r) {
        BackwardPanel(l, nr, nc, nr, scratch, r.begin(), r.end(), x);
      });
    }
    else
    {
      BackwardPanel(l, nr, nc, nr, scratch, 0, nc, x);
    }
    DiagBackward(l, nr, nc, this->InvDiag.data() + this->Super[k], x, top);
  };
  const std::size_t scratchFloats = 8 * this->MaxBelow;

  // Forward: L y = b. Subtrees in parallel (updates to shared ancestors into their slots, added
  // in task order), then the top of the tree.
  Vec8* slots = reinterpret_cast<Vec8*>(this->Slots.data());
  std::fill(this->Slots.begin(), this->Slots.end(), 0.0f);
  tbb::parallel_for(std::size_t(0), this->Tasks.size(), [&](std::size_t t) {
    std::vector<float> buffer(scratchFloats);
    for (std::int32_t k = this->Tasks[t].FirstSuper; k <= this->Tasks[t].LastSuper; ++k)
    {
      forward(k, slots, reinterpret_cast<Vec8*>(buffer.data()), false);
    }
  });
  for (std::size_t q = 0; q < this->SlotRow.size(); ++q)
  {
    w[this->SlotRow[q]] -= slots[q];
  }
  std::vector<float> topBuffer(scratchFloats);
  Vec8* topScratch = reinterpret_cast<Vec8*>(topBuffer.data());
  for (std::int32_t k : this->Top)
  {
    forward(k, nullptr, topScratch, true);
  }

  // Backward: Lᵀ x = y. The top first, then the subtrees in parallel (they only read ancestors).
  for (auto it = this->Top.rbegin(); it != this->Top.rend(); ++it)
  {
    backward(*it, topScratch, true);
  }
  tbb::parallel_for(std::size_t(0), this->Tasks.size(), [&](std::size_t t) {
    std::vector<float> buffer(scratchFloats);
    for (std::int32_t k = this->Tasks[t].LastSuper; k >= this->Tasks[t].FirstSuper; --k)
    {
      backward(k, reinterpret_cast<Vec8*>(buffer.data()), false);
    }
  });
}

void FloatSupernodalSolver::Solve(const double* b, double* x, int nrhs) const
{
  const std::size_t n = this->N;
  if (n == 0 || nrhs <= 0)
  {
    return;
  }
  this->W.resize(8 * n);
  this->Slots.resize(8 * this->SlotRow.size());
  Vec8* w = reinterpret_cast<Vec8*>(this->W.data());
  for (int c0 = 0; c0 < nrhs; c0 += 8)
  {
    const int nb = std::min(8, nrhs - c0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096),
      [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t k = r.begin(); k != r.end(); ++k)
        {
          Vec8 v = {};
          for (int q = 0; q < nb; ++q)
          {
            v[q] = static_cast<float>(b[static_cast<std::size_t>(c0 + q) * n + this->Perm[k]]);
          }
          w[k] = v;
        }
      });
    this->SolveBlock(w);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096),
      [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t k = r.begin(); k != r.end(); ++k)
        {
          for (int q = 0; q < nb; ++q)
          {
            x[static_cast<std::size_t>(c0 + q) * n + this->Perm[k]] = w[k][q];
          }
        }
      });
  }
}

} // namespace av
