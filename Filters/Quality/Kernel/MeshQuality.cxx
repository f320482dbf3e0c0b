// SPDX-License-Identifier: BSD-3-Clause
#include "MeshQuality.h"

#include "MetricAlgebra.h" // MoveSurfaceMetric, SurfaceMetricNormals

#include <Eigen/Dense>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace av
{
namespace
{
constexpr double kPi = 3.14159265358979323846;
constexpr double kRadToDeg = 180.0 / kPi;

Eigen::Matrix3d MetricTensor(const double* v, int ambientDim)
{
  Eigen::Matrix3d m;
  // MetricField order: XX, YY, ZZ, XY, YZ, XZ.
  m << v[0], v[3], v[5], v[3], v[1], v[4], v[5], v[4], v[2];
  if (ambientDim == 2)
  {
    m(2, 2) = 0.0;
    m(0, 2) = m(2, 0) = m(1, 2) = m(2, 1) = 0.0;
  }
  return m;
}

void CheckMesh(const SimplexMesh& mesh, const char* who)
{
  const std::string w(who);
  if (mesh.SimplexDim != 2 && mesh.SimplexDim != 3)
    throw InputError(w + ": only triangles (SimplexDim 2) and tetrahedra (3) are supported");
  if (mesh.AmbientDim != 2 && mesh.AmbientDim != 3)
    throw InputError(w + ": AmbientDim must be 2 or 3");
  if (mesh.SimplexDim > mesh.AmbientDim)
    throw InputError(w + ": tetrahedra need 3D points");
  if (mesh.Points.size() % static_cast<std::size_t>(mesh.AmbientDim) != 0 ||
    mesh.Cells.size() % static_cast<std::size_t>(mesh.SimplexDim + 1) != 0)
    throw InputError(w + ": Points/Cells array sizes are not multiples of the dimension");
  const auto np = static_cast<std::int64_t>(mesh.NumPoints());
  for (auto id : mesh.Cells)
    if (id < 0 || id >= np)
      throw InputError(w + ": cell refers to point id " + std::to_string(id) + " outside [0, " +
        std::to_string(np) + ")");
  for (double x : mesh.Points)
    if (!std::isfinite(x))
      throw InputError(w + ": mesh points contain NaN or Inf");
}

void CheckMetric(const SimplexMesh& mesh, const MetricField& metric, const char* who)
{
  const std::string w(who);
  if (metric.Values.size() != 6 * mesh.NumPoints())
    throw InputError(w + ": metric has " + std::to_string(metric.Values.size() / 6) +
      " tensors (6 values each) but the mesh has " + std::to_string(mesh.NumPoints()) + " points");
  for (double x : metric.Values)
    if (!std::isfinite(x))
      throw InputError(w + ": metric contains NaN or Inf");
}

/// min over the 6 edges of the dihedral angle at that edge, radians.
double MinDihedral(const Eigen::Vector3d p[4])
{
  static const int kEdges[6][4] = {
    { 0, 1, 2, 3 }, { 0, 2, 1, 3 }, { 0, 3, 1, 2 }, { 1, 2, 0, 3 }, { 1, 3, 0, 2 }, { 2, 3, 0, 1 }
  };
  double best = kPi;
  for (const auto& e : kEdges)
  {
    Eigen::Vector3d d = p[e[1]] - p[e[0]];
    const double dn = d.norm();
    if (dn <= 0.0)
      return 0.0;
    d /= dn;
    Eigen::Vector3d u = p[e[2]] - p[e[0]];
    Eigen::Vector3d w = p[e[3]] - p[e[0]];
    u -= u.dot(d) * d;
    w -= w.dot(d) * d;
    const double a = std::atan2(u.cross(w).norm(), u.dot(w));
    best = std::min(best, a);
  }
  return best;
}
/// Vertex `id` of the mesh in 3D (z = 0 for a flat 2D domain).
Eigen::Vector3d PointOf(const SimplexMesh& mesh, std::int32_t id)
{
  const double* p = mesh.Point(static_cast<std::size_t>(id));
  return Eigen::Vector3d(p[0], p[1], mesh.AmbientDim == 3 ? p[2] : 0.0);
}

/// One cell's G, smallest angle and orientation in the metric of its averaged square roots
/// A = mean of the vertex A_i (paper §5.2). Surfaces (`normals` not empty): each A_i moved into
/// the triangle's plane first (MoveSurfaceMetric).
void CellQuality(const SimplexMesh& mesh,
  const std::vector<Eigen::Matrix3d>& sqrtM,
  const std::vector<Eigen::Vector3d>& normals,
  std::size_t c,
  MeshQualityResult& res)
{
  const int k = mesh.SimplexDim;
  const int nv = k + 1;
  const int m = mesh.AmbientDim;
  const std::int32_t* ids = mesh.Cell(c);
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d x[4], y[4];
  for (int i = 0; i < nv; ++i)
  {
    x[i] = PointOf(mesh, ids[i]);
  }
  const Eigen::Vector3d faceNormal =
    normals.empty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d((x[1] - x[0]).cross(x[2] - x[0]));
  const double fn = faceNormal.norm();
  for (int i = 0; i < nv; ++i)
  {
    const auto v = static_cast<std::size_t>(ids[i]);
    a += fn > 0.0 ? MoveSurfaceMetric(sqrtM[v], normals[v], faceNormal / fn) : sqrtM[v];
  }
  a /= nv;
  for (int i = 0; i < nv; ++i)
    y[i] = a * x[i];
  if (k == 2)
  {
    const Eigen::Vector3d e0 = x[1] - x[0], e1 = x[2] - x[0];
    const double signedArea = m == 2 ? e0.x() * e1.y() - e0.y() * e1.x() : e0.cross(e1).norm();
    res.Inverted[c] = signedArea <= 0.0 ? 1 : 0;
    const double l[3] = { (y[1] - y[2]).norm(), (y[2] - y[0]).norm(), (y[0] - y[1]).norm() };
    const double s = 0.5 * (y[1] - y[0]).cross(y[2] - y[0]).norm();
    const double p = 0.5 * (l[0] + l[1] + l[2]);
    const double h = std::max({ l[0], l[1], l[2] });
    res.G[c] = p > 0.0 && h > 0.0 ? 2.0 * std::sqrt(3.0) * s / (p * h) : 0.0;
    double th = kPi;
    for (int i = 0; i < 3; ++i)
    {
      const Eigen::Vector3d u = y[(i + 1) % 3] - y[i], w = y[(i + 2) % 3] - y[i];
      th = std::min(th, std::atan2(u.cross(w).norm(), u.dot(w)));
    }
    res.MinAngle[c] = th * kRadToDeg;
  }
  else
  {
    const double vol0 = (x[1] - x[0]).dot((x[2] - x[0]).cross(x[3] - x[0])) / 6.0;
    res.Inverted[c] = vol0 <= 0.0 ? 1 : 0;
    const double v = std::abs((y[1] - y[0]).dot((y[2] - y[0]).cross(y[3] - y[0]))) / 6.0;
    double sl2 = 0.0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        sl2 += (y[j] - y[i]).squaredNorm();
    res.G[c] = sl2 > 0.0 ? 12.0 * std::cbrt(9.0 * v * v) / sl2 : 0.0;
    res.MinAngle[c] = MinDihedral(y) * kRadToDeg;
  }
}

/// Unique edges and their metric lengths with Q_ab = (A_a + A_b) / 2.
void EdgeMetricLengths(const SimplexMesh& mesh,
  const std::vector<Eigen::Matrix3d>& sqrtM,
  const std::vector<Eigen::Vector3d>& normals,
  MeshQualityResult& res)
{
  const std::size_t nc = mesh.NumCells();
  const std::size_t np = mesh.NumPoints();
  const int nv = mesh.SimplexDim + 1;
  std::vector<std::int64_t> keys;
  keys.reserve(nc * static_cast<std::size_t>(nv * (nv - 1) / 2));
  for (std::size_t c = 0; c < nc; ++c)
  {
    const std::int32_t* ids = mesh.Cell(c);
    for (int i = 0; i < nv; ++i)
      for (int j = i + 1; j < nv; ++j)
      {
        const std::int64_t lo = std::min(ids[i], ids[j]), hi = std::max(ids[i], ids[j]);
        if (lo != hi)
          keys.push_back(lo * static_cast<std::int64_t>(np) + hi);
      }
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  const std::size_t ne = keys.size();
  res.Edges.resize(2 * ne);
  res.EdgeLengths.resize(ne);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, ne),
    [&](const tbb::blocked_range<std::size_t>& r)
    {
      for (std::size_t e = r.begin(); e != r.end(); ++e)
      {
        const auto a = static_cast<std::int32_t>(keys[e] / static_cast<std::int64_t>(np));
        const auto b = static_cast<std::int32_t>(keys[e] % static_cast<std::int64_t>(np));
        res.Edges[2 * e] = a;
        res.Edges[2 * e + 1] = b;
        const auto ua = static_cast<std::size_t>(a), ub = static_cast<std::size_t>(b);
        const Eigen::Vector3d d = PointOf(mesh, b) - PointOf(mesh, a);
        res.EdgeLengths[e] = normals.empty()
          ? (0.5 * (sqrtM[ua] + sqrtM[ub]) * d).norm()
          : std::sqrt(SurfaceEdgeMetricLength2(d, sqrtM[ua], normals[ua], sqrtM[ub], normals[ub]));
      }
    });
}

/// G_min / G_avg, angles, % bad, the angle histogram and the edges in [1/sqrt2, sqrt2] x median.
void Summarize(int k, MeshQualityResult& res)
{
  const std::size_t nc = res.G.size();
  const std::size_t ne = res.EdgeLengths.size();
  MeshQualitySummary& s = res.Summary;
  s.NumCells = nc;
  s.BadAngleThreshold = k == 2 ? 30.0 : 15.0;
  s.HistogramBinWidth = 5.0;
  s.AngleHistogram.assign(18, 0);
  s.GMin = std::numeric_limits<double>::infinity();
  s.ThetaMin = std::numeric_limits<double>::infinity();
  double gSum = 0.0, tSum = 0.0;
  for (std::size_t c = 0; c < nc; ++c)
  {
    s.GMin = std::min(s.GMin, res.G[c]);
    s.ThetaMin = std::min(s.ThetaMin, res.MinAngle[c]);
    gSum += res.G[c];
    tSum += res.MinAngle[c];
    if (res.MinAngle[c] < s.BadAngleThreshold)
      ++s.NumBad;
    s.NumInverted += res.Inverted[c];
    const auto bin = std::min<std::size_t>(17,
      // The small offset keeps exact 60 / 70.53 deg out of the bin below after round-off.
      static_cast<std::size_t>(std::max(0.0, res.MinAngle[c]) / s.HistogramBinWidth + 1e-9));
    ++s.AngleHistogram[bin];
  }
  s.GAvg = gSum / static_cast<double>(nc);
  s.ThetaAvg = tSum / static_cast<double>(nc);
  s.PercentBad = 100.0 * static_cast<double>(s.NumBad) / static_cast<double>(nc);

  s.NumEdges = ne;
  if (ne > 0)
  {
    std::vector<double> sorted = res.EdgeLengths;
    std::nth_element(
      sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(ne / 2), sorted.end());
    double median = sorted[ne / 2];
    if (ne % 2 == 0)
    {
      const double lower =
        *std::max_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(ne / 2));
      median = 0.5 * (median + lower);
    }
    s.MedianEdgeLength = median;
    std::size_t inRange = 0;
    const double lo = 1.0 / std::sqrt(2.0), hi = std::sqrt(2.0);
    for (double& l : res.EdgeLengths)
    {
      l = median > 0.0 ? l / median : 0.0;
      if (l >= lo && l <= hi)
        ++inRange;
    }
    s.PercentEdgesInUnitRange = 100.0 * static_cast<double>(inRange) / static_cast<double>(ne);
  }
}
} // namespace

