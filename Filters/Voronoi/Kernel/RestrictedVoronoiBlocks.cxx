// SPDX-License-Identifier: BSD-3-Clause
// The dimension dispatch of the RVD: every (SimplexDim, Dim) pair the pipeline uses gets its own
// compiled ElementWorker (Geogram's RVD.cpp does the same), run over blocks of elements.
#include "RestrictedVoronoiBlocks.h"

#include "RestrictedVoronoiContext.h"
#include "RestrictedVoronoiSiteTree.h"
#include "RestrictedVoronoiVertexSites.h"
#include "RestrictedVoronoiWorker.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace av
{
namespace rvd
{
namespace
{

template <int K, int DIM>
void RunBlocks(const SimplexMesh& mesh, const Embedding& emb, const SiteSet& sites,
  const RestrictedVoronoiOptions& opt, const std::vector<std::int32_t>& adj,
  std::vector<Chunk>& chunks, std::size_t blockSize, std::size_t first, std::size_t last,
  const std::int32_t* list)
{
  const std::size_t ns = sites.NumSites();
  SiteCloud<DIM> cloud{ sites.Coords.data(), ns, sites.Dim };
  SiteTree<DIM> tree(sites.Dim, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  int nbrk = opt.NumNeighbors > 0 ? opt.NumNeighbors : (K == 2 ? 32 : 64);
  nbrk = static_cast<int>(std::min<std::size_t>(nbrk, ns - 1));
  const SiteNeighbors nbr = PrefetchNeighbors<DIM>(tree, sites, nbrk);
  const std::vector<std::int32_t> vertexSites = opt.WholeElementFastPath
    ? ClearNearestSites<DIM>(tree, nbr, mesh, emb, sites, first, last, list)
    : std::vector<std::int32_t>();
  const std::int32_t* vs = opt.WholeElementFastPath ? vertexSites.data() : nullptr;

  tbb::enumerable_thread_specific<Context<K>> contexts;
  tbb::enumerable_thread_specific<Chunk> scratch;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks.size()),
    [&](const tbb::blocked_range<std::size_t>& r) {
      Context<K>& C = contexts.local();
      C.Init(sites.NumSites());
      Chunk& out = scratch.local();
      ElementWorker<K, DIM> w(mesh, emb, sites, opt, tree, adj, nbr, vs);
      for (std::size_t b = r.begin(); b != r.end(); ++b)
      {
        const std::size_t e0 = first + b * blockSize, e1 = std::min(last, e0 + blockSize);
        out.Clear();
        for (std::size_t e = e0; e < e1; ++e)
          w.ProcessElement(C, list ? list[e] : static_cast<std::int32_t>(e), out);
        chunks[b] = out; // a copy at the exact sizes: the chunks are held until the assembly
      }
    });
}

template <int K>
void RunDim(int dim, const SimplexMesh& mesh, const Embedding& emb, const SiteSet& sites,
  const RestrictedVoronoiOptions& opt, const std::vector<std::int32_t>& adj,
  std::vector<Chunk>& chunks, std::size_t bs, std::size_t e0, std::size_t e1,
  const std::int32_t* list)
{
  switch (dim)
  {
    case 2: RunBlocks<K, 2>(mesh, emb, sites, opt, adj, chunks, bs, e0, e1, list); break;
    case 3: RunBlocks<K, 3>(mesh, emb, sites, opt, adj, chunks, bs, e0, e1, list); break;
    case 4: RunBlocks<K, 4>(mesh, emb, sites, opt, adj, chunks, bs, e0, e1, list); break;
    case 5: RunBlocks<K, 5>(mesh, emb, sites, opt, adj, chunks, bs, e0, e1, list); break;
    case 6: RunBlocks<K, 6>(mesh, emb, sites, opt, adj, chunks, bs, e0, e1, list); break;
    case 8: RunBlocks<K, 8>(mesh, emb, sites, opt, adj, chunks, bs, e0, e1, list); break;
    default: RunBlocks<K, -1>(mesh, emb, sites, opt, adj, chunks, bs, e0, e1, list);
  }
}

} // namespace

void ClipElementBlocks(const SimplexMesh& mesh, const Embedding& embedding, const SiteSet& sites,
  const RestrictedVoronoiOptions& options, const std::vector<std::int32_t>& adjacency,
  std::vector<Chunk>& chunks, std::size_t blockSize, std::size_t first, std::size_t last,
  const std::int32_t* list)
{
  if (mesh.SimplexDim == 2)
    RunDim<2>(embedding.Dim, mesh, embedding, sites, options, adjacency, chunks, blockSize, first,
      last, list);
  else
    RunDim<3>(embedding.Dim, mesh, embedding, sites, options, adjacency, chunks, blockSize, first,
      last, list);
}

} // namespace rvd
} // namespace av
