// SPDX-License-Identifier: BSD-3-Clause
#include "MetricPreparation.h"

#include "DomainChords.h"

#include "MeshTopology.h"
#include "MetricAlgebra.h"
#include "MetricFieldOps.h"
#include "VertexGraph.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace av
{
namespace
{
template <int D>
using Mat = Eigen::Matrix<double, D, D>;
template <int D>
using Vec = Eigen::Matrix<double, D, 1>;

/// Relative tolerance of the gradation's containment test (a metric "changes" beyond it).
constexpr double GradationTolerance = 1e-6;

template <int D>
Mat<D> Read(const double* v6)
{
  if constexpr (D == 3)
    return UnpackSymmetric(v6);
  else
    return UnpackSymmetric2(v6);
}

template <int D>
void Write(const Mat<D>& m, double* v6)
{
  if constexpr (D == 3)
    PackSymmetric(m, v6);
  else
    PackSymmetric2(m, v6);
}

template <int D>
std::vector<Mat<D>> ReadField(const MetricField& f)
{
  std::vector<Mat<D>> m(f.NumPoints());
  for (std::size_t i = 0; i < m.size(); ++i)
    m[i] = Read<D>(f.At(i));
  return m;
}

template <int D>
MetricField WriteField(const std::vector<Mat<D>>& m)
{
  MetricField f;
  f.Values.assign(6 * m.size(), 0.0);
  for (std::size_t i = 0; i < m.size(); ++i)
    Write<D>(m[i], f.Values.data() + 6 * i);
  return f;
}

template <class F>
void ForEachVertex(std::size_t n, const F& f)
{
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 512),
    [&](const tbb::blocked_range<std::size_t>& r)
    {
      for (std::size_t i = r.begin(); i != r.end(); ++i)
        f(i);
    });
}

/// The first D coordinates of mesh vertex i (missing ones are 0).
template <int D>
Vec<D> Position(const SimplexMesh& mesh, std::size_t i)
{
  Vec<D> x = Vec<D>::Zero();
  for (int k = 0; k < std::min(D, mesh.AmbientDim); ++k)
    x[k] = mesh.Point(i)[k];
  return x;
}

/// Size mode: M <- M det(M)^((alpha - 1) / D), so that det becomes det^alpha.
template <int D>
void ApplySizeMode(double alpha, std::vector<Mat<D>>& m)
{
  if (alpha == 1.0)
    return;
  ForEachVertex(m.size(),
    [&](std::size_t i)
    {
      const double logDet = EigenDecompose(m[i]).Values.array().log().sum();
      m[i] *= std::exp((alpha - 1.0) / D * logDet);
    });
}

/// Eigenvalues clamped to [lo, hi] (0 = no bound); flags |= 1 where raised to lo (hmax acted),
/// |= 2 where lowered to hi (hmin acted).
template <int D>
void ClampSizes(double lo, double hi, std::vector<Mat<D>>& m, std::vector<unsigned char>& flags)
{
  if (lo <= 0.0 && hi <= 0.0)
    return;
  ForEachVertex(m.size(),
    [&](std::size_t i)
    {
      const auto e = EigenDecompose(m[i]);
      Vec<D> v = e.Values;
      unsigned char f = 0;
      for (int k = 0; k < D; ++k)
      {
        if (lo > 0.0 && v[k] < lo)
        {
          v[k] = lo;
          f |= 1;
        }
        if (hi > 0.0 && v[k] > hi)
        {
          v[k] = hi;
          f |= 2;
        }
      }
      if (f)
        m[i] = e.Vectors * v.asDiagonal() * e.Vectors.transpose();
      flags[i] |= f;
    });
}

/// Smallest and largest eigenvalue of a metric (the gradation's quick containment test).
template <int D>
void Range(const Mat<D>& m, double& lo, double& hi)
{
  // Eigenvalues only, closed form: a quick test, exact to round-off is enough.
  Eigen::SelfAdjointEigenSolver<Mat<D>> es;
  es.computeDirect(m, Eigen::EigenvaluesOnly);
  lo = es.eigenvalues().minCoeff();
  hi = es.eigenvalues().maxCoeff();
}

