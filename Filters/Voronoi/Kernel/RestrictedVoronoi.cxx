// SPDX-License-Identifier: BSD-3-Clause
// ComputeRestrictedVoronoi: the whole-diagram driver (checks, clipping in element blocks,
// assembly). The parts: RestrictedVoronoiBlocks (dimension dispatch), ...Worker (one element),
// ...Candidates, ...Clipper, ...Emitter, ...Assembly; the update is in RestrictedVoronoiUpdate.
//
// Robustness: every vertex is (re)computed from its sorted symbolic labels (facets and the
// sites it is equidistant from) and classified against a new site m by comparing its distance
// to m with its distance to the smallest site of its label set. Every piece of an element
// therefore takes bit-identical decisions about a shared vertex; ties go to the lower site id.
#include "RestrictedVoronoi.h"

#include "RestrictedVoronoiAssembly.h"
#include "RestrictedVoronoiBlocks.h"
#include "RestrictedVoronoiChunk.h"
#include "RestrictedVoronoiValidation.h"
#include "MemoryBudget.h"

#include <string>
#include <vector>

namespace av
{

void RequireRestrictedVoronoiMemory(
  const SimplexMesh& mesh, const Embedding& embedding, std::size_t numSites)
{
  // A lower bound, so that only a problem that cannot fit is refused: every element and every
  // site's cell is at least one piece of K+1 vertices in both spaces, each piece held twice
  // (the per-block chunks, then the concatenated diagram), plus its records.
  const double pieces = static_cast<double>(mesh.NumCells() + numSites);
  const double perPiece = (mesh.SimplexDim + 1) * (mesh.AmbientDim + embedding.Dim) * 8.0 + 64.0;
  RequireMemory(2.0 * pieces * perPiece,
    "the restricted Voronoi diagram of " + std::to_string(numSites) + " sites on " +
      std::to_string(mesh.NumCells()) + " elements");
}

RestrictedVoronoiDiagram ComputeRestrictedVoronoi(const SimplexMesh& mesh,
  const Embedding& embedding, const SiteSet& sites, const RestrictedVoronoiOptions& options)
{
  ValidateRestrictedVoronoiInput(mesh, embedding, sites);
  const std::size_t nc = mesh.NumCells();
  RequireRestrictedVoronoiMemory(mesh, embedding, sites.NumSites());
  rvd::CheckDegenerateElements(mesh, embedding, nullptr, nc);
  std::vector<std::int32_t> ownAdjacency;
  const std::vector<std::int32_t>& adj = rvd::ElementAdjacencyFor(mesh, options, ownAdjacency);
  // Element range (a distributed run clips one block per process).
  std::size_t first = 0, last = 0;
  rvd::ElementRangeOf(options, nc, first, last);
  const std::size_t blockSize = 256;
  std::vector<rvd::Chunk> chunks((last - first + blockSize - 1) / blockSize);
  rvd::ClipElementBlocks(
    mesh, embedding, sites, options, adj, chunks, blockSize, first, last, nullptr);

  RestrictedVoronoiDiagram out = rvd::NewDiagram(mesh, embedding, sites.NumSites());
  out.NumRecomputedElements = last - first;
  for (const rvd::Chunk& ch : chunks)
    out.NumWholeElements += ch.NumWholeElements;
  if (first == 0 && last == nc && !options.MergeBySite)
    rvd::FillElementRecords(chunks, adj, nc, out); // for UpdateRestrictedVoronoi
  rvd::ConcatenateChunks(chunks, options, out);
  rvd::SumSiteMeasures(out);
  if (options.MergeBySite)
    return rvd::SortPiecesBySite(std::move(out), options);
  return out;
}

} // namespace av
