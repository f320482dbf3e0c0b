// SPDX-License-Identifier: BSD-3-Clause
// Conforming, longest-first splitting of the edges that are long in the metric (the refinement
// half of MetricAdaptedMesh), and the working-state helpers both halves share.
#include "AdaptiveMeshState.h"

#include "MetricAlgebra.h"
#include "MetricFieldOps.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>

namespace av
{

const int kSimplexEdges[6][2] = { { 0, 1 }, { 1, 2 }, { 0, 2 }, { 0, 3 }, { 1, 3 }, { 2, 3 } };

double AdaptiveMeshState::EdgeLength(std::int32_t a, std::int32_t b) const
{
  const Eigen::Matrix3d q = 0.5 *
    (UnpackSymmetric(SqrtMetric.data() + 6 * static_cast<std::size_t>(a)) +
      UnpackSymmetric(SqrtMetric.data() + 6 * static_cast<std::size_t>(b)));
  const Eigen::Vector3d d =
    Position(static_cast<std::size_t>(b)) - Position(static_cast<std::size_t>(a));
  return LengthScale * (q * d).norm();
}

void AdaptiveMeshState::UpdateSqrtMetric(std::size_t first)
{
  const std::size_t n = NumPoints();
  SqrtMetric.resize(6 * n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(first, n, 1024),
    [&](const tbb::blocked_range<std::size_t>& r)
    {
      for (std::size_t i = r.begin(); i != r.end(); ++i)
        PackSymmetric(
          SymmetricSqrt(UnpackSymmetric(Metric.data() + 6 * i)), SqrtMetric.data() + 6 * i);
    });
}

namespace
{
struct EdgeEntry
{
  std::uint64_t Key;
  std::int32_t Cell;
};

/// Parents of the midpoint of a and b: half of each, merged by input id. Both points lie in the
/// input element that contains the edge, so at most its 4 vertices carry weight.
void MidpointParents(const AdaptiveMeshState& s,
  std::int32_t a,
  std::int32_t b,
  std::int32_t* ids,
  double* w)
{
  int n = 0;
  for (int k = 0; k < 4; ++k)
  {
    ids[k] = -1;
    w[k] = 0.0;
  }
  for (const std::int32_t p : { a, b })
  {
    for (int k = 0; k < 4; ++k)
    {
      const std::int32_t id = s.Parents[4 * static_cast<std::size_t>(p) + k];
      if (id < 0)
        continue;
      const double wk = 0.5 * s.Weights[4 * static_cast<std::size_t>(p) + k];
      int slot = 0;
      while (slot < n && ids[slot] != id)
        ++slot;
      if (slot == n)
      {
        if (n == 4)
          continue; // cannot happen for a conforming input (see above); keeps memory safe
        ids[n++] = id;
      }
      w[slot] += wk;
    }
  }
}

/// The edges of the active cells, sorted by key, and where each edge's run of cells starts.
void CollectEdges(const AdaptiveMeshState& s,
  const std::vector<std::int32_t>& active,
  std::vector<EdgeEntry>& entries,
  std::vector<std::size_t>& starts)
{
  const int ne = s.SimplexDim == 3 ? 6 : 3;
  const int nv = s.Nv();
  entries.resize(active.size() * ne);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, active.size(), 2048),
    [&](const tbb::blocked_range<std::size_t>& r)
    {
      for (std::size_t i = r.begin(); i != r.end(); ++i)
      {
        const std::int32_t c = active[i];
        const std::int32_t* v = s.Cells.data() + static_cast<std::size_t>(c) * nv;
        for (int e = 0; e < ne; ++e)
          entries[i * ne + e] = { EdgeKey(v[kSimplexEdges[e][0]], v[kSimplexEdges[e][1]]), c };
      }
    });
  tbb::parallel_sort(entries.begin(),
    entries.end(),
    [](const EdgeEntry& x, const EdgeEntry& y)
    { return x.Key < y.Key || (x.Key == y.Key && x.Cell < y.Cell); });
  starts.clear();
  for (std::size_t i = 0; i < entries.size(); ++i)
  {
    if (i == 0 || entries[i].Key != entries[i - 1].Key)
      starts.push_back(i);
  }
  starts.push_back(entries.size());
}

/// Splits the edge `key` (its cells: entries[b, e)) at its midpoint; children are appended.
void SplitEdge(AdaptiveMeshState& s,
  std::uint64_t key,
  const EdgeEntry* cells,
  std::size_t count,
  std::vector<std::int32_t>& children)
{
  const std::int32_t a = static_cast<std::int32_t>(key >> 32);
  const std::int32_t b = static_cast<std::int32_t>(key & 0xffffffffu);
  const std::int32_t m = static_cast<std::int32_t>(s.NumPoints());
  for (int d = 0; d < s.AmbientDim; ++d)
    s.Points.push_back(0.5 * (s.Point(a)[d] + s.Point(b)[d]));
  std::int32_t ids[4];
  double w[4];
  MidpointParents(s, a, b, ids, w);
  s.Parents.insert(s.Parents.end(), ids, ids + 4);
  s.Weights.insert(s.Weights.end(), w, w + 4);
  s.Metric.resize(s.Metric.size() + 6, 0.0); // filled for all new points at once
  const int nv = s.Nv();
  for (std::size_t i = 0; i < count; ++i)
  {
    const std::size_t c = static_cast<std::size_t>(cells[i].Cell);
    std::int32_t child[4];
    int ia = -1, ib = -1;
    for (int k = 0; k < nv; ++k)
    {
      child[k] = s.Cells[c * nv + k];
      ia = child[k] == a ? k : ia;
      ib = child[k] == b ? k : ib;
    }
    // Replacing one end by the midpoint keeps the orientation of both halves.
    s.Cells[c * nv + ib] = m;
    child[ia] = m;
    children.push_back(static_cast<std::int32_t>(s.NumCells()));
    s.Cells.insert(s.Cells.end(), child, child + nv);
    s.CellParent.push_back(s.CellParent[c]);
  }
}

