// SPDX-License-Identifier: BSD-3-Clause
// Collapse of the edges that are short in the metric (the coarsening half of MetricAdaptedMesh):
// one end moves onto the other when no element inverts, flattens or loses quality, the boundary
// and the feature lines keep their shape, and the mesh stays a manifold.
#include "AdaptiveMeshState.h"

#include "MeshTopology.h"
#include "MetricAlgebra.h"
#include "SharpFeatures.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_set>

namespace av
{
namespace
{
/// Vertices with a larger star are left alone (keeps the per-collapse buffers on the stack).
constexpr int kMaxStar = 96;

/// Shape quality in the element's mean metric, 1 for a regular simplex, 0 when flat.
double MetricQuality(const AdaptiveMeshState& s, const std::int32_t* v)
{
  const int k = s.SimplexDim;
  // Sum the packed tensors, unpack once (the same sums entry by entry).
  double packed[6] = { 0, 0, 0, 0, 0, 0 };
  for (int i = 0; i <= k; ++i)
  {
    const double* mi = s.Metric.data() + 6 * static_cast<std::size_t>(v[i]);
    for (int q = 0; q < 6; ++q)
      packed[q] += mi[q];
  }
  Eigen::Matrix3d m = UnpackSymmetric(packed);
  m /= (k + 1);
  Eigen::Matrix3d e = Eigen::Matrix3d::Zero();
  const Eigen::Vector3d p0 = s.Position(static_cast<std::size_t>(v[0]));
  for (int j = 0; j < k; ++j)
    e.col(j) = s.Position(static_cast<std::size_t>(v[j + 1])) - p0;
  const Eigen::Matrix3d g = e.transpose() * m * e;
  double sumSq = 0.0;
  for (int i = 0; i < k; ++i)
  {
    sumSq += g(i, i);
    for (int j = i + 1; j < k; ++j)
      sumSq += g(i, i) + g(j, j) - 2.0 * g(i, j);
  }
  if (!(sumSq > 0.0))
    return 0.0;
  if (k == 3)
  {
    const double vol = std::sqrt(std::max(0.0, g.determinant())) / 6.0;
    return 12.0 * std::cbrt(9.0 * vol * vol) / sumSq;
  }
  const double det2 = g(0, 0) * g(1, 1) - g(0, 1) * g(0, 1);
  return 2.0 * std::sqrt(3.0) * std::sqrt(std::max(0.0, det2)) / sumSq;
}

/// Signed volume (tets) or signed area (2D triangles), or the normal (surface triangles).
Eigen::Vector3d Orientation(const AdaptiveMeshState& s, const std::int32_t* v)
{
  const Eigen::Vector3d p0 = s.Position(static_cast<std::size_t>(v[0]));
  const Eigen::Vector3d e1 = s.Position(static_cast<std::size_t>(v[1])) - p0;
  const Eigen::Vector3d e2 = s.Position(static_cast<std::size_t>(v[2])) - p0;
  if (s.SimplexDim == 3)
  {
    const Eigen::Vector3d e3 = s.Position(static_cast<std::size_t>(v[3])) - p0;
    return Eigen::Vector3d(e1.cross(e2).dot(e3) / 6.0, 0.0, 0.0);
  }
  return 0.5 * e1.cross(e2); // 2D: z holds the signed area
}

bool WithinAngle(const Eigen::Vector3d& x, const Eigen::Vector3d& y, double cosTol)
{
  const double n = x.norm() * y.norm();
  return n > 0.0 && x.dot(y) >= cosTol * n;
}

/// Everything the collapses of one pass share.
struct CollapseContext
{
  AdaptiveMeshState& S;
  const AdaptedMeshOptions& Options;
  double Target;
  double CosTol;
  std::vector<std::uint8_t> Class; ///< 0 corner, 1 line, 2 boundary (tets) / top, 3 top
  std::unordered_set<std::uint64_t> Lines;
  std::vector<char> Alive;
  std::vector<std::int32_t> StarOffsets, Stars; ///< point -> cells, rebuilt every pass
  /// Cells a point gained during the pass (a collapse onto it): with them the stars stay exact,
  /// so any edge can collapse after its neighbours did, in the same pass.
  std::vector<std::vector<std::int32_t>> Gained;
};

bool CellHas(const AdaptiveMeshState& s, std::int32_t c, std::int32_t p)
{
  const std::int32_t* v = s.Cells.data() + static_cast<std::size_t>(c) * s.Nv();
  for (int k = 0; k < s.Nv(); ++k)
    if (v[k] == p)
      return true;
  return false;
}

/// The alive cells around `p` into `out`; false when there are more than kMaxStar. A cell listed
/// for p may have lost it in this pass (p collapsed onto a neighbour): only cells holding p count.
bool GatherStar(const CollapseContext& ctx, std::int32_t p, std::int32_t* out, int& n)
{
  n = 0;
  const auto take = [&](std::int32_t c) {
    if (!ctx.Alive[c] || !CellHas(ctx.S, c, p))
      return true;
    if (n == kMaxStar)
      return false;
    out[n++] = c;
    return true;
  };
  for (std::int32_t i = ctx.StarOffsets[p]; i < ctx.StarOffsets[p + 1]; ++i)
    if (!take(ctx.Stars[i]))
      return false;
  for (const std::int32_t c : ctx.Gained[p])
    if (!take(c))
      return false;
  return true;
}

/// Unique sorted vertices of the cells, without `self`.
int StarVertices(const AdaptiveMeshState& s,
  const std::int32_t* cells,
  int n,
  std::int32_t self,
  std::int32_t* out)
{
  int m = 0;
  for (int i = 0; i < n; ++i)
  {
    const std::int32_t* v = s.Cells.data() + static_cast<std::size_t>(cells[i]) * s.Nv();
    for (int k = 0; k < s.Nv(); ++k)
      if (v[k] != self)
        out[m++] = v[k];
  }
  std::sort(out, out + m);
  return static_cast<int>(std::unique(out, out + m) - out);
}

/// The facets through `p` of the cells (as keys of the other vertices), sorted, with repeats.
int FacetsThrough(const AdaptiveMeshState& s,
  const std::int32_t* cells,
  int n,
  std::int32_t p,
  std::int32_t from,
  std::uint64_t* out)
{
  int m = 0;
  const int nv = s.Nv();
  for (int i = 0; i < n; ++i)
  {
    const std::int32_t* v = s.Cells.data() + static_cast<std::size_t>(cells[i]) * nv;
    std::int32_t others[3];
    int no = 0;
    for (int k = 0; k < nv; ++k)
      if (v[k] != p && v[k] != from)
        others[no++] = v[k];
    // Each facet through p leaves out one of the other vertices.
    for (int drop = 0; drop < no; ++drop)
    {
      if (s.SimplexDim == 3)
      {
        const std::int32_t x = others[drop == 0 ? 1 : 0], y = others[drop == 2 ? 1 : 2];
        out[m++] = EdgeKey(x, y);
      }
      else
      {
        out[m++] = static_cast<std::uint64_t>(others[1 - drop]);
      }
    }
  }
  std::sort(out, out + m);
  return m;
}

/// Checks and, when safe, performs the collapse of a onto b. See AdaptBackgroundMesh.
bool TryCollapse(CollapseContext& ctx, std::int32_t a, std::int32_t b)
{
  AdaptiveMeshState& s = ctx.S;
  const int k = s.SimplexDim, nv = s.Nv();
  const int ca = ctx.Class[a];
  if (ca == 0 || ctx.Class[b] > ca)
    return false;
  std::int32_t starA[kMaxStar], starB[kMaxStar];
  int na = 0, nb = 0;
  if (!GatherStar(ctx, a, starA, na) || !GatherStar(ctx, b, starB, nb) || na == 0 || nb == 0)
    return false; // a or b was removed by an earlier collapse of the pass
  std::int32_t vertsA[kMaxStar * 4], vertsB[kMaxStar * 4];
  const int nva = StarVertices(s, starA, na, a, vertsA);
  const int nvb = StarVertices(s, starB, nb, b, vertsB);

  // Link condition: a vertex next to both a and b must lie in an element through a-b.
  std::int32_t changed[kMaxStar];
  int nChanged = 0;
  std::int32_t ring[kMaxStar * 4];
  int nRing = 0;
  for (int i = 0; i < na; ++i)
  {
    if (CellHas(s, starA[i], b))
    {
      const std::int32_t* v = s.Cells.data() + static_cast<std::size_t>(starA[i]) * nv;
      for (int q = 0; q < nv; ++q)
        if (v[q] != a && v[q] != b)
          ring[nRing++] = v[q];
    }
    else
      changed[nChanged++] = starA[i];
  }
  if (nChanged == na)
    return false; // a-b is not an edge any more
  std::sort(ring, ring + nRing);
  for (int i = 0; i < nva; ++i)
  {
    if (vertsA[i] != b && std::binary_search(vertsB, vertsB + nvb, vertsA[i]) &&
      !std::binary_search(ring, ring + nRing, vertsA[i]))
      return false;
  }

  // Boundary and lines: a moves only within its own stratum.
  std::uint64_t facets[kMaxStar * 3];
  const int nf = FacetsThrough(s, starA, na, a, -1, facets);
  if (ca == 1 || (k == 3 && ca == 2))
  {
    bool onStratum = false;
    if (ca == 1)
    {
      int lineEdges = 0;
      std::int32_t other = -1;
      for (int i = 0; i < nva; ++i)
      {
        if (ctx.Lines.count(EdgeKey(a, vertsA[i])))
        {
          ++lineEdges;
          onStratum = onStratum || vertsA[i] == b;
          other = vertsA[i] == b ? other : vertsA[i];
        }
      }
      if (lineEdges != 2 || !onStratum ||
        !WithinAngle(s.Position(a) - s.Position(other), s.Position(b) - s.Position(a), ctx.CosTol))
        return false;
    }
    else
    {
      for (int i = 0; i < nf && !onStratum; ++i)
      {
        const bool single =
          (i == 0 || facets[i] != facets[i - 1]) && (i + 1 == nf || facets[i + 1] != facets[i]);
        const std::int32_t x = static_cast<std::int32_t>(facets[i] >> 32);
        const std::int32_t y = static_cast<std::int32_t>(facets[i] & 0xffffffffu);
        onStratum = single && (x == b || y == b);
      }
      if (!onStratum)
        return false;
    }
  }
  // Boundary faces through a (tets) keep their plane within the tolerance.
  if (k == 3 && ca <= 2)
  {
    for (int i = 0; i < nf; ++i)
    {
      const bool single =
        (i == 0 || facets[i] != facets[i - 1]) && (i + 1 == nf || facets[i + 1] != facets[i]);
      const std::int32_t x = static_cast<std::int32_t>(facets[i] >> 32);
      const std::int32_t y = static_cast<std::int32_t>(facets[i] & 0xffffffffu);
      if (!single || x == b || y == b)
        continue;
      const Eigen::Vector3d px = s.Position(x), py = s.Position(y);
      const Eigen::Vector3d before = (px - s.Position(a)).cross(py - s.Position(a));
      const Eigen::Vector3d after = (px - s.Position(b)).cross(py - s.Position(b));
      if (!WithinAngle(before, after, ctx.CosTol))
        return false;
    }
  }

  // No new edge longer than the target.
  for (int i = 0; i < nva; ++i)
  {
    const std::int32_t c = vertsA[i];
    if (c != b && !std::binary_search(vertsB, vertsB + nvb, c) && s.EdgeLength(b, c) > ctx.Target)
      return false;
  }

  // Orientation, surface folding and quality of the changed elements.
  double oldQ = 1.0, newQ = 1.0;
  for (int i = 0; i < na; ++i)
    oldQ =
      std::min(oldQ, MetricQuality(s, s.Cells.data() + static_cast<std::size_t>(starA[i]) * nv));
  const bool surface = k == 2 && s.AmbientDim == 3;
  for (int i = 0; i < nChanged; ++i)
  {
    std::int32_t v[4];
    const std::int32_t* old = s.Cells.data() + static_cast<std::size_t>(changed[i]) * nv;
    for (int q = 0; q < nv; ++q)
      v[q] = old[q] == a ? b : old[q];
    const Eigen::Vector3d before = Orientation(s, old), after = Orientation(s, v);
    if (surface ? !WithinAngle(before, after, ctx.CosTol)
                : (k == 3 ? !(after[0] > 0.0) : !(after[2] * before[2] > 0.0)))
      return false;
    newQ = std::min(newQ, MetricQuality(s, v));
  }
  if (newQ < std::min(ctx.Options.MinQuality, oldQ))
    return false;

  // Manifold: after the collapse no facet through b is shared by more than two elements.
  std::int32_t after[kMaxStar * 2];
  int nAfter = 0;
  for (int i = 0; i < nb; ++i)
    if (!CellHas(s, starB[i], a))
      after[nAfter++] = starB[i];
  std::uint64_t facetsB[kMaxStar * 6];
  int nfb = FacetsThrough(s, after, nAfter, b, -1, facetsB);
  const int nfa = FacetsThrough(s, changed, nChanged, a, b, facetsB + nfb);
  nfb += nfa;
  std::sort(facetsB, facetsB + nfb);
  for (int i = 2; i < nfb; ++i)
    if (facetsB[i] == facetsB[i - 2])
      return false;

  // Commit: the changed elements take b, the elements through a-b die.
  for (int i = 0; i < nChanged; ++i)
  {
    std::int32_t* v = s.Cells.data() + static_cast<std::size_t>(changed[i]) * nv;
    for (int q = 0; q < nv; ++q)
      v[q] = v[q] == a ? b : v[q];
  }
  for (int i = 0; i < na; ++i)
    if (CellHas(s, starA[i], b) && CellHas(s, starA[i], a))
      ctx.Alive[starA[i]] = 0;
  // b's gained cells: drop those GatherStar would skip (a vertex that absorbs many collapses
  // would otherwise drag its dead cells along), then add a's.
  std::vector<std::int32_t>& gained = ctx.Gained[b];
  gained.erase(std::remove_if(gained.begin(), gained.end(),
                 [&](std::int32_t c) { return !ctx.Alive[c] || !CellHas(s, c, b); }),
    gained.end());
  gained.insert(gained.end(), changed, changed + nChanged);
  if (ca == 1)
  {
    for (int i = 0; i < nva; ++i)
    {
      if (vertsA[i] != b && ctx.Lines.erase(EdgeKey(a, vertsA[i])))
        ctx.Lines.insert(EdgeKey(b, vertsA[i]));
    }
    ctx.Lines.erase(EdgeKey(a, b));
  }
  return true;
}

/// The working mesh as a SimplexMesh (for the boundary and feature detection).
SimplexMesh AsSimplexMesh(const AdaptiveMeshState& s)
{
  SimplexMesh m;
  m.AmbientDim = s.AmbientDim;
  m.SimplexDim = s.SimplexDim;
  m.Points = s.Points;
  m.Cells = s.Cells;
  return m;
}

/// Strata of the vertices and the line edges: tets: feature edges; triangles: boundary edges and
/// (surfaces) creases.
void ClassifyVertices(CollapseContext& ctx)
{
  const AdaptiveMeshState& s = ctx.S;
  const SimplexMesh m = AsSimplexMesh(s);
  const std::vector<char> boundary = BoundaryVertexMask(m);
  const std::size_t np = s.NumPoints();
  const int k = s.SimplexDim;
  ctx.Class.assign(np, static_cast<std::uint8_t>(k));
  for (std::size_t i = 0; i < np; ++i)
    if (boundary[i] && k == 3)
      ctx.Class[i] = 2;
  const SharpFeatures f = DetectSharpFeatures(m, ctx.Options.FeatureAngle);
  for (std::size_t e = 0; e < f.NumEdges(); ++e)
    ctx.Lines.insert(EdgeKey(f.Edges[2 * e], f.Edges[2 * e + 1]));
  if (k == 2)
  {
    // Boundary edges of a triangle mesh: edges of one triangle.
    std::vector<std::uint64_t> keys;
    keys.reserve(3 * s.NumCells());
    for (std::size_t c = 0; c < s.NumCells(); ++c)
      for (int e = 0; e < 3; ++e)
        keys.push_back(
          EdgeKey(s.Cells[3 * c + kSimplexEdges[e][0]], s.Cells[3 * c + kSimplexEdges[e][1]]));
    tbb::parallel_sort(keys.begin(), keys.end());
    for (std::size_t i = 0; i < keys.size(); ++i)
    {
      const bool single =
        (i == 0 || keys[i] != keys[i - 1]) && (i + 1 == keys.size() || keys[i + 1] != keys[i]);
      if (single)
        ctx.Lines.insert(keys[i]);
    }
  }
  for (const std::uint64_t key : ctx.Lines)
  {
    ctx.Class[key >> 32] = 1;
    ctx.Class[key & 0xffffffffu] = 1;
  }
  for (const std::int32_t c : f.Corners)
    ctx.Class[c] = 0;
}

void BuildStars(CollapseContext& ctx)
{
  const AdaptiveMeshState& s = ctx.S;
  const int nv = s.Nv();
  ctx.StarOffsets.assign(s.NumPoints() + 1, 0);
  for (std::size_t c = 0; c < s.NumCells(); ++c)
    if (ctx.Alive[c])
      for (int q = 0; q < nv; ++q)
        ++ctx.StarOffsets[s.Cells[c * nv + q] + 1];
  for (std::size_t i = 0; i < s.NumPoints(); ++i)
    ctx.StarOffsets[i + 1] += ctx.StarOffsets[i];
  ctx.Stars.resize(ctx.StarOffsets.back());
  std::vector<std::int32_t> fill(ctx.StarOffsets.begin(), ctx.StarOffsets.end() - 1);
  for (std::size_t c = 0; c < s.NumCells(); ++c)
    if (ctx.Alive[c])
      for (int q = 0; q < nv; ++q)
        ctx.Stars[fill[s.Cells[c * nv + q]]++] = static_cast<std::int32_t>(c);
}

/// Short edges of the alive cells, shortest first. Lengths are evaluated per cell edge in
/// parallel so that only the short ones are sorted.
std::vector<std::pair<double, std::uint64_t>> ShortEdges(const CollapseContext& ctx,
  double shortLength)
{
  const AdaptiveMeshState& s = ctx.S;
  const int nv = s.Nv(), ne = s.SimplexDim == 3 ? 6 : 3;
  using Short = std::pair<double, std::uint64_t>;
  tbb::enumerable_thread_specific<std::vector<Short>> local;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, s.NumCells(), 2048),
    [&](const tbb::blocked_range<std::size_t>& r)
    {
      std::vector<Short>& out = local.local();
      for (std::size_t c = r.begin(); c != r.end(); ++c)
      {
        if (!ctx.Alive[c])
          continue;
        for (int e = 0; e < ne; ++e)
        {
          const std::int32_t a = s.Cells[c * nv + kSimplexEdges[e][0]];
          const std::int32_t b = s.Cells[c * nv + kSimplexEdges[e][1]];
          const double l = s.EdgeLength(a, b);
          if (l < shortLength)
            out.emplace_back(l, EdgeKey(a, b));
        }
      }
    });
  std::vector<Short> out;
  for (const auto& v : local)
    out.insert(out.end(), v.begin(), v.end());
  tbb::parallel_sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

/// Drops the dead cells and the points no cell uses (ids renumbered in order).
void Compact(AdaptiveMeshState& s, const std::vector<char>& alive)
{
  const int nv = s.Nv();
  std::size_t nc = 0;
  for (std::size_t c = 0; c < s.NumCells(); ++c)
  {
    if (!alive[c])
      continue;
    std::copy_n(s.Cells.begin() + c * nv, nv, s.Cells.begin() + nc * nv);
    s.CellParent[nc++] = s.CellParent[c];
  }
  s.Cells.resize(nc * nv);
  s.CellParent.resize(nc);
  std::vector<std::int32_t> newId(s.NumPoints(), -1);
  for (const std::int32_t p : s.Cells)
    newId[p] = 0;
  std::size_t np = 0;
  const int d = s.AmbientDim;
  for (std::size_t i = 0; i < newId.size(); ++i)
  {
    if (newId[i] < 0)
      continue;
    newId[i] = static_cast<std::int32_t>(np);
    std::copy_n(s.Points.begin() + i * d, d, s.Points.begin() + np * d);
    std::copy_n(s.Metric.begin() + 6 * i, 6, s.Metric.begin() + 6 * np);
    std::copy_n(s.SqrtMetric.begin() + 6 * i, 6, s.SqrtMetric.begin() + 6 * np);
    std::copy_n(s.Parents.begin() + 4 * i, 4, s.Parents.begin() + 4 * np);
    std::copy_n(s.Weights.begin() + 4 * i, 4, s.Weights.begin() + 4 * np);
    ++np;
  }
  s.Points.resize(np * d);
  s.Metric.resize(6 * np);
  s.SqrtMetric.resize(6 * np);
  s.Parents.resize(4 * np);
  s.Weights.resize(4 * np);
  for (std::int32_t& p : s.Cells)
    p = newId[p];
}
} // namespace

