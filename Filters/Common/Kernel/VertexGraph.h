// SPDX-License-Identifier: BSD-3-Clause
// VertexGraph: the vertex neighbors of a mesh as a CSR graph, and the Laplacian smoothing step
// that the metric stages run on it (tensor metrics, surface curvature metrics).
#ifndef av_VertexGraph_h
#define av_VertexGraph_h

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{

/// Neighbors of vertex i: Neighbors[Offsets[i] .. Offsets[i+1]).
struct VertexGraph
{
  std::vector<std::int32_t> Offsets;
  std::vector<std::int32_t> Neighbors;
};

/// The graph of `n` vertices joined by the edges (a0, b0, a1, b1, ...), e.g. UniqueEdges(mesh).
inline VertexGraph BuildVertexGraph(std::size_t n, const std::vector<std::int32_t>& edgePairs)
{
  VertexGraph g;
  g.Offsets.assign(n + 1, 0);
  for (std::int32_t e : edgePairs)
  {
    ++g.Offsets[static_cast<std::size_t>(e) + 1];
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    g.Offsets[i + 1] += g.Offsets[i];
  }
  g.Neighbors.resize(edgePairs.size());
  std::vector<std::int32_t> fill(g.Offsets.begin(), g.Offsets.end() - 1);
  for (std::size_t e = 0; e + 1 < edgePairs.size(); e += 2)
  {
    g.Neighbors[static_cast<std::size_t>(fill[edgePairs[e]]++)] = edgePairs[e + 1];
    g.Neighbors[static_cast<std::size_t>(fill[edgePairs[e + 1]]++)] = edgePairs[e];
  }
  return g;
}

/// One Jacobi step x_i <- (x_i + mean of the neighbors' x) / 2 for any value type with + and
/// scalar *, in parallel; isolated vertices keep their value.
template <class T>
void HalfLaplacianStep(const VertexGraph& g, const std::vector<T>& in, std::vector<T>& out)
{
  const std::size_t n = in.size();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024),
    [&](const tbb::blocked_range<std::size_t>& range) {
      for (std::size_t i = range.begin(); i != range.end(); ++i)
      {
        const std::int32_t b = g.Offsets[i], e = g.Offsets[i + 1];
        if (b == e)
        {
          out[i] = in[i];
          continue;
        }
        T sum = in[static_cast<std::size_t>(g.Neighbors[static_cast<std::size_t>(b)])];
        for (std::int32_t k = b + 1; k < e; ++k)
        {
          sum += in[static_cast<std::size_t>(g.Neighbors[static_cast<std::size_t>(k)])];
        }
        out[i] = 0.5 * in[i] + (0.5 / (e - b)) * sum;
      }
    });
}

} // namespace av

#endif
