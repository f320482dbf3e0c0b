// SPDX-License-Identifier: BSD-3-Clause
// EmbeddingSolver setup: input validation, element operators, mesh topology, initial state.
#include "EmbeddingSolverInternals.h"

#include "EdgeLengthError.h"
#include "MeshTopology.h"
#include "MetricAlgebra.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <random>
#include <string>

namespace av
{

namespace
{
/// Largest factor by which an edge-length metric may scale a squared length against the vertex
/// mean. Beyond it the edge lengths hardly describe one simplex (a folded metric simplex, near a
/// Cayley-Menger zero, or a metric that turns within the element), and the element blends back
/// towards the mean. 4 measured best of {2, 4, 16} with clamping or a hard fall-back to the mean
/// (Filters/Embedding/README.md).
constexpr double kEdgeMetricMaxRatio = 4.0;

/// EmbeddingElementMetric::EdgeLengths: the metric g (m x m; rank k on surfaces, zero along the
/// normal) with w^T g w = ℓ(a, b)^2 for every edge w = b - a of the element, from the Gram
/// matrix H of the edges at vertex 0 in the §5.1 lengths (polarization). wm: the edge vectors at
/// vertex 0 (m x k), wp its pseudo-inverse (k x m). When the generalized eigenvalues of H against
/// the vertex mean's Gram matrix Hm leave [1/r, r] (r = kEdgeMetricMaxRatio), H is replaced by
/// the blend (1 - t) Hm + t H with the largest t that brings them back into range, and the result
/// is false (counted). A blend, not a clamp per eigenvalue: it keeps the element's shape changing
/// continuously with its edge lengths. metric: in, the vertex mean; out, g. Kept (and false)
/// when the mean is singular or a length is NaN.
template <typename WP>
bool EdgeLengthMetric(const SimplexMesh& mesh, const std::int32_t* cell, int k,
  const Eigen::Matrix3d& wm, const WP& wp, const std::vector<Eigen::Matrix3d>& roots,
  Eigen::Matrix3d& metric)
{
  const int m = mesh.AmbientDim;
  auto length2 = [&](int la, int lb) { return MetricEdgeLength2(mesh, roots, cell[la], cell[lb]); };
  Eigen::Matrix3d h = Eigen::Matrix3d::Identity(); // k x k used; identity pads k = 2
  for (int l = 0; l < k; ++l)
  {
    h(l, l) = length2(0, l + 1);
  }
  for (int l = 0; l < k; ++l)
  {
    for (int q = l + 1; q < k; ++q)
    {
      h(l, q) = h(q, l) = 0.5 * (h(l, l) + h(q, q) - length2(l + 1, q + 1));
    }
  }
  // The same Gram matrix in the vertex mean, and the generalized eigenvalues of the pair.
  Eigen::Matrix3d hm = Eigen::Matrix3d::Identity();
  hm.topLeftCorner(k, k) = wm.topLeftCorner(m, k).transpose() * metric.topLeftCorner(m, m) *
    wm.topLeftCorner(m, k);
  const Eigen::LLT<Eigen::Matrix3d> llt(hm);
  if (llt.info() != Eigen::Success)
  {
    return false;
  }
  const Eigen::Matrix3d linv = llt.matrixL().solve(Eigen::Matrix3d::Identity());
  const SymmetricEigen3 ratio = EigenDecompose(Eigen::Matrix3d(linv * h * linv.transpose()));
  const double lo = ratio.Values.minCoeff(), hi = ratio.Values.maxCoeff();
  const double r = kEdgeMetricMaxRatio;
  double t = 1.0;
  if (lo < 1.0 / r)
  {
    t = std::min(t, (1.0 - 1.0 / r) / (1.0 - lo));
  }
  if (hi > r)
  {
    t = std::min(t, (r - 1.0) / (hi - 1.0));
  }
  if (!(t >= 0.0)) // NaN lengths: keep the mean
  {
    return false;
  }
  // Generalized eigenvalues of the blend are (1 - t) + t * lambda: inside [1/r, r] by the t above.
  h = (1.0 - t) * hm + t * h;
  metric.setZero();
  metric.topLeftCorner(m, m) = wp.transpose() * h.topLeftCorner(k, k) * wp;
  metric = 0.5 * (metric + metric.transpose()).eval();
  return t == 1.0;
}

/// Dimensions, sizes, options, finite points and point ids in range.
void ValidateSizesAndOptions(
  const SimplexMesh& mesh, const MetricField& metric, const EmbeddingOptions& o)
{
  if (!((mesh.AmbientDim == 2 && mesh.SimplexDim == 2) ||
        (mesh.AmbientDim == 3 && (mesh.SimplexDim == 3 || mesh.SimplexDim == 2))))
  {
    throw InputError("embedding: unsupported mesh (AmbientDim " + std::to_string(mesh.AmbientDim) +
      ", SimplexDim " + std::to_string(mesh.SimplexDim) +
      "); expected a 2D triangle mesh, a 3D tetrahedral mesh or a triangle surface in 3D");
  }
  if (mesh.NumPoints() == 0 || mesh.NumCells() == 0)
  {
    throw InputError("embedding: the input mesh is empty (" + std::to_string(mesh.NumPoints()) +
      " points, " + std::to_string(mesh.NumCells()) + " cells)");
  }
  if (mesh.Points.size() != mesh.NumPoints() * mesh.AmbientDim ||
    mesh.Cells.size() != mesh.NumCells() * mesh.VerticesPerCell())
  {
    throw InputError("embedding: point or cell array size is not a multiple of its tuple size");
  }
  if (mesh.NumPoints() > static_cast<std::size_t>(INT32_MAX / 64))
  {
    throw InputError("embedding: mesh too large");
  }
  if (o.TargetDim < mesh.AmbientDim + 1 || o.TargetDim > kEmbeddingMaxTargetDim)
  {
    throw InputError("embedding: target dimension " + std::to_string(o.TargetDim) +
      " out of range; it must be in [" + std::to_string(mesh.AmbientDim + 1) + ", " +
      std::to_string(kEmbeddingMaxTargetDim) + "] for a mesh in " +
      std::to_string(mesh.AmbientDim) + "D");
  }
  if (o.Iterations < 0 || !(o.Mu >= 0.0) || !std::isfinite(o.Mu) || o.AndersonWindow < 0 ||
    o.AndersonWindow > 50 || !(o.RelativeEnergyTolerance >= 0.0) ||
    !std::isfinite(o.InitialAmplitude) || o.MaxIterations < 0 ||
    !(o.ConvergenceTolerance >= 0.0) || !(o.TargetAverageErrorPercent >= 0.0) || !(o.IterativeTolerance > 0.0 && o.IterativeTolerance < 1.0) ||
    !(o.DirectSwitchCgIterations >= 0.0 && o.DirectSwitchCgIterations <= 1e6))
  {
    throw InputError("embedding: invalid options (need Iterations >= 0, MaxIterations >= 0, "
                     "finite Mu >= 0, AndersonWindow in [0, 50], RelativeEnergyTolerance >= 0, "
                     "ConvergenceTolerance >= 0, TargetAverageErrorPercent >= 0, "
                     "IterativeTolerance in (0, 1), DirectSwitchCgIterations in [0, 1e6])");
  }
  if (metric.Values.size() != 6 * mesh.NumPoints())
  {
    throw InputError("embedding: metric has " + std::to_string(metric.Values.size()) +
      " values; expected 6 per point (" + std::to_string(6 * mesh.NumPoints()) + ")");
  }
  if (!AllFinite(mesh.Points.data(), static_cast<int>(mesh.Points.size())))
  {
    throw InputError("embedding: the input points contain NaN or Inf");
  }
  const std::int32_t np = static_cast<std::int32_t>(mesh.NumPoints());
  for (std::int32_t id : mesh.Cells)
  {
    if (id < 0 || id >= np)
    {
      throw InputError("embedding: cell refers to point " + std::to_string(id) + ", mesh has " +
        std::to_string(np) + " points");
    }
  }
}

/// Metric: finite, SPD (volumes, 2D) or PSD (surfaces). Reports the first bad vertex.
void ValidateMetric(const SimplexMesh& mesh, const MetricField& metric)
{
  for (std::size_t i = 0; i < mesh.NumPoints(); ++i)
  {
    const double* v = metric.At(i);
    if (!AllFinite(v, 6))
    {
      throw InputError("embedding: metric at point " + std::to_string(i) + " contains NaN or Inf");
    }
    bool ok;
    if (mesh.AmbientDim == 2)
    {
      ok = IsPositiveDefinite(UnpackSymmetric2(v));
    }
    else if (mesh.SimplexDim == 3)
    {
      ok = IsPositiveDefinite(UnpackSymmetric(v));
    }
    else
    {
      ok = IsPositiveSemiDefinite(UnpackSymmetric(v));
    }
    if (!ok)
    {
      throw InputError("embedding: metric at point " + std::to_string(i) + " is not " +
        (mesh.SimplexDim == 2 && mesh.AmbientDim == 3 ? "positive semi-definite"
                                                      : "symmetric positive definite") +
        "; convert/clamp the tensor field into a metric first");
    }
  }
}

/// Squared length of the longest edge of a cell (the scale of the degeneracy test).
double LongestEdgeSquared(const SimplexMesh& mesh, const std::int32_t* cell)
{
  double h2 = 0.0;
  for (int a = 0; a < mesh.VerticesPerCell(); ++a)
  {
    for (int b = a + 1; b < mesh.VerticesPerCell(); ++b)
    {
      double s = 0.0;
      for (int d = 0; d < mesh.AmbientDim; ++d)
      {
        const double e = mesh.Point(cell[b])[d] - mesh.Point(cell[a])[d];
        s += e * e;
      }
      h2 = std::max(h2, s);
    }
  }
  return h2;
}

/// Elements: non-degenerate, and (volumes, 2D) consistently oriented.
void ValidateCells(const SimplexMesh& mesh)
{
  std::size_t positive = 0, negative = 0, firstNeg = 0, firstPos = 0;
  for (std::size_t c = 0; c < mesh.NumCells(); ++c)
  {
    const double h2 = LongestEdgeSquared(mesh, mesh.Cell(c));
    const double meas = CellMeasure(mesh, c);
    const double scale = mesh.SimplexDim == 3 ? h2 * std::sqrt(h2) : h2;
    if (!(std::abs(meas) > 1e-12 * scale))
    {
      throw InputError("embedding: cell " + std::to_string(c) +
        " is degenerate (zero or near-zero " + (mesh.SimplexDim == 3 ? "volume" : "area") +
        "; repeated or collinear/coplanar vertices)");
    }
    if (meas > 0)
    {
      if (positive++ == 0)
      {
        firstPos = c;
      }
    }
    else if (negative++ == 0)
    {
      firstNeg = c;
    }
  }
  if (positive > 0 && negative > 0)
  {
    const std::size_t bad = positive >= negative ? firstNeg : firstPos;
    throw InputError("embedding: cell " + std::to_string(bad) + " is inverted (" +
      std::to_string(std::min(positive, negative)) + " of " + std::to_string(mesh.NumCells()) +
      " cells have the opposite orientation of the others)");
  }
}

/// Vertex -> smallest vertex of its connected component (union-find over the cells).
std::vector<std::int32_t> ComponentRoots(
  const std::vector<std::int32_t>& cells, int nv, std::size_t np, std::size_t ne)
{
  std::vector<std::int32_t> parent(np);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](std::int32_t x) {
    while (parent[x] != x)
    {
      parent[x] = parent[parent[x]];
      x = parent[x];
    }
    return x;
  };
  for (std::size_t j = 0; j < ne; ++j)
  {
    const std::int32_t r0 = find(cells[j * nv]);
    for (int l = 1; l < nv; ++l)
    {
      const std::int32_t r = find(cells[j * nv + l]);
      if (r != r0)
      {
        parent[std::max(r, r0)] = std::min(r, r0);
      }
    }
  }
  std::vector<std::int32_t> root(np);
  for (std::size_t i = 0; i < np; ++i)
  {
    root[i] = find(static_cast<std::int32_t>(i));
  }
  return root;
}

/// CSR offsets (n + 1) of the ids in `ids`: off[v + 1] - off[v] = occurrences of v.
std::vector<std::int32_t> CountOffsets(const std::vector<std::int32_t>& ids, std::size_t n)
{
  std::vector<std::int32_t> off(n + 1, 0);
  for (std::int32_t v : ids)
  {
    ++off[v + 1];
  }
  std::partial_sum(off.begin(), off.end(), off.begin());
  return off;
}

/// Per free dimension: sum of 3 plane waves, random direction, 0.25..1 periods over the
/// domain, random phase and weight; column m + f of x (row stride mb).
void SmoothInitialField(const SimplexMesh& mesh, int mb, int nfree, const double* lo, double ext,
  double amp, std::mt19937_64& rng, std::vector<double>& x)
{
  const int m = mesh.AmbientDim;
  const std::size_t np = mesh.NumPoints();
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  constexpr int nw = 3;
  const double pi = 3.14159265358979323846;
  for (int f = 0; f < nfree; ++f)
  {
    double dir[nw][3], phase[nw], wt[nw];
    for (int w = 0; w < nw; ++w)
    {
      double n2 = 0.0;
      do
      {
        n2 = 0.0;
        for (int d = 0; d < 3; ++d)
        {
          dir[w][d] = d < m ? uni(rng) : 0.0;
          n2 += dir[w][d] * dir[w][d];
        }
      } while (n2 < 1e-4 || n2 > 1.0);
      const double freq = 2.0 * pi * (0.25 + 0.375 * (uni(rng) + 1.0)) / (ext * std::sqrt(n2));
      for (int d = 0; d < 3; ++d)
      {
        dir[w][d] *= freq;
      }
      phase[w] = pi * uni(rng);
      wt[w] = uni(rng);
    }
    for (std::size_t i = 0; i < np; ++i)
    {
      double s = 0.0;
      for (int w = 0; w < nw; ++w)
      {
        double arg = phase[w];
        for (int d = 0; d < m; ++d)
        {
          arg += dir[w][d] * (mesh.Point(i)[d] - lo[d]);
        }
        s += wt[w] * std::sin(arg);
      }
      x[i * mb + m + f] = amp * s;
    }
  }
}
} // namespace

