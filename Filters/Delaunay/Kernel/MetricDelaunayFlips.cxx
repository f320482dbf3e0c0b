// SPDX-License-Identifier: BSD-3-Clause
#include "MetricDelaunayFlips.h"

#include "MetricAlgebra.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <vector>

namespace av
{
namespace
{
using Face = std::array<std::int32_t, 3>;
using Tet = std::array<std::int32_t, 4>;
// New tets must be this far from flat (k! volume over (sum of squared edges)^(3/2); a regular
// tet: 0.048, the flat rule of ComputeRestrictedDelaunay: 1e-7): Delaunay flips in a varying
// metric would otherwise trade a non-Delaunay face for a sliver the improvement cannot undo.
constexpr double kFlatTolerance = 1e-4;

Face SortedFace(std::int32_t a, std::int32_t b, std::int32_t c)
{
  Face f{ a, b, c };
  std::sort(f.begin(), f.end());
  return f;
}

class FlipState
{
public:
  FlipState(SimplexMesh& m,
    const MetricField& metric,
    const std::vector<std::array<std::int32_t, 4>>& targets)
    : Mesh(m)
  {
    Targets.reserve(targets.size());
    for (Tet t : targets)
    {
      std::sort(t.begin(), t.end());
      Targets.push_back(t);
    }
    std::sort(Targets.begin(), Targets.end());
    Sqrt.resize(m.NumPoints());
    for (std::size_t i = 0; i < m.NumPoints(); ++i)
      Sqrt[i] = SymmetricSqrt(UnpackSymmetric(metric.At(i)));
    for (std::size_t c = 0; c < m.NumCells(); ++c)
    {
      const std::int32_t* v = m.Cell(c);
      Add({ v[0], v[1], v[2], v[3] });
    }
  }

  MetricDelaunayFlipResult Run()
  {
    MetricDelaunayFlipResult r;
    std::deque<Face> queue;
    for (const auto& f : Faces)
      queue.push_back(f.first);
    const std::size_t budget = 10 * Tets.size();
    while (!queue.empty())
    {
      if (r.NumFlips23 + r.NumFlips32 >= budget)
      {
        r.Capped = true;
        break;
      }
      const Face f = queue.front();
      queue.pop_front();
      const auto it = Faces.find(f);
      if (it == Faces.end() || it->second.size() != 2)
        continue;
      ++r.NumChecked;
      const std::int32_t t1 = it->second[0], t2 = it->second[1];
      if (IsTarget(Tets[t1]) || IsTarget(Tets[t2]))
        continue;
      const std::int32_t d = Apex(t1, f), e = Apex(t2, f);
      // Without targets (or when the face is not Delaunay) any valid flip; otherwise only one
      // that creates a target tet.
      const bool targetOnly = !InSphere(f, d, e);
      if (targetOnly && Targets.empty())
        continue;
      std::vector<std::int32_t> touched;
      bool created = false;
      if (Flip23(t1, t2, f, d, e, targetOnly, created, touched))
        ++r.NumFlips23;
      else if (Flip32(f, d, e, targetOnly, created, touched))
        ++r.NumFlips32;
      else
        continue;
      r.NumTargetFlips += targetOnly;
      for (const std::int32_t t : touched)
        for (int skip = 0; skip < 4; ++skip)
          queue.push_back(FaceOf(Tets[t], skip));
    }
    Write();
    return r;
  }

private:
  SimplexMesh& Mesh;
  std::vector<Eigen::Matrix3d> Sqrt;
  std::vector<Tet> Tets;
  std::vector<char> Alive;
  std::map<Face, std::vector<std::int32_t>> Faces;
  std::vector<Tet> Targets; // sorted quadruples, sorted

  bool IsTarget(Tet t) const
  {
    if (Targets.empty())
      return false;
    std::sort(t.begin(), t.end());
    return std::binary_search(Targets.begin(), Targets.end(), t);
  }

  /// Whether a flip to `n` (count `k`) may be made: with `targetOnly`, one of them is a target.
  bool Allowed(const Tet* n, int k, bool targetOnly, bool& created) const
  {
    created = false;
    for (int i = 0; i < k; ++i)
      created = created || IsTarget(n[i]);
    return !targetOnly || created;
  }

