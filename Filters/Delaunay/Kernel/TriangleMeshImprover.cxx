// SPDX-License-Identifier: BSD-3-Clause
#include "TriangleMeshImprover.h"

#include "MetricSimplexQuality.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace av
{
namespace
{
constexpr double Pi = 3.14159265358979323846;
// No operation may leave an element below this quality (sine of 0.00006 degrees): a flat
// element's sign is round-off.
constexpr double kMinQuality = kMinImprovementQuality;

int IndexIn(const std::array<std::int32_t, 3>& t, std::int32_t v)
{
  for (int i = 0; i < 3; ++i)
    if (t[i] == v)
      return i;
  return -1;
}

void Replace(std::vector<std::int32_t>& s, std::int32_t from, std::int32_t to)
{
  s.erase(std::find(s.begin(), s.end(), from));
  if (to >= 0)
    s.push_back(to);
}
} // namespace

TriangleMeshImprover::TriangleMeshImprover(SimplexMesh& mesh,
  std::vector<Eigen::Matrix2d> sqrtMetrics,
  const std::vector<std::uint8_t>* fixed,
  const MeshImprovementOptions& options)
  : Mesh(mesh)
  , S(std::move(sqrtMetrics))
  , Options(options)
{
  const std::size_t np = mesh.NumPoints();
  P.resize(np);
  for (std::size_t i = 0; i < np; ++i)
    P[i] = Eigen::Vector2d(mesh.Point(i)[0], mesh.Point(i)[1]);
  Star.resize(np);
  Fixed.assign(np, 0);
  if (fixed)
    for (std::size_t i = 0; i < np; ++i)
      Fixed[i] = (*fixed)[i] ? 1 : 0;
  Moved.assign(np, 0);
  Tris.resize(mesh.NumCells());
  for (std::size_t c = 0; c < mesh.NumCells(); ++c)
  {
    const std::int32_t* v = mesh.Cell(c);
    Tris[c] = { v[0], v[1], v[2] };
    for (int i = 0; i < 3; ++i)
      Star[v[i]].push_back(static_cast<std::int32_t>(c));
  }
  MarkBoundaryAndNonManifold();
}

double TriangleMeshImprover::Quality(const Tri& t) const
{
  return TriangleMetricQuality(P[t[0]], P[t[1]], P[t[2]], S[t[0]], S[t[1]], S[t[2]]);
}

double TriangleMeshImprover::WorstQuality() const
{
  double worst = std::numeric_limits<double>::infinity();
  for (const Tri& t : Tris)
    worst = std::min(worst, Quality(t));
  return worst;
}

double TriangleMeshImprover::StarWorst(std::int32_t v) const
{
  double worst = std::numeric_limits<double>::infinity();
  for (std::int32_t t : Star[v])
    worst = std::min(worst, Quality(Tris[t]));
  return worst;
}

bool TriangleMeshImprover::Accepts(double after, double before) const
{
  return AcceptsImprovement(after, before, Options.AcceptWorsening);
}

// Vertices on edges of one triangle (the boundary) or of more than two never move.
void TriangleMeshImprover::MarkBoundaryAndNonManifold()
{
  std::vector<std::pair<std::int32_t, std::int32_t>> edges;
  edges.reserve(Tris.size() * 3);
  for (const Tri& t : Tris)
    for (int e = 0; e < 3; ++e)
      edges.emplace_back(std::min(t[e], t[(e + 1) % 3]), std::max(t[e], t[(e + 1) % 3]));
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();)
  {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j] == edges[i])
      ++j;
    if (j - i != 2)
      Fixed[edges[i].first] = Fixed[edges[i].second] = 1;
    i = j;
  }
}

bool TriangleMeshImprover::HasEdge(std::int32_t a, std::int32_t b) const
{
  for (std::int32_t t : Star[a])
    if (IndexIn(Tris[t], b) >= 0)
      return true;
  return false;
}

// 2-2 flip of edge `edge` (t[edge], t[edge+1]) of triangle `tri`: (a, b, c) and (b, a, d)
// become (c, a, d) and (d, b, c).
bool TriangleMeshImprover::TryFlip(std::int32_t tri, int edge)
{
  const Tri t1 = Tris[tri];
  const std::int32_t a = t1[edge], b = t1[(edge + 1) % 3], c = t1[(edge + 2) % 3];
  std::int32_t other = -1;
  int count = 0;
  for (std::int32_t t : Star[a])
    if (t != tri && IndexIn(Tris[t], b) >= 0)
    {
      other = t;
      ++count;
    }
  if (count != 1)
    return false; // boundary or non-manifold edge
  const Tri& t2 = Tris[other];
  const std::int32_t d =
    t2[0] != a && t2[0] != b ? t2[0] : (t2[1] != a && t2[1] != b ? t2[1] : t2[2]);
  if (d == c || HasEdge(c, d))
    return false;
  const Tri n1 = { c, a, d }, n2 = { d, b, c };
  const double before = std::min(Quality(t1), Quality(t2));
  const double after = std::min(Quality(n1), Quality(n2));
  if (!Accepts(after, before))
    return false;
  Tris[tri] = n1;
  Tris[other] = n2;
  Replace(Star[a], other, -1);
  Replace(Star[b], tri, -1);
  Star[c].push_back(other);
  Star[d].push_back(tri);
  ++Flips;
  return true;
}