void EmbeddingSolver::Internals::Validate(const SimplexMesh& mesh, const MetricField& metric)
{
  ValidateSizesAndOptions(mesh, metric, this->Options);
  ValidateMetric(mesh, metric);
  ValidateCells(mesh);
}

void EmbeddingSolver::Internals::BuildElements(const SimplexMesh& mesh, const MetricField& metric)
{
  const int m = this->M, k = this->K, nv = k + 1;
  this->Cells = mesh.Cells;
  this->Gt.assign(this->NE * nv * m, 0.0);
  this->A.assign(this->NE * m * m, 0.0);
  this->W.assign(this->NE, 1.0);
  std::vector<double> measure(this->NE);
  const bool edgeLengths = this->Options.ElementMetric == EmbeddingElementMetric::EdgeLengths;
  std::vector<Eigen::Matrix3d> vertexRoots;
  if (edgeLengths)
  {
    vertexRoots = VertexMetricRoots(metric, m);
  }
  // Surfaces: each vertex metric is moved into the triangle's plane before the mean (a rim
  // vertex's tangent plane can be nearly normal to its long CAD triangles).
  std::vector<Eigen::Vector3d> normals;
  if (m == 3 && k == 2 && !edgeLengths)
  {
    normals = SurfaceMetricNormals(metric);
  }
  tbb::enumerable_thread_specific<std::size_t> fallbacks(0);
  tbb::parallel_for(std::size_t(0), this->NE, [&](std::size_t j) {
    const std::int32_t* cell = mesh.Cell(j);
    // W = edge vectors (m x k); W+ = pseudo-inverse (k x m); Gt = D W+ with D the (k+1) x k
    // difference operator (row 0 = -1, row l = e_l).
    Eigen::Matrix3d wm = Eigen::Matrix3d::Zero();
    for (int l = 0; l < k; ++l)
    {
      for (int d = 0; d < m; ++d)
      {
        wm(d, l) = mesh.Point(cell[l + 1])[d] - mesh.Point(cell[0])[d];
      }
    }
    using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3>; // no heap
    Small wp; // k x m
    if (k == m)
    {
      wp = Small(wm.topLeftCorner(m, m)).inverse();
    }
    else
    {
      const Small w = wm.topLeftCorner(m, k);
      const Small wtw = w.transpose() * w;
      wp = wtw.inverse() * w.transpose();
    }
    double* g = this->Gt.data() + j * nv * m;
    for (int d = 0; d < m; ++d)
    {
      double s = 0.0;
      for (int l = 0; l < k; ++l)
      {
        g[(l + 1) * m + d] = wp(l, d);
        s += wp(l, d);
      }
      g[d] = -s;
    }
    // Element metric: average of the vertex metrics (or, EdgeLengths, the metric of the edges'
    // §5.1 lengths); A = its symmetric square root.
    Eigen::Matrix3d mm = Eigen::Matrix3d::Zero();
    const Eigen::Vector3d faceNormal = normals.empty()
      ? Eigen::Vector3d::Zero()
      : Eigen::Vector3d(wm.col(0).cross(wm.col(1)).normalized());
    for (int l = 0; l < nv; ++l)
    {
      if (m == 2)
      {
        mm.topLeftCorner<2, 2>() += UnpackSymmetric2(metric.At(cell[l]));
      }
      else if (!normals.empty())
      {
        mm += MoveSurfaceMetric(UnpackSymmetric(metric.At(cell[l])), normals[cell[l]], faceNormal);
      }
      else
      {
        mm += UnpackSymmetric(metric.At(cell[l]));
      }
    }
    mm /= nv;
    if (edgeLengths && !EdgeLengthMetric(mesh, cell, k, wm, wp, vertexRoots, mm))
    {
      fallbacks.local() += 1;
    }
    double* a = this->A.data() + j * m * m;
    if (m == 2)
    {
      Eigen::Map<Eigen::Matrix2d> am(a);
      am = SymmetricSqrt(Eigen::Matrix2d(mm.topLeftCorner<2, 2>()));
    }
    else
    {
      Eigen::Map<Eigen::Matrix3d> am(a);
      am = SymmetricSqrt(mm);
    }
    measure[j] = std::abs(CellMeasure(mesh, j));
  });
  this->ElementMetricFallbacks = fallbacks.combine(std::plus<std::size_t>());
  if (this->Options.ElementMeasureWeighting)
  {
    const double mean = std::accumulate(measure.begin(), measure.end(), 0.0) / this->NE;
    for (std::size_t j = 0; j < this->NE; ++j)
    {
      this->W[j] = measure[j] / mean;
    }
  }
}