void CompactMesh(AdaptiveMeshState& s)
{
  Compact(s, std::vector<char>(s.NumCells(), 1));
}

std::size_t CollapseShortEdges(AdaptiveMeshState& s,
  double shortLength,
  double target,
  const AdaptedMeshOptions& options,
  int maxPasses,
  int& passes)
{
  CollapseContext ctx{ s,
    options,
    target,
    std::cos(options.SurfaceDeviationAngle * 3.14159265358979323846 / 180.0),
    {},
    {},
    {},
    {},
    {},
    {} };
  ClassifyVertices(ctx);
  ctx.Alive.assign(s.NumCells(), 1);
  std::size_t total = 0;
  for (int pass = 0; pass < maxPasses; ++pass)
  {
    BuildStars(ctx);
    const auto edges = ShortEdges(ctx, shortLength);
    ctx.Gained.assign(s.NumPoints(), {});
    std::size_t done = 0;
    // An edge of the list keeps its length while both ends live (collapses move no point);
    // TryCollapse refuses it once a collapse removed it.
    for (const auto& e : edges)
    {
      const std::int32_t a = static_cast<std::int32_t>(e.second >> 32);
      const std::int32_t b = static_cast<std::int32_t>(e.second & 0xffffffffu);
      // Remove the end of the higher stratum (an interior point rather than a boundary one).
      const bool aFirst = ctx.Class[a] >= ctx.Class[b];
      if (TryCollapse(ctx, aFirst ? a : b, aFirst ? b : a) ||
        (ctx.Class[a] == ctx.Class[b] && TryCollapse(ctx, b, a)))
        ++done;
    }
    ++passes;
    total += done;
    if (done == 0 || done * 100 < s.NumPoints())
      break;
  }
  Compact(s, ctx.Alive);
  return total;
}

} // namespace av