  Eigen::Vector3d P(std::int32_t i) const
  {
    return Eigen::Map<const Eigen::Vector3d>(Mesh.Point(i));
  }

  static Face FaceOf(const Tet& t, int skip)
  {
    std::array<std::int32_t, 3> f;
    int n = 0;
    for (int a = 0; a < 4; ++a)
      if (a != skip)
        f[n++] = t[a];
    return SortedFace(f[0], f[1], f[2]);
  }

  std::int32_t Apex(std::int32_t t, const Face& f) const
  {
    for (const std::int32_t v : Tets[t])
      if (v != f[0] && v != f[1] && v != f[2])
        return v;
    return -1;
  }

  void Add(const Tet& t)
  {
    const auto id = static_cast<std::int32_t>(Tets.size());
    Tets.push_back(t);
    Alive.push_back(1);
    for (int skip = 0; skip < 4; ++skip)
      Faces[FaceOf(t, skip)].push_back(id);
  }

  void Kill(std::int32_t id)
  {
    Alive[id] = 0;
    for (int skip = 0; skip < 4; ++skip)
    {
      const auto it = Faces.find(FaceOf(Tets[id], skip));
      auto& v = it->second;
      v.erase(std::remove(v.begin(), v.end(), id), v.end());
      if (v.empty())
        Faces.erase(it);
    }
  }

  /// Positive with the flat rule's margin (input space).
  bool Valid(const Tet& t) const
  {
    const Eigen::Vector3d a = P(t[0]), b = P(t[1]), c = P(t[2]), d = P(t[3]);
    const double six = (b - a).dot((c - a).cross(d - a));
    const double l2 = (b - a).squaredNorm() + (c - a).squaredNorm() + (d - a).squaredNorm() +
      (c - b).squaredNorm() + (d - b).squaredNorm() + (d - c).squaredNorm();
    return six > kFlatTolerance * std::pow(l2, 1.5);
  }

  /// (a, b, c, d) ordered to be positive (a flat one is left to Valid to refuse).
  Tet Oriented(std::int32_t a, std::int32_t b, std::int32_t c, std::int32_t d) const
  {
    const double six = (P(b) - P(a)).dot((P(c) - P(a)).cross(P(d) - P(a)));
    return six >= 0.0 ? Tet{ a, b, c, d } : Tet{ a, b, d, c };
  }

  /// Whether e is strictly inside the circumsphere of (f, d), in the mean metric of the five.
  bool InSphere(const Face& f, std::int32_t d, std::int32_t e) const
  {
    const std::int32_t v[5] = { f[0], f[1], f[2], d, e };
    Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
    for (const std::int32_t i : v)
      s += Sqrt[i];
    s /= 5.0;
    Eigen::Vector3d q[5];
    for (int i = 0; i < 5; ++i)
      q[i] = s * P(v[i]);
    // Circumcenter of the first four: 2 (q_i - q_0) . x = |q_i|^2 - |q_0|^2.
    Eigen::Matrix3d a;
    Eigen::Vector3d rhs;
    for (int i = 1; i < 4; ++i)
    {
      a.row(i - 1) = 2.0 * (q[i] - q[0]).transpose();
      rhs[i - 1] = q[i].squaredNorm() - q[0].squaredNorm();
    }
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(a);
    if (!lu.isInvertible())
      return false;
    const Eigen::Vector3d x = lu.solve(rhs);
    const double r2 = (q[0] - x).squaredNorm();
    return (q[4] - x).squaredNorm() < r2 * (1.0 - 1e-9);
  }

  bool Flip23(std::int32_t t1,
    std::int32_t t2,
    const Face& f,
    std::int32_t d,
    std::int32_t e,
    bool targetOnly,
    bool& created,
    std::vector<std::int32_t>& touched)
  {
    const Tet n[3] = {
      Oriented(f[0], f[1], d, e), Oriented(f[1], f[2], d, e), Oriented(f[2], f[0], d, e)
    };
    if (!Allowed(n, 3, targetOnly, created))
      return false;
    for (const Tet& t : n)
      if (!Valid(t))
        return false;
    // The three new tets fill the old two exactly only when de crosses abc: their volumes add up.
    double before = 0.0, after = 0.0;
    for (const std::int32_t t : { t1, t2 })
      before += Volume(Tets[t]);
    for (const Tet& t : n)
      after += Volume(t);
    if (std::abs(after - before) > 1e-9 * before)
      return false;
    Kill(t1);
    Kill(t2);
    for (const Tet& t : n)
    {
      touched.push_back(static_cast<std::int32_t>(Tets.size()));
      Add(t);
    }
    return true;
  }