void EmbeddingSolver::Internals::BuildTopology(const SimplexMesh& mesh)
{
  const int nv = this->K + 1;
  const std::size_t np = this->NP;
  // Vertex -> incident (element, local vertex).
  this->VOff = CountOffsets(this->Cells, np);
  this->VInc.resize(this->Cells.size());
  {
    std::vector<std::int32_t> fill(this->VOff.begin(), this->VOff.end() - 1);
    for (std::size_t i = 0; i < this->Cells.size(); ++i)
    {
      this->VInc[fill[this->Cells[i]]++] = static_cast<std::int32_t>(i); // i = j * nv + l
    }
  }
  // One-ring neighbors from the unique edges.
  const std::vector<std::int32_t> edges = UniqueEdges(mesh);
  this->NOff = CountOffsets(edges, np);
  this->NIdx.resize(edges.size());
  {
    std::vector<std::int32_t> fill(this->NOff.begin(), this->NOff.end() - 1);
    for (std::size_t e = 0; e < edges.size(); e += 2)
    {
      this->NIdx[fill[edges[e]]++] = edges[e + 1];
      this->NIdx[fill[edges[e + 1]]++] = edges[e];
    }
  }
  for (std::size_t i = 0; i < np; ++i)
  {
    std::sort(this->NIdx.begin() + this->NOff[i], this->NIdx.begin() + this->NOff[i + 1]);
  }
  const std::vector<char> boundary = BoundaryVertexMask(mesh);
  this->Interior.resize(np);
  for (std::size_t i = 0; i < np; ++i)
  {
    this->Interior[i] = !boundary[i] && this->NOff[i + 1] > this->NOff[i];
  }
  // Connected components: pin the first vertex of each one, which removes the constant null
  // space of every free dimension (the paper fixes v_1).
  this->Pinned = ComponentRoots(this->Cells, nv, np, this->NE);
  this->Reduced.assign(np, -1);
  std::int32_t next = 0;
  for (std::size_t i = 0; i < np; ++i)
  {
    // The root of a component is its smallest vertex id: pin it.
    if (this->Pinned[i] != static_cast<std::int32_t>(i))
    {
      this->Reduced[i] = next++;
    }
  }
  this->NR = static_cast<std::size_t>(next);
}