template <int D>
std::size_t Grade(const SimplexMesh& mesh,
  const VertexGraph& g,
  double lnBeta,
  std::vector<Mat<D>>& m,
  int& sweeps)
{
  const std::size_t n = m.size();
  std::vector<double> lo(n), hi(n);
  ForEachVertex(n, [&](std::size_t i) { Range<D>(m[i], lo[i], hi[i]); });
  std::vector<std::int32_t> active(n), candidates;
  for (std::size_t i = 0; i < n; ++i)
    active[i] = static_cast<std::int32_t>(i);
  std::vector<char> isSource(n, 0), isCandidate(n, 0), everChanged(n, 0);
  std::vector<Mat<D>> next;
  std::vector<double> nextLo, nextHi;
  std::vector<char> changed;
  sweeps = 0;
  // Metrics only grow and stay below the field's largest eigenvalue, so the work list empties;
  // the bound is a guard against round-off cycling.
  const int maxSweeps = static_cast<int>(std::min<std::size_t>(n, 1000000)) + 1000;
  while (!active.empty() && sweeps < maxSweeps)
  {
    ++sweeps;
    candidates.clear();
    for (std::int32_t p : active)
    {
      isSource[p] = 1;
      for (std::int32_t k = g.Offsets[p]; k < g.Offsets[p + 1]; ++k)
      {
        const std::int32_t q = g.Neighbors[k];
        if (!isCandidate[q])
        {
          isCandidate[q] = 1;
          candidates.push_back(q);
        }
      }
    }
    next.resize(candidates.size());
    nextLo.resize(candidates.size());
    nextHi.resize(candidates.size());
    changed.assign(candidates.size(), 0);
    // Jacobi: each candidate pulls from its changed neighbors' current metrics.
    ForEachVertex(candidates.size(),
      [&](std::size_t c)
      {
        const std::int32_t q = candidates[c];
        Mat<D> mq = m[q];
        const Vec<D> xq = Position<D>(mesh, q);
        bool any = false;
        for (std::int32_t k = g.Offsets[q]; k < g.Offsets[q + 1]; ++k)
        {
          const std::int32_t p = g.Neighbors[k];
          if (!isSource[p])
            continue;
          const Vec<D> e = xq - Position<D>(mesh, p);
          const double l = std::sqrt(std::max(0.0, e.dot(m[p] * e)));
          const double grow = 1.0 + l * lnBeta;
          const double eta = 1.0 / (grow * grow);
          if (eta * hi[p] <= lo[q] * (1.0 + GradationTolerance))
            continue; // the propagated ball contains q's: nothing to do (lo[q] only grows)
          any |= IntersectInto(mq, Mat<D>(eta * m[p]), GradationTolerance);
        }
        if (any)
        {
          next[c] = mq;
          Range<D>(mq, nextLo[c], nextHi[c]);
          changed[c] = 1;
        }
      });
    for (std::int32_t p : active)
      isSource[p] = 0;
    active.clear();
    for (std::size_t c = 0; c < candidates.size(); ++c)
    {
      const std::int32_t q = candidates[c];
      isCandidate[q] = 0;
      if (!changed[c])
        continue;
      m[q] = next[c];
      lo[q] = nextLo[c];
      hi[q] = nextHi[c];
      everChanged[q] = 1;
      active.push_back(q);
    }
  }
  return static_cast<std::size_t>(std::count(everChanged.begin(), everChanged.end(), 1));
}

template <int D>
MetricDeviation Deviation(const SimplexMesh& mesh,
  const MetricField& raw,
  const MetricField& prepared,
  double threshold)
{
  const std::size_t n = raw.NumPoints();
  MetricDeviation d;
  if (n == 0)
    return d;
  // The raw field at the prepared one's complexity: both ask for the same number of cells.
  const double cRaw = MetricComplexity(mesh, raw);
  const double cPrep = MetricComplexity(mesh, prepared);
  const double k = mesh.SimplexDim;
  const double t = (cRaw > 0.0 && cPrep > 0.0) ? std::pow(cPrep / cRaw, 2.0 / k) : 1.0;
  std::vector<double> change(n);
  ForEachVertex(n,
    [&](std::size_t i)
    {
      const auto e = EigenDecompose(Read<D>(raw.At(i)));
      const Mat<D> mp = Read<D>(prepared.At(i));
      double worst = 0.0;
      for (int a = 0; a < D; ++a)
      {
        const Vec<D> v = e.Vectors.col(a);
        const double rho = std::sqrt(v.dot(mp * v) / (t * e.Values[a]));
        worst = std::max(worst, std::max(rho, 1.0 / rho) - 1.0);
      }
      change[i] = worst;
    });
  d.ChangedFraction =
    static_cast<double>(std::count_if(
      change.begin(), change.end(), [threshold](double c) { return c > threshold; })) /
    static_cast<double>(n);
  d.Maximum = *std::max_element(change.begin(), change.end());
  auto quantile = [&](double q)
  {
    const auto at = change.begin() + static_cast<std::ptrdiff_t>(q * static_cast<double>(n - 1));
    std::nth_element(change.begin(), at, change.end());
    return *at;
  };
  d.Median = quantile(0.5);
  d.Percentile95 = quantile(0.95);
  return d;
}