// Steepest ascent of the worst triangle of v's star, as TetMeshImprover::TrySmooth.
bool TriangleMeshImprover::TrySmooth(std::int32_t v)
{
  if (Fixed[v] || Star[v].empty())
    return false;
  const Eigen::Vector2d start = P[v];
  double scale = std::numeric_limits<double>::infinity();
  for (std::int32_t t : Star[v])
    for (std::int32_t w : Tris[t])
      if (w != v)
        scale = std::min(scale, (P[w] - start).norm());
  const double before = StarWorst(v);
  double current = before;
  for (int iter = 0; iter < 8; ++iter)
  {
    std::int32_t worstTri = Star[v][0];
    for (std::int32_t t : Star[v])
      if (Quality(Tris[t]) < Quality(Tris[worstTri]))
        worstTri = t;
    const double h = 1e-6 * scale;
    const Eigen::Vector2d here = P[v];
    Eigen::Vector2d g;
    for (int k = 0; k < 2; ++k)
    {
      P[v] = here;
      P[v][k] += h;
      const double qp = Quality(Tris[worstTri]);
      P[v][k] -= 2.0 * h;
      const double qm = Quality(Tris[worstTri]);
      g[k] = (qp - qm) / (2.0 * h);
    }
    P[v] = here;
    const double gn = g.norm();
    if (!(gn > 0.0) || !std::isfinite(gn))
      break;
    bool stepped = false;
    for (double alpha = 0.2 * scale; alpha > 1e-4 * scale; alpha *= 0.5)
    {
      P[v] = here + (alpha / gn) * g;
      const double q = StarWorst(v);
      if (q > current + 1e-12)
      {
        current = q;
        stepped = true;
        break;
      }
    }
    if (!stepped)
    {
      P[v] = here;
      break;
    }
  }
  if (!Accepts(current, before) || (Options.AcceptMove && !Options.AcceptMove(v, P[v].data())))
  {
    P[v] = start;
    return false;
  }
  Moved[v] = 1;
  ++Smoothed;
  return true;
}

bool TriangleMeshImprover::Improve(std::int32_t tri)
{
  if (Options.Flips)
    for (int e = 0; e < 3; ++e)
      if (TryFlip(tri, e))
        return true;
  bool any = false;
  if (Options.Smoothing)
  {
    const Tri t = Tris[tri];
    for (std::int32_t v : t)
      any = TrySmooth(v) || any;
  }
  return any;
}

void TriangleMeshImprover::Run(MeshImprovementResult& result)
{
  auto angle = [](double q) { return std::asin(std::max(-1.0, std::min(1.0, q))) * 180.0 / Pi; };
  result.WorstBefore = Tris.empty() ? 0.0 : angle(WorstQuality());
  const double target = std::sin(Options.TargetAngle * Pi / 180.0);
  std::vector<std::pair<double, std::int32_t>> bad;
  for (int pass = 0; pass < Options.MaxPasses; ++pass)
  {
    bad.clear();
    for (std::size_t t = 0; t < Tris.size(); ++t)
    {
      const double q = Quality(Tris[t]);
      if (q < target)
        bad.emplace_back(q, static_cast<std::int32_t>(t));
    }
    std::sort(bad.begin(), bad.end());
    std::size_t changes = 0;
    for (const auto& item : bad)
      if (Improve(item.second))
        ++changes;
    ++result.Passes;
    if (changes == 0)
      break;
  }
  result.WorstAfter = Tris.empty() ? 0.0 : angle(WorstQuality());
  for (std::size_t c = 0; c < Tris.size(); ++c)
    for (int i = 0; i < 3; ++i)
      Mesh.Cells[c * 3 + i] = Tris[c][i];
  const int dim = Mesh.AmbientDim;
  for (std::size_t i = 0; i < P.size(); ++i)
    if (Moved[i])
      for (int d = 0; d < 2; ++d)
        Mesh.Points[i * dim + d] = P[i][d];
  result.NumFlips22 = Flips;
  result.NumSmoothed = Smoothed;
  result.Moved = std::move(Moved);
}

} // namespace av