void EmbeddingSolver::Internals::InitializeState(const SimplexMesh& mesh)
{
  const int m = this->M, mb = this->MB;
  const std::size_t np = this->NP;
  this->X.assign(np * mb, 0.0);
  for (std::size_t i = 0; i < np; ++i)
  {
    for (int d = 0; d < m; ++d)
    {
      this->X[i * mb + d] = mesh.Point(i)[d];
    }
  }
  double lo[3], hi[3], ext = 0.0;
  PointBounds(mesh, lo, hi);
  for (int d = 0; d < m; ++d)
  {
    ext = std::max(ext, hi[d] - lo[d]);
  }
  const bool smooth = this->Options.Initialization != EmbeddingInitialization::Random;
  const double amp = ext *
    (this->Options.InitialAmplitude > 0.0 ? this->Options.InitialAmplitude : (smooth ? 0.2 : 1e-3));
  std::mt19937_64 rng(this->Options.Seed);
  if (smooth)
  {
    SmoothInitialField(mesh, mb, this->F, lo, ext, amp, rng, this->X);
  }
  else
  {
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    for (std::size_t i = 0; i < np; ++i)
    {
      for (int f = 0; f < this->F; ++f)
      {
        this->X[i * mb + m + f] = amp * uni(rng);
      }
    }
  }
  // Shift each component so that its pinned vertex sits at 0 in the free dimensions (constants
  // do not change the energy; the reduced system then needs no pinned-value correction).
  for (std::size_t i = np; i-- > 0;)
  {
    const std::size_t p = static_cast<std::size_t>(this->Pinned[i]);
    if (p != i)
    {
      for (int f = 0; f < this->F; ++f)
      {
        this->X[i * mb + m + f] -= this->X[p * mb + m + f];
      }
    }
  }
  for (std::size_t i = 0; i < np; ++i)
  {
    if (static_cast<std::size_t>(this->Pinned[i]) == i)
    {
      for (int f = 0; f < this->F; ++f)
      {
        this->X[i * mb + m + f] = 0.0;
      }
    }
  }
  this->C.assign(this->NE * (this->K + 1) * this->F, 0.0);
}

} // namespace av