void CheckInputs(const SimplexMesh& mesh,
  const MetricField& metric,
  const MetricPreparationOptions& o,
  const std::vector<std::int32_t>& edges)
{
  const std::string who = "metric preparation: ";
  const std::size_t n = mesh.NumPoints();
  if (n == 0 || mesh.NumCells() == 0)
    throw InputError(who + "the mesh is empty");
  if (metric.NumPoints() != n || metric.Values.size() != 6 * n)
    throw InputError(who + "the metric has " + std::to_string(metric.NumPoints()) + " tuples for " +
      std::to_string(n) + " vertices");
  if (o.Dimension != 2 && o.Dimension != 3)
    throw InputError(who + "Dimension must be 2 or 3");
  if (!(o.SizeBlend >= 0.0 && o.SizeBlend <= 1.0))
    throw InputError(who + "the size blend must be in [0, 1]");
  if (!(o.TargetSites >= 0.0) || !std::isfinite(o.TargetSites))
    throw InputError(who + "the target number of sites must be >= 0");
  if (!(o.HMin >= 0.0 && o.HMax >= 0.0) || !std::isfinite(o.HMin) || !std::isfinite(o.HMax))
    throw InputError(who + "hmin and hmax must be >= 0 (0 = no limit)");
  if (o.HMin > 0.0 && o.HMax > 0.0 && o.HMin > o.HMax)
    throw InputError(who + "hmin must not exceed hmax");
  if (!(o.MinCellsAcross >= 0.0) || !std::isfinite(o.MinCellsAcross))
    throw InputError(who + "the cells across thin parts must be >= 0 (0 = off)");
  if (o.Gradation && !(o.GradationFactor > 1.0 && std::isfinite(o.GradationFactor)))
    throw InputError(who + "the gradation factor (hgrad) must be > 1");
  if (o.MaxNormalizationRounds < 1 || !(o.ComplexityTolerance > 0.0))
    throw InputError(who + "invalid normalization rounds or tolerance");
  if (edges.size() % 2 != 0)
    throw InputError(who + "the edge list must hold pairs of ids");
  for (std::int32_t e : edges)
    if (e < 0 || static_cast<std::size_t>(e) >= n)
      throw InputError(who + "edge references vertex " + std::to_string(e) + ", outside [0, " +
        std::to_string(n) + ")");
  CheckCellIds(mesh, who, "cell");
  for (std::size_t i = 0; i < n; ++i)
  {
    const double* v = metric.At(i);
    const bool ok = AllFinite(v, 6) &&
      (o.Dimension == 3 ? IsPositiveDefinite(UnpackSymmetric(v))
                        : IsPositiveDefinite(UnpackSymmetric2(v)));
    if (!ok)
      throw InputError(who + "the metric of vertex " + std::to_string(i) +
        " is not symmetric positive definite (or has NaN/Inf)");
  }
}

/// MinCellsAcross: where the chord c along direction d holds fewer than `cells` unit lengths,
/// add (cells^2 / c^2 - d^T M d) d d^T to M (SPD kept, lengths only grow). Returns the number
/// of vertices changed.
template <int D>
std::size_t LimitByThickness(const DomainChords& chords, double cells, std::vector<Mat<D>>& m)
{
  const std::size_t nd = chords.NumDirections();
  std::vector<unsigned char> changed(m.size(), 0);
  ForEachVertex(m.size(),
    [&](std::size_t i)
    {
      for (std::size_t k = 0; k < nd; ++k)
      {
        const double c = chords.Chord[i * nd + k];
        if (!std::isfinite(c) || !(c > 0.0))
          continue;
        const Vec<D> d = Eigen::Map<const Vec<D>>(chords.Directions.data() + k * D);
        const double need = (cells / c) * (cells / c);
        const double have = d.dot(m[i] * d);
        if (have < need)
        {
          m[i] += (need - have) * d * d.transpose();
          changed[i] = 1;
        }
      }
    });
  return static_cast<std::size_t>(std::count(changed.begin(), changed.end(), 1));
}

