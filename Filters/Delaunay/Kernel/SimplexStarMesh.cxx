// SPDX-License-Identifier: BSD-3-Clause
#include "SimplexStarMesh.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <utility>

namespace av
{

template <int K>
SimplexStarMesh<K>::SimplexStarMesh(const SimplexMesh& mesh,
  std::vector<Eigen::Matrix3d> sqrtMetrics,
  const std::vector<std::uint8_t>* fixed)
  : SqrtMetrics(std::move(sqrtMetrics))
{
  const std::size_t np = mesh.NumPoints();
  const bool z = mesh.AmbientDim == 3;
  Points.resize(np);
  for (std::size_t i = 0; i < np; ++i)
    Points[i] = Eigen::Vector3d(mesh.Point(i)[0], mesh.Point(i)[1], z ? mesh.Point(i)[2] : 0.0);
  if constexpr (K == 2)
    Normals.assign(np, Eigen::Vector3d::UnitZ());
  Stars.resize(np);
  Fixed.assign(np, 0);
  if (fixed)
    for (std::size_t i = 0; i < np; ++i)
      Fixed[i] = (*fixed)[i] ? 1 : 0;
  Moved.assign(np, 0);
  // Tet flips add cells: room for a quarter more before the first reallocation.
  Simplices.reserve(mesh.NumCells() + mesh.NumCells() / 4);
  for (std::size_t c = 0; c < mesh.NumCells(); ++c)
  {
    Simplex t;
    std::copy(mesh.Cell(c), mesh.Cell(c) + K + 1, t.begin());
    Add(t);
  }
}

template <int K>
double SimplexStarMesh<K>::WorstQuality() const
{
  double worst = std::numeric_limits<double>::infinity();
  for (const Simplex& t : Simplices)
    if (t[0] != kDead)
      worst = std::min(worst, Quality(t));
  return worst;
}

template <int K>
double SimplexStarMesh<K>::StarWorst(std::int32_t v) const
{
  double worst = std::numeric_limits<double>::infinity();
  for (std::int32_t t : Stars[v])
    worst = std::min(worst, Quality(Simplices[t]));
  return worst;
}

template <int K>
double SimplexStarMesh<K>::StarMeanRatio(std::int32_t v) const
{
  double sum = 0.0;
  for (std::int32_t t : Stars[v])
    sum += MeanRatio(Simplices[t]);
  return Stars[v].empty() ? 0.0 : sum / static_cast<double>(Stars[v].size());
}

template <int K>
void SimplexStarMesh<K>::StarMeanAndWorst(std::int32_t v, double& mean, double& worst) const
{
  double sum = 0.0;
  worst = std::numeric_limits<double>::infinity();
  for (std::int32_t t : Stars[v])
  {
    const auto m = Mapped(Simplices[t]);
    if constexpr (K == 3)
    {
      sum += TetMeanRatio(m);
      worst = std::min(worst, TetQuality(m));
    }
    else
    {
      sum += TriangleMeanRatio(m);
      worst = std::min(worst, TriangleQuality(m));
    }
  }
  mean = Stars[v].empty() ? 0.0 : sum / static_cast<double>(Stars[v].size());
}

template <int K>
std::vector<std::vector<std::int32_t>> SimplexStarMesh<K>::IndependentClasses(
  const std::vector<std::int32_t>& vertices) const
{
  std::vector<int> colour(Points.size(), -1);
  std::vector<std::vector<std::int32_t>> classes;
  std::vector<char> used;
  for (std::int32_t v : vertices)
  {
    used.assign(classes.size() + 1, 0);
    for (std::int32_t t : Stars[v])
      for (std::int32_t w : Simplices[t])
        if (colour[w] >= 0)
          used[static_cast<std::size_t>(colour[w])] = 1;
    const int c = static_cast<int>(std::find(used.begin(), used.end(), 0) - used.begin());
    if (c == static_cast<int>(classes.size()))
      classes.emplace_back();
    classes[static_cast<std::size_t>(c)].push_back(v);
    colour[v] = c;
  }
  return classes;
}

// Seeded with the first simplex, as the triangle copy was; the tet copy started from +inf,
// which differs only when the first quality is NaN (and found none when all were).
template <int K>
std::int32_t SimplexStarMesh<K>::WorstInStar(std::int32_t v) const
{
  std::int32_t worst = Stars[v][0];
  double worstQuality = Quality(Simplices[worst]);
  for (std::int32_t t : Stars[v])
  {
    const double q = Quality(Simplices[t]);
    if (q < worstQuality)
    {
      worstQuality = q;
      worst = t;
    }
  }
  return worst;
}

template <int K>
bool SimplexStarMesh<K>::HasEdge(std::int32_t a, std::int32_t b) const
{
  for (std::int32_t t : Stars[a])
    if (IndexIn(Simplices[t], b) >= 0)
      return true;
  return false;
}

template <int K>
int SimplexStarMesh<K>::IndexIn(const Simplex& t, std::int32_t v)
{
  for (int i = 0; i <= K; ++i)
    if (t[i] == v)
      return i;
  return -1;
}

template <int K>
std::int32_t SimplexStarMesh<K>::Add(const Simplex& t)
{
  const auto id = static_cast<std::int32_t>(Simplices.size());
  Simplices.push_back(t);
  for (std::int32_t v : t)
    Stars[v].push_back(id);
  return id;
}

template <int K>
void SimplexStarMesh<K>::Kill(std::int32_t id)
{
  for (std::int32_t v : Simplices[id])
  {
    std::vector<std::int32_t>& s = Stars[v];
    s.erase(std::find(s.begin(), s.end(), id));
  }
  Simplices[id].fill(kDead);
}

template <int K>
void SimplexStarMesh<K>::Revive(std::int32_t id, const Simplex& t)
{
  Simplices[id] = t;
  for (std::int32_t v : t)
    Stars[v].push_back(id);
}

template <int K>
void SimplexStarMesh<K>::TruncateDead(std::size_t count)
{
  for (std::size_t i = count; i < Simplices.size(); ++i)
    if (Simplices[i][0] != kDead)
      throw std::logic_error("SimplexStarMesh::TruncateDead: an alive simplex");
  Simplices.resize(std::min(count, Simplices.size()));
}

template <int K>
std::int32_t SimplexStarMesh<K>::AddPoint(const Eigen::Vector3d& x, const Eigen::Matrix3d& s)
{
  const auto id = static_cast<std::int32_t>(Points.size());
  Points.push_back(x);
  SqrtMetrics.push_back(s);
  if constexpr (K == 2)
    Normals.push_back(Eigen::Vector3d::UnitZ());
  Stars.emplace_back();
  Fixed.push_back(0);
  Moved.push_back(0);
  return id;
}

template <int K>
void SimplexStarMesh<K>::RemoveLastPoint()
{
  if (Points.empty() || !Stars.back().empty())
    throw std::logic_error("SimplexStarMesh::RemoveLastPoint: the point is in use");
  Points.pop_back();
  SqrtMetrics.pop_back();
  if constexpr (K == 2)
    Normals.pop_back();
  Stars.pop_back();
  Fixed.pop_back();
  Moved.pop_back();
}

template <int K>
int SimplexStarMesh<K>::ImproveWorstFirst(double target,
  int maxPasses,
  const std::function<bool(std::int32_t)>& improve)
{
  std::vector<std::pair<double, std::int32_t>> bad;
  int passes = 0;
  while (passes < maxPasses)
  {
    bad.clear();
    for (std::size_t t = 0; t < Simplices.size(); ++t)
      if (Simplices[t][0] != kDead)
      {
        const double q = Quality(Simplices[t]);
        if (q < target)
          bad.emplace_back(q, static_cast<std::int32_t>(t));
      }
    std::sort(bad.begin(), bad.end());
    std::size_t changes = 0;
    for (const auto& item : bad)
      if (improve(item.second))
        ++changes;
    ++passes;
    if (changes == 0)
      break;
  }
  return passes;
}

template <int K>
void SimplexStarMesh<K>::WriteBack(SimplexMesh& mesh) const
{
  mesh.Cells.clear();
  for (const Simplex& t : Simplices)
    if (t[0] != kDead)
      mesh.Cells.insert(mesh.Cells.end(), t.begin(), t.end());
  const int dim = mesh.AmbientDim;
  mesh.Points.resize(Points.size() * static_cast<std::size_t>(dim));
  for (std::size_t i = 0; i < Points.size(); ++i)
    if (Moved[i])
      for (int d = 0; d < dim; ++d)
        mesh.Points[i * dim + d] = Points[i][d];
}

template class SimplexStarMesh<2>;
template class SimplexStarMesh<3>;

} // namespace av