MeshQualityResult EvaluateMeshQuality(const SimplexMesh& mesh, const MetricField& metric)
{
  CheckMesh(mesh, "EvaluateMeshQuality");
  CheckMetric(mesh, metric, "EvaluateMeshQuality");
  const std::size_t nc = mesh.NumCells();
  const std::size_t np = mesh.NumPoints();
  if (nc == 0)
    throw InputError("EvaluateMeshQuality: the mesh has no cells");
  const int m = mesh.AmbientDim;

  // Per-vertex A_i = M_i^{1/2}.
  std::vector<Eigen::Matrix3d> sqrtM(np);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, np),
    [&](const tbb::blocked_range<std::size_t>& r)
    {
      for (std::size_t i = r.begin(); i != r.end(); ++i)
        sqrtM[i] = SymmetricSqrt(MetricTensor(metric.At(i), m));
    });

  // Surfaces: the rank-2 vertex metrics' normals, to move them into each triangle's plane.
  const std::vector<Eigen::Vector3d> normals = m == 3 && mesh.SimplexDim == 2
    ? SurfaceMetricNormals(metric)
    : std::vector<Eigen::Vector3d>();
  MeshQualityResult res;
  res.G.assign(nc, 0.0);
  res.MinAngle.assign(nc, 0.0);
  res.Inverted.assign(nc, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nc),
    [&](const tbb::blocked_range<std::size_t>& r)
    {
      for (std::size_t c = r.begin(); c != r.end(); ++c)
        CellQuality(mesh, sqrtM, normals, c, res);
    });
  EdgeMetricLengths(mesh, sqrtM, normals, res);
  Summarize(mesh.SimplexDim, res);
  return res;
}