template <int D>
MetricPreparationResult Prepare(const SimplexMesh& mesh,
  const MetricField& metric,
  const MetricPreparationOptions& o,
  const std::vector<std::int32_t>& edges)
{
  MetricPreparationResult r;
  const double k = mesh.SimplexDim;
  const double unit = UnitVertexMeasure(mesh.SimplexDim);
  r.RawComplexity = MetricComplexity(mesh, metric);
  std::vector<Mat<D>> sized = ReadField<D>(metric);
  const double alpha = o.SizeMode == MetricSizeMode::Tensor ? 1.0
    : o.SizeMode == MetricSizeMode::Uniform                 ? 0.0
                                                            : o.SizeBlend;
  ApplySizeMode<D>(alpha, sized);
  const VertexGraph graph =
    BuildVertexGraph(mesh.NumPoints(), edges.empty() ? UniqueEdges(mesh) : edges);
  r.TargetComplexity = o.TargetSites * unit;
  double scale = 1.0;
  if (r.TargetComplexity > 0.0)
    scale = std::pow(r.TargetComplexity / MetricComplexity(mesh, WriteField<D>(sized)), 2.0 / k);
  const double lo = o.HMax > 0.0 ? 1.0 / (o.HMax * o.HMax) : 0.0;
  const double hi = o.HMin > 0.0 ? 1.0 / (o.HMin * o.HMin) : 0.0;
  const int rounds = r.TargetComplexity > 0.0 ? o.MaxNormalizationRounds : 1;
  // Geometry only: computed once. Volumes, and flat 2D domains in the 2D metric block.
  // Not in Uniform mode: its contract is equal sizes (det M constant).
  bool thickness = o.MinCellsAcross > 0.0 && o.SizeMode != MetricSizeMode::Uniform &&
    mesh.SimplexDim == D && (mesh.AmbientDim == D || (D == 2 && mesh.AmbientDim == 3));
  for (std::size_t i = 0; thickness && D == 2 && mesh.AmbientDim == 3 && i < mesh.NumPoints(); ++i)
    thickness = mesh.Point(i)[2] == mesh.Point(0)[2]; // a flat domain, not a surface
  const DomainChords chords = thickness ? ComputeDomainChords(mesh) : DomainChords();
  std::vector<Mat<D>> m;
  const double initialScale = scale;
  // `start`: the first scale tried (a later attempt with fewer cells across starts from the
  // scale the one before ended at, which is much closer than the plain normalization's).
  const auto normalize = [&](double cells, double start)
  {
    scale = start;
    double previousScale = scale, previousComplexity = 0.0;
    for (int round = 0; round < rounds; ++round)
    {
      // Every round starts again from the sized field, so the result does not depend on the
      // rounds before, only on the final scale.
      m = sized;
      ForEachVertex(m.size(), [&](std::size_t i) { m[i] *= scale; });
      // Limits, gradation, limits again: the intersections of the gradation can leave a size a
      // little outside [hmin, hmax], and the limits are the user's hard bounds.
      std::vector<unsigned char> clamped(m.size(), 0);
      ClampSizes<D>(lo, hi, m, clamped);
      r.NumThicknessLimited = thickness ? LimitByThickness<D>(chords, cells, m) : 0;
      r.NumGraded = 0;
      r.GradationSweeps = 0;
      if (o.Gradation)
      {
        r.NumGraded = Grade<D>(mesh, graph, std::log(o.GradationFactor), m, r.GradationSweeps);
        ++r.GradationRuns;
        r.TotalGradationSweeps += r.GradationSweeps;
      }
      ClampSizes<D>(lo, hi, m, clamped);
      r.NumHMaxClamped = static_cast<std::size_t>(
        std::count_if(clamped.begin(), clamped.end(), [](unsigned char f) { return f & 1; }));
      r.NumHMinClamped = static_cast<std::size_t>(
        std::count_if(clamped.begin(), clamped.end(), [](unsigned char f) { return f & 2; }));
      r.Metric = WriteField<D>(m);
      r.Complexity = MetricComplexity(mesh, r.Metric);
      r.Scale = scale;
      if (r.TargetComplexity <= 0.0)
        break;
      r.NormalizationRounds = round + 1;
      const double ratio = r.TargetComplexity / r.Complexity;
      if (std::abs(ratio - 1.0) <= o.ComplexityTolerance)
        break;
      // Newton on log C(log s): the slope is k/2 for a plain scaling, less where hmin or hmax
      // hold the sizes; secant estimate after the first round.
      double slope = 0.5 * k;
      if (round > 0 && std::abs(std::log(scale / previousScale)) > 1e-12)
      {
        slope = std::log(r.Complexity / previousComplexity) / std::log(scale / previousScale);
        // Too many cells that hardly shrink with the scale: the thin parts' floor (and the
        // gradation from it) holds them. More rounds only drive the scale towards 0 (squareBend:
        // 1e-19 after 8, the ratio stuck at 0.61); fewer cells across is the way out.
        if (thickness && slope < 0.1 && ratio < 1.0 - 25.0 * o.ComplexityTolerance)
          break;
        slope = std::clamp(slope, 0.05, k);
      }
      previousScale = scale;
      previousComplexity = r.Complexity;
      scale *= std::exp(std::log(ratio) / slope);
    }
  };
  double cells = o.MinCellsAcross;
  normalize(cells, initialScale);
  // Where the thin parts alone need more cells than the target (a long duct for few sites),
  // fewer cells across: their complexity grows like cells^e, e = k at first, then the secant
  // of log C(log cells) (squareBend: about 1.4, the gradation ties only part of the sizes).
  double previousCells = 0.0, previousComplexity = 0.0;
  for (int attempt = 0; thickness && r.TargetComplexity > 0.0 && attempt < 4 &&
       r.Complexity > (1.0 + 25.0 * o.ComplexityTolerance) * r.TargetComplexity;
       ++attempt)
  {
    double exponent = k;
    if (previousCells > 0.0 && std::abs(std::log(cells / previousCells)) > 1e-12)
      exponent = std::clamp(
        std::log(r.Complexity / previousComplexity) / std::log(cells / previousCells), 0.5, k);
    previousCells = cells;
    previousComplexity = r.Complexity;
    cells *= std::pow(r.TargetComplexity / r.Complexity, 1.0 / exponent);
    normalize(cells, r.Scale);
  }
  r.CellsAcross = thickness ? cells : 0.0;
  r.ImpliedSites = r.Complexity / unit;
  r.StretchRatio.resize(m.size());
  ForEachVertex(m.size(),
    [&](std::size_t i)
    {
      const auto e = EigenDecompose(m[i]);
      r.StretchRatio[i] = std::sqrt(e.Values.maxCoeff() / e.Values.minCoeff());
    });
  r.Deviation = Deviation<D>(mesh, metric, r.Metric, o.ChangeThreshold);
  return r;
}
} // namespace