  /// 3-2: an edge of f with exactly the tets (f, d), (f, e) and one with d and e around it.
  bool Flip32(const Face& f,
    std::int32_t d,
    std::int32_t e,
    bool targetOnly,
    bool& created,
    std::vector<std::int32_t>& touched)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::int32_t a = f[k], b = f[(k + 1) % 3], c = f[(k + 2) % 3];
      const auto it1 = Faces.find(SortedFace(a, b, d));
      const auto it2 = Faces.find(SortedFace(a, b, e));
      if (it1 == Faces.end() || it2 == Faces.end() || it1->second.size() != 2 ||
        it2->second.size() != 2)
        continue;
      // The third tet: abde, shared by faces abd and abe.
      std::int32_t third = -1;
      for (const std::int32_t t : it1->second)
        if (std::find(it2->second.begin(), it2->second.end(), t) != it2->second.end())
          third = t;
      if (third < 0 || IsTarget(Tets[third]))
        continue;
      const auto fc = Faces.find(f);
      const std::int32_t t1 = fc->second[0], t2 = fc->second[1];
      if (EdgeDegree(a, b, t1, 3) != 3)
        continue;
      const Tet n[2] = { Oriented(a, c, d, e), Oriented(b, c, d, e) };
      if (!Allowed(n, 2, targetOnly, created) || !Valid(n[0]) || !Valid(n[1]))
        continue;
      const double before = Volume(Tets[t1]) + Volume(Tets[t2]) + Volume(Tets[third]);
      const double after = Volume(n[0]) + Volume(n[1]);
      if (std::abs(after - before) > 1e-9 * before)
        continue;
      Kill(t1);
      Kill(t2);
      Kill(third);
      for (const Tet& t : n)
      {
        touched.push_back(static_cast<std::int32_t>(Tets.size()));
        Add(t);
      }
      return true;
    }
    return false;
  }

  /// Tets around edge ab, by rotation from tet `start` across the faces that hold ab; -1 if
  /// the edge is on the boundary (or a non-manifold face) or has more than `limit` tets.
  int EdgeDegree(std::int32_t a, std::int32_t b, std::int32_t start, int limit) const
  {
    std::int32_t t = start, y = -1;
    for (const std::int32_t v : Tets[t])
      if (v != a && v != b)
        y = v; // one of the two others: rotate across face aby
    for (int count = 1; count <= limit; ++count)
    {
      const auto it = Faces.find(SortedFace(a, b, y));
      if (it == Faces.end() || it->second.size() != 2)
        return -1;
      const std::int32_t next = it->second[0] == t ? it->second[1] : it->second[0];
      if (next == start)
        return count;
      std::int32_t z = -1;
      for (const std::int32_t v : Tets[next])
        if (v != a && v != b && v != y)
          z = v;
      t = next;
      y = z;
    }
    return -1;
  }

  double Volume(const Tet& t) const
  {
    return std::abs((P(t[1]) - P(t[0])).dot((P(t[2]) - P(t[0])).cross(P(t[3]) - P(t[0])))) / 6.0;
  }

  void Write()
  {
    Mesh.Cells.clear();
    for (std::size_t t = 0; t < Tets.size(); ++t)
      if (Alive[t])
        Mesh.Cells.insert(Mesh.Cells.end(), Tets[t].begin(), Tets[t].end());
  }
};

} // namespace

MetricDelaunayFlipResult FlipTowardsMetricDelaunay(SimplexMesh& mesh,
  const MetricField& metric,
  const std::vector<std::array<std::int32_t, 4>>& targets)
{
  if (mesh.SimplexDim != 3 || mesh.AmbientDim != 3 || metric.NumPoints() != mesh.NumPoints())
    return {};
  FlipState s(mesh, metric, targets);
  return s.Run();
}

} // namespace av