std::vector<double> SimplexQualityInEmbedding(const std::vector<std::int32_t>& cells,
  int simplexDim,
  const std::vector<double>& coords,
  int dim)
{
  const int k = simplexDim;
  if (k != 2 && k != 3)
    throw InputError(
      "SimplexQualityInEmbedding: simplex dimension must be 2 or 3, got " + std::to_string(k));
  if (dim < k)
    throw InputError("SimplexQualityInEmbedding: dimension " + std::to_string(dim) +
      " is smaller than the simplex dimension " + std::to_string(k));
  const std::size_t nv = static_cast<std::size_t>(k + 1);
  if (cells.size() % nv != 0 || coords.size() % static_cast<std::size_t>(dim) != 0)
    throw InputError("SimplexQualityInEmbedding: array sizes are not multiples of " +
      std::to_string(nv) + " ids / " + std::to_string(dim) + " coordinates");
  const std::size_t np = coords.size() / static_cast<std::size_t>(dim);
  for (std::int32_t id : cells)
    if (id < 0 || static_cast<std::size_t>(id) >= np)
      throw InputError("SimplexQualityInEmbedding: point id " + std::to_string(id) +
        " out of range [0, " + std::to_string(np) + ")");
  for (double v : coords)
    if (!std::isfinite(v))
      throw InputError("SimplexQualityInEmbedding: a coordinate is not finite");

  const std::size_t nc = cells.size() / nv;
  std::vector<double> g(nc, 0.0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nc),
    [&](const tbb::blocked_range<std::size_t>& r)
    {
      for (std::size_t c = r.begin(); c != r.end(); ++c)
      {
        const std::int32_t* ids = cells.data() + c * nv;
        const double* p0 = coords.data() + static_cast<std::size_t>(ids[0]) * dim;
        // Gram matrix of the edge vectors from vertex 0 (fixed size: no allocation).
        Eigen::Matrix3d gram = Eigen::Matrix3d::Identity();
        for (int a = 0; a < k; ++a)
        {
          const double* pa = coords.data() + static_cast<std::size_t>(ids[a + 1]) * dim;
          for (int b = a; b < k; ++b)
          {
            const double* pb = coords.data() + static_cast<std::size_t>(ids[b + 1]) * dim;
            double s = 0.0;
            for (int d = 0; d < dim; ++d)
              s += (pa[d] - p0[d]) * (pb[d] - p0[d]);
            gram(a, b) = gram(b, a) = s;
          }
        }
        // Squared edge lengths: |e_a|^2 and |e_a - e_b|^2.
        double l2[6];
        int n = 0;
        for (int a = 0; a < k; ++a)
          l2[n++] = gram(a, a);
        for (int a = 0; a < k; ++a)
          for (int b = a + 1; b < k; ++b)
            l2[n++] = gram(a, a) + gram(b, b) - 2.0 * gram(a, b);
        const double det = std::max(0.0, gram.determinant()); // identity padding for k = 2
        if (k == 2)
        {
          const double area = 0.5 * std::sqrt(det);
          double per = 0.0, h = 0.0;
          for (int e = 0; e < 3; ++e)
          {
            const double l = std::sqrt(std::max(0.0, l2[e]));
            per += l;
            h = std::max(h, l);
          }
          g[c] = h > 0.0 ? 2.0 * std::sqrt(3.0) * area / (0.5 * per * h) : 0.0;
        }
        else
        {
          const double vol = std::sqrt(det) / 6.0;
          double sum = 0.0;
          for (int e = 0; e < 6; ++e)
            sum += l2[e];
          g[c] = sum > 0.0 ? 12.0 * std::cbrt(9.0 * vol * vol) / sum : 0.0;
        }
      }
    });
  return g;
}