MetricPreparationResult PrepareMetric(const SimplexMesh& mesh,
  const MetricField& metric,
  const MetricPreparationOptions& options,
  const std::vector<std::int32_t>& edges)
{
  CheckInputs(mesh, metric, options, edges);
  return options.Dimension == 2 ? Prepare<2>(mesh, metric, options, edges)
                                : Prepare<3>(mesh, metric, options, edges);
}

std::size_t GradeMetric(const SimplexMesh& mesh,
  const std::vector<std::int32_t>& edges,
  double beta,
  int dimension,
  MetricField& metric,
  int& sweeps)
{
  MetricPreparationOptions o;
  o.Dimension = dimension;
  o.GradationFactor = beta;
  CheckInputs(mesh, metric, o, edges);
  const VertexGraph graph =
    BuildVertexGraph(mesh.NumPoints(), edges.empty() ? UniqueEdges(mesh) : edges);
  std::size_t changed = 0;
  if (dimension == 2)
  {
    std::vector<Mat<2>> m = ReadField<2>(metric);
    changed = Grade<2>(mesh, graph, std::log(beta), m, sweeps);
    metric = WriteField<2>(m);
  }
  else
  {
    std::vector<Mat<3>> m = ReadField<3>(metric);
    changed = Grade<3>(mesh, graph, std::log(beta), m, sweeps);
    metric = WriteField<3>(m);
  }
  return changed;
}

MetricDeviation MeasureMetricDeviation(const SimplexMesh& mesh,
  const MetricField& raw,
  const MetricField& prepared,
  int dimension,
  double changeThreshold)
{
  MetricPreparationOptions o;
  o.Dimension = dimension;
  CheckInputs(mesh, raw, o, {});
  CheckInputs(mesh, prepared, o, {});
  return dimension == 2 ? Deviation<2>(mesh, raw, prepared, changeThreshold)
                        : Deviation<3>(mesh, raw, prepared, changeThreshold);
}

} // namespace av