/// Log-Euclidean metric of the points [first, n) from their input parents.
void InterpolateNewMetrics(AdaptiveMeshState& s, const MetricField& inputMetric, std::size_t first)
{
  tbb::parallel_for(tbb::blocked_range<std::size_t>(first, s.NumPoints(), 256),
    [&](const tbb::blocked_range<std::size_t>& r)
    {
      for (std::size_t i = r.begin(); i != r.end(); ++i)
      {
        const double* ptrs[4];
        double w[4];
        int n = 0;
        for (int k = 0; k < 4; ++k)
        {
          const std::int32_t id = s.Parents[4 * i + k];
          if (id >= 0)
          {
            ptrs[n] = inputMetric.At(static_cast<std::size_t>(id));
            w[n++] = s.Weights[4 * i + k];
          }
        }
        PackSymmetric(LogEuclideanMean(ptrs, w, n), s.Metric.data() + 6 * i);
      }
    });
  s.UpdateSqrtMetric(first);
}
} // namespace

RefineStatus RefineLongEdges(AdaptiveMeshState& s,
  const MetricField& inputMetric,
  double target,
  std::size_t maxPoints,
  int maxPasses,
  std::size_t& numSplits,
  int& passes)
{
  int done = 0;
  std::vector<std::int32_t> active(s.NumCells());
  for (std::size_t c = 0; c < active.size(); ++c)
    active[c] = static_cast<std::int32_t>(c);
  std::vector<EdgeEntry> entries;
  std::vector<std::size_t> starts;
  std::vector<double> lengths;
  std::vector<std::uint32_t> longEdges;
  std::vector<char> locked, hasLong;
  std::vector<std::int32_t> next;
  while (!active.empty())
  {
    if (done == maxPasses)
      return RefineStatus::PassLimit;
    CollectEdges(s, active, entries, starts);
    const std::size_t numEdges = starts.size() - 1;
    lengths.resize(numEdges);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, numEdges, 2048),
      [&](const tbb::blocked_range<std::size_t>& r)
      {
        for (std::size_t g = r.begin(); g != r.end(); ++g)
        {
          const std::uint64_t key = entries[starts[g]].Key;
          lengths[g] = s.EdgeLength(
            static_cast<std::int32_t>(key >> 32), static_cast<std::int32_t>(key & 0xffffffffu));
        }
      });
    longEdges.clear();
    for (std::size_t g = 0; g < numEdges; ++g)
    {
      if (lengths[g] > target)
        longEdges.push_back(static_cast<std::uint32_t>(g));
    }
    if (longEdges.empty())
      break;
    // Longest first; equal lengths by key, so that the result does not depend on the threads.
    std::sort(longEdges.begin(),
      longEdges.end(),
      [&](std::uint32_t x, std::uint32_t y)
      { return lengths[x] > lengths[y] || (lengths[x] == lengths[y] && x < y); });
    locked.assign(s.NumCells(), 0);
    hasLong.assign(s.NumCells(), 0);
    for (const std::uint32_t g : longEdges)
      for (std::size_t i = starts[g]; i < starts[g + 1]; ++i)
        hasLong[entries[i].Cell] = 1;
    const std::size_t firstNew = s.NumPoints();
    next.clear();
    bool full = false;
    for (const std::uint32_t g : longEdges)
    {
      bool free = true;
      for (std::size_t i = starts[g]; i < starts[g + 1] && free; ++i)
        free = !locked[entries[i].Cell];
      if (!free)
        continue;
      if (s.NumPoints() >= maxPoints)
      {
        full = true;
        break;
      }
      for (std::size_t i = starts[g]; i < starts[g + 1]; ++i)
        locked[entries[i].Cell] = 1;
      SplitEdge(
        s, entries[starts[g]].Key, entries.data() + starts[g], starts[g + 1] - starts[g], next);
      ++numSplits;
    }
    InterpolateNewMetrics(s, inputMetric, firstNew);
    ++passes;
    ++done;
    if (full)
      return RefineStatus::PointLimit;
    // Cells without a long edge never get one again: splits only cut long edges.
    for (const std::int32_t c : active)
    {
      if (hasLong[c])
        next.push_back(c);
    }
    active.swap(next);
  }
  return RefineStatus::Done;
}

} // namespace av