MetricField InterpolateMetricAtSites(const SimplexMesh& mesh,
  const MetricField& metric,
  const SiteSet& sites)
{
  CheckMesh(mesh, "InterpolateMetricAtSites");
  CheckMetric(mesh, metric, "InterpolateMetricAtSites");
  const std::size_t ns = sites.NumSites();
  if (sites.Bary.size() != 4 * ns)
    throw InputError("InterpolateMetricAtSites: sites need 4 barycentric weights each");
  const auto nc = static_cast<std::int64_t>(mesh.NumCells());
  for (auto c : sites.CellIds)
    if (c < 0 || c >= nc)
      throw InputError("InterpolateMetricAtSites: site cell id " + std::to_string(c) +
        " is not a cell of the mesh");
  MetricField out;
  out.Values.assign(6 * ns, 0.0);
  // Surfaces: rank-2 vertex metrics are moved into the cell's plane first, so that the
  // interpolated one is rank 2 in that plane (a plain mean of tilted ones is not).
  const std::vector<Eigen::Vector3d> normals = mesh.AmbientDim == 3 && mesh.SimplexDim == 2
    ? SurfaceMetricNormals(metric)
    : std::vector<Eigen::Vector3d>();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, ns),
    [&](const tbb::blocked_range<std::size_t>& r)
    {
      for (std::size_t s = r.begin(); s != r.end(); ++s)
        InterpolateMetricInCell(
          mesh, metric, normals, sites.CellIds[s], sites.Bary.data() + 4 * s, out.Values.data() + 6 * s);
    });
  return out;
}

void InterpolateMetricInCell(const SimplexMesh& mesh,
  const MetricField& metric,
  const std::vector<Eigen::Vector3d>& normals,
  std::int32_t cell,
  const double* lambda,
  double* out)
{
  const std::int32_t* ids = mesh.Cell(static_cast<std::size_t>(cell));
  Eigen::Vector3d faceNormal = Eigen::Vector3d::Zero();
  if (!normals.empty())
  {
    faceNormal = (PointOf(mesh, ids[1]) - PointOf(mesh, ids[0]))
                   .cross(PointOf(mesh, ids[2]) - PointOf(mesh, ids[0]));
  }
  const double fn = faceNormal.norm();
  for (int j = 0; j < 6; ++j)
    out[j] = 0.0;
  for (int i = 0; i <= mesh.SimplexDim; ++i)
  {
    const auto v = static_cast<std::size_t>(ids[i]);
    double moved[6];
    const double* m = metric.At(v);
    if (fn > 0.0)
    {
      PackSymmetric(MoveSurfaceMetric(UnpackSymmetric(m), normals[v], faceNormal / fn), moved);
      m = moved;
    }
    for (int j = 0; j < 6; ++j)
      out[j] += lambda[i] * m[j];
  }
}

} // namespace av
