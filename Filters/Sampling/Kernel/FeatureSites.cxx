// SPDX-License-Identifier: BSD-3-Clause
#include "FeatureSites.h"

#include <cmath>
#include <string>

namespace av
{
namespace
{

/// One edge of a chain, walked from point From to point To.
struct ChainStep
{
  std::int32_t Edge, From, To;
  double Length;
};

double EmbeddedDistance(const Embedding& emb, std::int32_t a, std::int32_t b)
{
  const double* x = emb.At(static_cast<std::size_t>(a));
  const double* y = emb.At(static_cast<std::size_t>(b));
  double s = 0.0;
  for (int d = 0; d < emb.Dim; ++d)
    s += (x[d] - y[d]) * (x[d] - y[d]);
  return std::sqrt(s);
}

std::int32_t OtherEnd(const SharpFeatures& f, std::int32_t edge, std::int32_t point)
{
  const std::int32_t a = f.Edges[2 * static_cast<std::size_t>(edge)];
  return a == point ? f.Edges[2 * static_cast<std::size_t>(edge) + 1] : a;
}

/// Appends a site on `step` at fraction t from its From point.
void AddLineSite(const Embedding& emb, const SharpFeatures& f, const ChainStep& step, double t,
  FeatureSitePlacement& out)
{
  const auto e = static_cast<std::size_t>(step.Edge);
  const bool fromIsA = f.Edges[2 * e] == step.From;
  const double tb = fromIsA ? t : 1.0 - t; // weight of point B = Edges[2e + 1]
  SiteSet& s = out.Sites;
  s.CellIds.push_back(f.EdgeCells[e]);
  double bary[4] = { 0.0, 0.0, 0.0, 0.0 };
  bary[f.EdgeLocal[2 * e]] = 1.0 - tb;
  bary[f.EdgeLocal[2 * e + 1]] = tb;
  s.Bary.insert(s.Bary.end(), bary, bary + 4);
  const double* xa = emb.At(static_cast<std::size_t>(f.Edges[2 * e]));
  const double* xb = emb.At(static_cast<std::size_t>(f.Edges[2 * e + 1]));
  for (int d = 0; d < emb.Dim; ++d)
    s.Coords.push_back((1.0 - tb) * xa[d] + tb * xb[d]);
  out.Edge.push_back(step.Edge);
}

/// Sites at arc lengths `first`, first + step, ... (count of them) along the chain.
void PlaceOnChain(const Embedding& emb, const SharpFeatures& f, const std::vector<ChainStep>& chain,
  double first, double stride, std::size_t count, FeatureSitePlacement& out)
{
  std::size_t i = 0;
  double start = 0.0; // arc length at chain[i].From
  for (std::size_t j = 0; j < count; ++j)
  {
    const double s = first + static_cast<double>(j) * stride;
    while (i + 1 < chain.size() && s > start + chain[i].Length)
      start += chain[i++].Length;
    const double len = chain[i].Length;
    const double t = len > 0.0 ? std::min(1.0, std::max(0.0, (s - start) / len)) : 0.0;
    AddLineSite(emb, f, chain[i], t, out);
  }
}

} // namespace

std::int32_t NextFeatureEdge(const SharpFeatures& f, std::int32_t edge, std::int32_t point)
{
  const auto p = static_cast<std::size_t>(point);
  if (f.IsCorner[p])
    return -1;
  const std::int32_t b = f.PointEdgeOffsets[p], e = f.PointEdgeOffsets[p + 1];
  if (e - b != 2)
    return -1;
  const std::int32_t e0 = f.PointEdges[static_cast<std::size_t>(b)];
  const std::int32_t e1 = f.PointEdges[static_cast<std::size_t>(b) + 1];
  return e0 == edge ? e1 : e0;
}

FeatureSitePlacement PlaceFeatureSites(const SimplexMesh& mesh, const Embedding& embedding,
  const SharpFeatures& f, double spacing)
{
  if (!std::isfinite(spacing) || !(spacing > 0.0))
    throw InputError("feature sites: the spacing must be positive and finite");
  if (embedding.NumPoints() != mesh.NumPoints() || f.IsCorner.size() != mesh.NumPoints() ||
    f.PointEdgeOffsets.size() != mesh.NumPoints() + 1 || f.EdgeCells.size() != f.NumEdges() ||
    f.EdgeLocal.size() != 2 * f.NumEdges() || f.CornerCells.size() != f.Corners.size())
    throw InputError("feature sites: the features or the embedding do not match the mesh");

  FeatureSitePlacement out;
  out.Sites.Dim = embedding.Dim;
  for (std::size_t c = 0; c < f.Corners.size(); ++c)
  {
    out.Sites.CellIds.push_back(f.CornerCells[c]);
    double bary[4] = { 0.0, 0.0, 0.0, 0.0 };
    bary[f.CornerLocal[c]] = 1.0;
    out.Sites.Bary.insert(out.Sites.Bary.end(), bary, bary + 4);
    const double* x = embedding.At(static_cast<std::size_t>(f.Corners[c]));
    out.Sites.Coords.insert(out.Sites.Coords.end(), x, x + embedding.Dim);
    out.Edge.push_back(-1);
  }
  out.NumCorners = f.Corners.size();
  for (std::size_t e = 0; e < f.NumEdges(); ++e)
    out.FeatureLength += EmbeddedDistance(embedding, f.Edges[2 * e], f.Edges[2 * e + 1]);

  std::vector<char> visited(f.NumEdges(), 0);
  std::vector<ChainStep> chain;
  auto walk = [&](std::int32_t edge, std::int32_t from, bool loop)
  {
    chain.clear();
    const std::int32_t origin = from;
    while (edge >= 0 && !visited[static_cast<std::size_t>(edge)])
    {
      visited[static_cast<std::size_t>(edge)] = 1;
      const std::int32_t to = OtherEnd(f, edge, from);
      chain.push_back({ edge, from, to, EmbeddedDistance(embedding, from, to) });
      if (loop && to == origin)
        break;
      edge = NextFeatureEdge(f, edge, to);
      from = to;
    }
    double length = 0.0;
    for (const ChainStep& s : chain)
      length += s.Length;
    ++out.NumChains;
    if (loop)
    {
      const auto m = static_cast<std::size_t>(std::max(1L, std::lround(length / spacing)));
      PlaceOnChain(embedding, f, chain, 0.0, length / static_cast<double>(m), m, out);
    }
    else
    {
      const long m = std::max(0L, std::lround(length / spacing) - 1);
      const double stride = length / static_cast<double>(m + 1);
      PlaceOnChain(embedding, f, chain, stride, stride, static_cast<std::size_t>(m), out);
    }
  };
  // Open chains start at corners (every chain end is a corner: see DetectSharpFeatures).
  for (std::int32_t c : f.Corners)
    for (std::int32_t k = f.PointEdgeOffsets[static_cast<std::size_t>(c)];
         k < f.PointEdgeOffsets[static_cast<std::size_t>(c) + 1]; ++k)
    {
      const std::int32_t e = f.PointEdges[static_cast<std::size_t>(k)];
      if (!visited[static_cast<std::size_t>(e)])
        walk(e, c, false);
    }
  // What is left are closed loops without corners.
  for (std::size_t e = 0; e < f.NumEdges(); ++e)
    if (!visited[e])
      walk(static_cast<std::int32_t>(e), f.Edges[2 * e], true);
  return out;
}

} // namespace av
