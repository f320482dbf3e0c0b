#include "ParticleSampler.h"
#include "MeshTopology.h"
#include "SimdClones.h"

#include "FeatureSites.h"
#include "SharpFeatures.h"

#include <Eigen/Dense>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <memory>
#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <string>
#include <cstdlib>
#include <cstring>

namespace av
{
namespace
{
// Side of the cells of a uniform grid over the box [lo, hi] (3 projected coordinates) for
// searches of radius r among `count` points: a bit over r, so neighbours are in adjacent
// cells despite round-off, coarsened while the grid would have more than 4 count + 64 cells
// (far-apart clusters: still exact). Writes the cell counts per axis.
double GridCellSide(const double lo[3], const double hi[3], double r, std::size_t count,
  long long cellsPerAxis[3])
{
  double extent = 0.0;
  for (int a = 0; a < 3; ++a)
    extent = std::max(extent, hi[a] - lo[a]);
  double h = std::max(r * (1.0 + 1e-6), 1e-12 * extent + 1e-300);
  for (;;)
  {
    long long cells = 1;
    for (int a = 0; a < 3; ++a)
    {
      cellsPerAxis[a] = static_cast<long long>((hi[a] - lo[a]) / h) + 1;
      cells *= cellsPerAxis[a];
    }
    if (cells <= 4 * static_cast<long long>(count) + 64)
      return h;
    h *= 1.5;
  }
}
constexpr int kMaxDim = 20;

/// exp(x) for x in [-700, 0], within a few ulp of std::exp; inline and branch-free so that
/// loops over it vectorise (glibc's exp is a call per value).
inline double ExpNonPositive(double x)
{
  // k = round(x / ln 2) by the 1.5 * 2^52 trick: the low bits of t hold k.
  const double magic = 0x1.8p52;
  const double t = x * 1.4426950408889634 + magic;
  const double k = t - magic;
  const double r = (x - k * 0x1.62e42fefa39efp-1) - k * 0x1.abc9e3b39803fp-56; // |r| <= ln2 / 2
  // Taylor series to degree 13 (truncation error < 1e-17 relative).
  double p = 1.0 / 6227020800.0;
  p = p * r + 1.0 / 479001600.0;
  p = p * r + 1.0 / 39916800.0;
  p = p * r + 1.0 / 3628800.0;
  p = p * r + 1.0 / 362880.0;
  p = p * r + 1.0 / 40320.0;
  p = p * r + 1.0 / 5040.0;
  p = p * r + 1.0 / 720.0;
  p = p * r + 1.0 / 120.0;
  p = p * r + 1.0 / 24.0;
  p = p * r + 1.0 / 6.0;
  p = p * r + 0.5;
  p = p * r + 1.0;
  p = p * r + 1.0;
  std::uint64_t bits;
  std::memcpy(&bits, &t, sizeof bits);
  bits = (bits + 1023) << 52; // 2^k (k >= -1010: a normal number)
  double scale;
  std::memcpy(&scale, &bits, sizeof scale);
  return p * scale;
}

constexpr std::size_t kExpChunk = 32;

/**
 * w[j] = exp(-d2[j] * inv4s2) where d2[j] < rc2, else 0 (j < m <= kExpChunk; d2 >= 0).
 * The comparisons are on the bit patterns (ordered like the values for non-negative
 * doubles): floating-point selects would keep GCC from vectorising the loop.
 */
AV_SIMD_CLONES void GaussianKernel(
  const double* d2, double* w, std::size_t m, double inv4s2, double rc2)
{
  const double clampD2 = std::min(rc2, 700.0 / inv4s2); // exp's argument stays >= -700
  std::int64_t bRc2, bClamp;
  std::memcpy(&bRc2, &rc2, sizeof bRc2);
  std::memcpy(&bClamp, &clampD2, sizeof bClamp);
  for (std::size_t j = 0; j < m; ++j)
  {
    std::int64_t b;
    std::memcpy(&b, d2 + j, sizeof b);
    const std::uint64_t keep = b < bRc2 ? ~0ull : 0ull;
    b = std::min(b, bClamp);
    double d;
    std::memcpy(&d, &b, sizeof d);
    const double v = ExpNonPositive(-d * inv4s2);
    std::uint64_t vb;
    std::memcpy(&vb, &v, sizeof vb);
    vb &= keep;
    std::memcpy(w + j, &vb, sizeof vb);
  }
}

void CheckInputs(const SimplexMesh& mesh, const Embedding& emb)
{
  if (mesh.SimplexDim != 2 && mesh.SimplexDim != 3)
    throw InputError("SampleParticles: only triangles (SimplexDim 2) and tetrahedra (3)");
  if (mesh.AmbientDim < 2 || mesh.AmbientDim > 3)
    throw InputError("SampleParticles: AmbientDim must be 2 or 3");
  if (mesh.Points.size() % static_cast<std::size_t>(mesh.AmbientDim) != 0 ||
    mesh.Cells.size() % static_cast<std::size_t>(mesh.SimplexDim + 1) != 0)
    throw InputError("SampleParticles: Points/Cells array sizes are not multiples of the "
                     "dimension");
  if (mesh.NumCells() == 0)
    throw InputError("SampleParticles: the mesh has no cells");
  const int lo = std::max(mesh.AmbientDim, mesh.SimplexDim);
  if (emb.Dim < lo || emb.Dim > kMaxDim)
    throw InputError("SampleParticles: embedding dimension " + std::to_string(emb.Dim) +
      " is outside [" + std::to_string(lo) + ", " + std::to_string(kMaxDim) + "]");
  if (emb.Coords.size() != mesh.NumPoints() * static_cast<std::size_t>(emb.Dim))
    throw InputError("SampleParticles: the embedding has " +
      std::to_string(emb.Coords.size()) + " values, expected NumPoints (" +
      std::to_string(mesh.NumPoints()) + ") x Dim (" + std::to_string(emb.Dim) + ")");
  for (double x : emb.Coords)
    if (!std::isfinite(x))
      throw InputError("SampleParticles: the embedding contains NaN or Inf");
  const auto np = static_cast<std::int64_t>(mesh.NumPoints());
  for (auto id : mesh.Cells)
    if (id < 0 || id >= np)
      throw InputError("SampleParticles: cell refers to point id " + std::to_string(id) +
        " outside [0, " + std::to_string(np) + ")");
}

/// Portable uniform double in [0,1) (std distributions differ between standard libraries).
struct Rng
{
  std::uint64_t State;
  explicit Rng(std::uint64_t seed)
    : State(seed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull)
  {
  }
  std::uint64_t Next() // splitmix64
  {
    std::uint64_t z = (State += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double Uniform() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }
};

/// Vertex -> incident cells (CSR); faces are matched by intersecting these short lists.
struct VertexCells
{
  std::vector<std::int64_t> Offs;
  std::vector<std::int32_t> Inc;
};

VertexCells BuildVertexCells(const SimplexMesh& mesh)
{
  const std::size_t nc = mesh.NumCells(), np = mesh.NumPoints();
  const int nv = mesh.VerticesPerCell();
  VertexCells vc;
  vc.Offs.assign(np + 1, 0);
  for (auto v : mesh.Cells)
    ++vc.Offs[static_cast<std::size_t>(v) + 1];
  for (std::size_t i = 0; i < np; ++i)
    vc.Offs[i + 1] += vc.Offs[i];
  vc.Inc.resize(mesh.Cells.size());
  std::vector<std::int64_t> fill(vc.Offs.begin(), vc.Offs.end() - 1);
  for (std::size_t c = 0; c < nc; ++c)
    for (int i = 0; i < nv; ++i)
      vc.Inc[static_cast<std::size_t>(fill[static_cast<std::size_t>(mesh.Cell(c)[i])]++)] =
        static_cast<std::int32_t>(c);
  return vc;
}

/// The cell across the face of cell c opposite its local vertex i (-1: boundary, or more
/// than two cells share the face).
std::int32_t FaceNeighbour(const SimplexMesh& mesh, const VertexCells& vc, std::size_t c, int i)
{
  const int nv = mesh.VerticesPerCell();
  const std::int32_t* ids = mesh.Cell(c);
  const auto& offs = vc.Offs;
  std::int32_t face[3] = { 0, 0, 0 };
  int nfv = 0;
  for (int j = 0; j < nv; ++j)
    if (j != i)
      face[nfv++] = ids[j];
  // Scan the shortest incidence list among the face's vertices.
  for (int a = 1; a < nfv; ++a)
  {
    const auto va = static_cast<std::size_t>(face[a]);
    const auto v0 = static_cast<std::size_t>(face[0]);
    if (offs[va + 1] - offs[va] < offs[v0 + 1] - offs[v0])
      std::swap(face[0], face[a]);
  }
  std::int32_t found = -1;
  int count = 0;
  const auto v0 = static_cast<std::size_t>(face[0]);
  for (auto k = offs[v0]; k < offs[v0 + 1]; ++k)
  {
    const std::int32_t other = vc.Inc[static_cast<std::size_t>(k)];
    if (other == static_cast<std::int32_t>(c))
      continue;
    const std::int32_t* oids = mesh.Cell(static_cast<std::size_t>(other));
    bool all = true;
    for (int a = 1; a < nfv && all; ++a)
      all = std::find(oids, oids + nv, face[a]) != oids + nv;
    if (all)
    {
      found = other;
      ++count;
    }
  }
  return count == 1 ? found : -1;
}

/// a . b with four interleaved partial sums (a single running sum is one add latency per
/// value; the fixed order keeps the result independent of the thread count).
inline double Dot(const double* a, const double* b, std::size_t n)
{
  double acc[4] = { 0.0, 0.0, 0.0, 0.0 };
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4)
    for (std::size_t k = 0; k < 4; ++k)
      acc[k] += a[i + k] * b[i + k];
  for (; i < n; ++i)
    acc[0] += a[i] * b[i];
  return (acc[0] + acc[1]) + (acc[2] + acc[3]);
}

/**
 * The optimiser for a compile-time embedding dimension D (Eigen::Dynamic: runtime, stack
 * storage up to kMaxDim) and simplex dimension K.
 */
template <int D, int K>
class Sampler
{
  static constexpr int MaxD = D == Eigen::Dynamic ? kMaxDim : D;
  static constexpr int NV = K + 1;
  using Vec = Eigen::Matrix<double, D, 1, Eigen::ColMajor, MaxD, 1>;
  using Edges = Eigen::Matrix<double, D, Eigen::Dynamic, Eigen::ColMajor, MaxD, K>;
  using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, K, K>;
  using SmallVec = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, K, 1>;

  /**
   * Per-particle copy of the data of one cell: the embedded vertices, face neighbours, the
   * degeneracy flag and the inverse Gram matrix of the full cell. Every particle keeps two
   * (its accepted cell and the trial cell of the line search): the hot loops then read this
   * contiguous per-particle record instead of gathering cell ids, neighbours and vertices
   * from three mesh-sized tables (L2 misses dominated the tangent projections).
   */
  struct CellData
  {
    std::int32_t Cell = -1;
    std::int32_t Ids[NV];
    std::int32_t Nbrs[NV];
    bool Degenerate = false;
    bool InverseOk = false;   ///< Gram matrix of the full cell invertible (det > 0, finite)
    Eigen::Matrix3d GramInv = Eigen::Matrix3d::Identity(); ///< of the K edges v_j - v_0
    double V[NV][MaxD] = {};
  };

public:
  Sampler(const SimplexMesh& mesh, const Embedding& emb, const VertexCells& vc,
    const SharpFeatures* features)
    : Mesh(mesh)
    , Emb(emb)
    , VC(vc)
    , Features(features)
    , Dim(emb.Dim)
    , NbrMemo(new std::atomic<std::int32_t>[mesh.NumCells() * NV])
  {
    for (std::size_t i = 0, e = mesh.NumCells() * NV; i < e; ++i)
      NbrMemo[i].store(kUnknown, std::memory_order_relaxed);
  }

  Eigen::Map<const Vec> Vertex(const CellData& cd, int i) const
  {
    return Eigen::Map<const Vec>(cd.V[i], Dim);
  }

  /// Copies cell `cell` into `cd` (degeneracy and the full-cell inverse computed here, only
  /// for the cells particles visit).
  void Fill(std::int32_t cell, CellData& cd) const
  {
    const std::int32_t* ids = Mesh.Cell(static_cast<std::size_t>(cell));
    cd.Cell = cell;
    for (int i = 0; i < NV; ++i)
    {
      cd.Ids[i] = ids[i];
      // Face neighbours only of the cells particles visit (all 240k of cube2 took 8% of the
      // run), memoised: a cell is refilled often. Concurrent fills store the same value.
      auto& memo = NbrMemo[static_cast<std::size_t>(cell) * NV + static_cast<std::size_t>(i)];
      std::int32_t nb = memo.load(std::memory_order_relaxed);
      if (nb == kUnknown)
      {
        nb = FaceNeighbour(Mesh, VC, static_cast<std::size_t>(cell), i);
        memo.store(nb, std::memory_order_relaxed);
      }
      cd.Nbrs[i] = nb;
      std::copy_n(Emb.At(static_cast<std::size_t>(ids[i])), Dim, cd.V[i]);
    }
    {
      Eigen::Matrix<double, D, K, Eigen::ColMajor, MaxD, K> e(Dim, K);
      for (int j = 0; j < K; ++j)
        e.col(j) = Vertex(cd, j + 1) - Vertex(cd, 0);
      const Eigen::Matrix<double, K, K> g = e.transpose() * e;
      cd.Degenerate = !(g.determinant() > 1e-14 * std::pow(g.trace() / K, K));
    }
    cd.InverseOk = false;
    if (cd.Degenerate)
      return;
    Vec e[3];
    for (int j = 0; j < K; ++j)
      e[j] = Vertex(cd, j + 1) - Vertex(cd, 0);
    cd.InverseOk = PaddedGramInverse(e, K, cd.GramInv);
  }

  /// Inverse of the Gram matrix of the m edges e[0..m-1], padded to 3x3 with the identity;
  /// false when it is singular or not finite.
  static bool PaddedGramInverse(const Vec* e, int m, Eigen::Matrix3d& inverse)
  {
    Eigen::Matrix3d g = Eigen::Matrix3d::Identity();
    for (int i = 0; i < m; ++i)
      for (int j = 0; j <= i; ++j)
        g(i, j) = g(j, i) = e[i].dot(e[j]);
    const double det = g.determinant();
    if (!(det > 0.0) || !std::isfinite(det))
      return false;
    inverse = g.inverse();
    return true;
  }

  /// The cached data of `cell` for particle p (slot `prefer` is refilled on a miss).
  const CellData& Data(std::size_t p, std::int32_t cell, int prefer, int* slotOut = nullptr)
  {
    CellData* two = CellCache.data() + 2 * p;
    int slot = two[0].Cell == cell ? 0 : (two[1].Cell == cell ? 1 : -1);
    if (slot < 0)
    {
      slot = prefer;
      Fill(cell, two[slot]);
    }
    if (slotOut)
      *slotOut = slot;
    return two[slot];
  }

  Vec Position(const CellData& cd, const double* b) const
  {
    Vec x = b[0] * Vertex(cd, 0);
    for (int i = 1; i < NV; ++i)
      x += b[i] * Vertex(cd, i);
    return x;
  }

  /**
   * Least-squares barycentric change (sum 0, zero on `active` vertices) whose embedded
   * displacement best matches d in the cell; returns false for a degenerate cell.
   */
  bool TangentBary(const CellData& cd, const bool active[NV], const Vec& d, double db[NV]) const
  {
    int fr[NV];
    int nf = 0;
    for (int i = 0; i < NV; ++i)
    {
      db[i] = 0.0;
      if (!active[i])
        fr[nf++] = i;
    }
    if (nf <= 1)
      return true;
    if (cd.Degenerate)
      return false;
    // Least squares in the free vertices: edges e_j = v_{fr[j+1]} - v_{fr[0]}, normal
    // equations (E^T E) a = E^T d solved in closed form (m = 1, 2, 3); the full cell's
    // inverse comes from the cache (same arithmetic as solving here).
    const int m = nf - 1;
    const auto base = Vertex(cd, fr[0]);
    Vec e[3];
    for (int j = 0; j < m; ++j)
      e[j] = Vertex(cd, fr[j + 1]) - base;
    double a[3] = { 0.0, 0.0, 0.0 };
    if (m == 1)
    {
      const double g = e[0].squaredNorm();
      if (!(g > 0.0))
        return false;
      a[0] = e[0].dot(d) / g;
    }
    else
    {
      Eigen::Matrix<double, 3, 1> rhs = Eigen::Matrix<double, 3, 1>::Zero();
      for (int i = 0; i < m; ++i)
        rhs[i] = e[i].dot(d);
      Eigen::Matrix<double, 3, 1> sol;
      if (m == K)
      {
        if (!cd.InverseOk)
          return false;
        sol = cd.GramInv * rhs;
      }
      else
      {
        Eigen::Matrix3d inverse;
        if (!PaddedGramInverse(e, m, inverse))
          return false;
        sol = inverse * rhs;
      }
      for (int j = 0; j < m; ++j)
        a[j] = sol[j];
      if (!(std::isfinite(a[0]) && std::isfinite(a[1]) && std::isfinite(a[2])))
        return false;
    }
    double sum = 0.0;
    for (int j = 0; j < m; ++j)
    {
      db[fr[j + 1]] = a[j];
      sum += a[j];
    }
    db[fr[0]] = -sum;
    return true;
  }

  /**
   * Projects the descent direction -g of a particle onto its feasible tangent cone: the
   * cell's tangent space, restricted to boundary faces it already touches when it points out.
   * Returns the projected gradient (embedded vector).
   */
  Vec ProjectGradient(const CellData& cd, const double* b, const Vec& g) const
  {
    bool active[NV] = {};
    double db[NV];
    const Vec d = -g;
    for (int pass = 0; pass <= K; ++pass)
    {
      if (!TangentBary(cd, active, d, db))
        return Vec::Zero(Dim);
      bool changed = false;
      for (int i = 0; i < NV; ++i)
        if (!active[i] && b[i] <= 1e-12 && db[i] < 0.0 && cd.Nbrs[i] < 0)
        {
          active[i] = true;
          changed = true;
        }
      if (!changed)
        break;
    }
    Vec p = Vec::Zero(Dim);
    for (int i = 0; i < NV; ++i)
      p -= db[i] * Vertex(cd, i);
    return p;
  }

  /// Unit embedded direction of feature edge e (from its first to its second point).
  Vec EdgeDirection(std::int32_t e, double* length) const
  {
    const auto ue = static_cast<std::size_t>(e);
    const Eigen::Map<const Vec> a(Emb.At(static_cast<std::size_t>(Features->Edges[2 * ue])), Dim);
    const Eigen::Map<const Vec> b(Emb.At(static_cast<std::size_t>(Features->Edges[2 * ue + 1])), Dim);
    Vec u = b - a;
    *length = u.norm();
    if (*length > 0.0)
      u /= *length;
    return u;
  }

  /**
   * Moves a feature-line particle by the component of d along its edge, continuing through
   * non-corner points onto the next edge of the line and stopping at corners and junctions.
   * The particle's cell is always its edge's EdgeCells entry, its barycentrics nonzero only
   * at the edge's two points. Returns the data of the final cell.
   */
  const CellData& WalkLine(std::size_t p, std::int32_t& cell, double* b, std::int32_t& edge, const Vec& d)
  {
    const SharpFeatures& f = *Features;
    auto ue = static_cast<std::size_t>(edge);
    double len = 0.0;
    const Vec u = EdgeDirection(edge, &len);
    double t = b[f.EdgeLocal[2 * ue + 1]]; // weight of the edge's second point
    double s = u.dot(d);                   // signed distance towards the second point
    for (int guard = 0; guard < 100000 && len > 0.0; ++guard)
    {
      const double tn = t + s / len;
      if (tn >= 0.0 && tn <= 1.0)
      {
        t = tn;
        break;
      }
      const bool forward = tn > 1.0;
      const double rest = forward ? (tn - 1.0) * len : -tn * len;
      const std::int32_t at = f.Edges[2 * ue + (forward ? 1 : 0)];
      const std::int32_t next = NextFeatureEdge(f, edge, at);
      if (next < 0)
      {
        t = forward ? 1.0 : 0.0;
        break;
      }
      edge = next;
      ue = static_cast<std::size_t>(edge);
      EdgeDirection(edge, &len);
      // Continue away from `at` on the next edge.
      const bool atFirst = f.Edges[2 * ue] == at;
      t = atFirst ? 0.0 : 1.0;
      s = atFirst ? rest : -rest;
    }
    cell = f.EdgeCells[ue];
    for (int i = 0; i < 4; ++i)
      b[i] = 0.0;
    b[f.EdgeLocal[2 * ue]] = 1.0 - t;
    b[f.EdgeLocal[2 * ue + 1]] = t;
    return Data(p, cell, 1);
  }

  /**
   * Moves particle p by the embedded displacement d: projected on the tangent space of the
   * current cell, walked across faces into neighbours (the rest of d is re-projected there),
   * sliding along boundary faces. Returns the data of the final cell.
   */
  const CellData& Walk(std::size_t p, std::int32_t& cell, double* b, Vec d)
  {
    bool active[NV] = {};
    double db[NV];
    std::int32_t prev = -1;
    int home = 0;
    const CellData* cd = &Data(p, cell, 0, &home);
    for (int step = 0; step < 256; ++step)
    {
      if (!TangentBary(*cd, active, d, db))
        return *cd;
      double scale = 0.0;
      for (int i = 0; i < NV; ++i)
        scale += std::abs(db[i]);
      if (scale <= 1e-300)
        return *cd;
      double t = 1.0;
      int hit = -1;
      for (int i = 0; i < NV; ++i)
        if (!active[i] && db[i] < -1e-15 * scale)
        {
          const double ti = std::max(0.0, b[i]) / -db[i];
          if (ti < t)
          {
            t = ti;
            hit = i;
          }
        }
      double sum = 0.0;
      for (int i = 0; i < NV; ++i)
      {
        b[i] = std::max(0.0, b[i] + t * db[i]);
        if (i == hit)
          b[i] = 0.0;
        sum += b[i];
      }
      for (int i = 0; i < NV; ++i)
        b[i] /= sum;
      if (hit < 0)
        return *cd;
      d *= (1.0 - t);
      const std::int32_t nb = cd->Nbrs[hit];
      if (nb < 0 || (nb == prev && t <= 1e-12))
      {
        // Boundary (or bouncing back without progress): slide on the face.
        active[hit] = true;
        int nfree = 0;
        for (int i = 0; i < NV; ++i)
          nfree += active[i] ? 0 : 1;
        if (nfree <= 1)
          return *cd;
        continue;
      }
      // The start cell keeps its slot; cells walked into share the other one (which may be
      // *cd itself: copy its ids first).
      std::int32_t from[NV];
      std::copy_n(cd->Ids, NV, from);
      const CellData& next = Data(p, nb, 1 - home);
      const std::int32_t* to = next.Ids;
      double nbBary[NV];
      for (int j = 0; j < NV; ++j)
      {
        nbBary[j] = 0.0;
        for (int i = 0; i < NV; ++i)
          if (from[i] == to[j])
            nbBary[j] = b[i];
      }
      for (int j = 0; j < NV; ++j)
      {
        b[j] = nbBary[j];
        active[j] = false;
      }
      prev = cell;
      cell = nb;
      cd = &next;
    }
    return *cd;
  }

  /// Outer lists: all pairs closer than Cutoff + Skin + OuterSkin at the positions x, each
  /// sorted by particle index (the summation order then does not depend on the search). The
  /// candidates come from a uniform grid on the particles' 3 principal coordinates: the
  /// projection onto orthonormal axes shortens distances, so no pair is missed, and the
  /// particles live on a 2- or 3-manifold, so these coordinates separate them well (a kd-tree
  /// over all Dim coordinates visits many more leaves at this radius).
  void BuildOuter(const std::vector<double>& x)
  {
    ++Rebuilds;
    OuterPositions = x;
    const double r = Cutoff + Skin + OuterSkin;
    const double r2 = r * r;
    const int kp = std::min(3, Dim);
    // Principal axes (serial: deterministic).
    Vec mean = Vec::Zero(Dim);
    for (std::size_t p = 0; p < N; ++p)
      mean += Eigen::Map<const Vec>(x.data() + p * static_cast<std::size_t>(Dim), Dim);
    mean /= static_cast<double>(N);
    Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(Dim, Dim);
    for (std::size_t p = 0; p < N; ++p)
    {
      const Vec c = Eigen::Map<const Vec>(x.data() + p * static_cast<std::size_t>(Dim), Dim) - mean;
      cov.noalias() += c * c.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(cov);
    Eigen::Matrix<double, 3, D, Eigen::RowMajor, 3, MaxD> axes =
      Eigen::Matrix<double, 3, D, Eigen::RowMajor, 3, MaxD>::Zero(3, Dim);
    if (eig.info() == Eigen::Success)
      for (int a = 0; a < kp; ++a)
        axes.row(a) = eig.eigenvectors().col(Dim - 1 - a).transpose().normalized();
    else
      for (int a = 0; a < kp; ++a)
        axes(a, a) = 1.0;
    // Projected coordinates and the grid (cell side a bit over r: neighbours are in the
    // adjacent cells despite round-off).
    Proj.resize(3 * N);
    double lo[3] = { 0.0, 0.0, 0.0 }, hi[3] = { 0.0, 0.0, 0.0 };
    for (std::size_t p = 0; p < N; ++p)
    {
      const Eigen::Vector3d y =
        axes * Eigen::Map<const Vec>(x.data() + p * static_cast<std::size_t>(Dim), Dim);
      for (int a = 0; a < 3; ++a)
      {
        Proj[3 * p + a] = y[a];
        lo[a] = p == 0 ? y[a] : std::min(lo[a], y[a]);
        hi[a] = p == 0 ? y[a] : std::max(hi[a], y[a]);
      }
    }
    long long n[3];
    const double h = GridCellSide(lo, hi, r, N, n);
    auto cellOf = [&](std::size_t p, int a)
    { return std::min(n[a] - 1, static_cast<long long>((Proj[3 * p + a] - lo[a]) / h)); };
    const auto numCells = static_cast<std::size_t>(n[0] * n[1] * n[2]);
    GridStart.assign(numCells + 1, 0);
    ParticleCell.resize(N);
    for (std::size_t p = 0; p < N; ++p)
    {
      const long long c = (cellOf(p, 0) * n[1] + cellOf(p, 1)) * n[2] + cellOf(p, 2);
      ParticleCell[p] = static_cast<std::uint32_t>(c);
      ++GridStart[static_cast<std::size_t>(c) + 1];
    }
    for (std::size_t c = 0; c < numCells; ++c)
      GridStart[c + 1] += GridStart[c];
    GridItems.resize(N);
    GridX.resize(x.size()); // positions in grid order: the candidate scan reads them in a row
    {
      std::vector<std::uint32_t> fill(GridStart.begin(), GridStart.end() - 1);
      for (std::size_t p = 0; p < N; ++p)
      {
        const std::uint32_t t = fill[ParticleCell[p]]++;
        GridItems[t] = static_cast<std::uint32_t>(p);
        std::copy_n(x.data() + p * static_cast<std::size_t>(Dim), Dim,
          GridX.data() + t * static_cast<std::size_t>(Dim));
      }
    }
    // Candidates: the 3 x 3 x 3 grid cells around the particle's, as 9 runs of consecutive
    // cells; full distances on grid-ordered positions, stored branch-free.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, N),
      [&](const tbb::blocked_range<std::size_t>& rg)
      {
        std::vector<std::uint32_t> buffer; // per chunk, grows to the largest neighbourhood
        for (std::size_t p = rg.begin(); p != rg.end(); ++p)
        {
          const Eigen::Map<const Vec> xp(x.data() + p * static_cast<std::size_t>(Dim), Dim);
          long long c[3];
          for (int a = 0; a < 3; ++a)
            c[a] = cellOf(p, a);
          const long long k0 = std::max(0LL, c[2] - 1), k1 = std::min(n[2] - 1, c[2] + 1);
          std::size_t count = 0;
          for (long long i = std::max(0LL, c[0] - 1); i <= std::min(n[0] - 1, c[0] + 1); ++i)
            for (long long j = std::max(0LL, c[1] - 1); j <= std::min(n[1] - 1, c[1] + 1); ++j)
            {
              const auto row = static_cast<std::size_t>((i * n[1] + j) * n[2]);
              const std::uint32_t t0 = GridStart[row + static_cast<std::size_t>(k0)];
              const std::uint32_t t1 = GridStart[row + static_cast<std::size_t>(k1) + 1];
              if (buffer.size() < count + (t1 - t0))
                buffer.resize(2 * (count + (t1 - t0)));
              for (std::uint32_t t = t0; t < t1; ++t)
              {
                const Eigen::Map<const Vec> xq(
                  GridX.data() + t * static_cast<std::size_t>(Dim), Dim);
                const std::uint32_t q = GridItems[t];
                buffer[count] = q;
                count += ((xp - xq).squaredNorm() < r2) & (q != p) ? 1 : 0;
              }
            }
          auto& list = Outer[p];
          list.assign(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(count));
          std::sort(list.begin(), list.end());
        }
      });
    OuterStart.resize(N + 1);
    OuterStart[0] = 0;
    for (std::size_t p = 0; p < N; ++p)
      OuterStart[p + 1] = OuterStart[p] + Outer[p].size();
    Inner.resize(OuterStart[N]);
  }

  /// Sums f(i0, i1, out) (out: M partial sums of [i0, i1)) over fixed blocks of [0, n) in
  /// parallel, then adds the blocks' partials in block order: the same bits for any number
  /// of threads.
  template <int M, class F>
  std::array<double, M> BlockedSums(std::size_t n, F&& f)
  {
    const std::size_t blocks = (n + kBlock - 1) / kBlock;
    Partials.resize(blocks * M);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks, 1),
      [&](const tbb::blocked_range<std::size_t>& r)
      {
        for (std::size_t b = r.begin(); b != r.end(); ++b)
          f(b * kBlock, std::min(n, (b + 1) * kBlock), Partials.data() + b * M);
      });
    std::array<double, M> sum{};
    for (std::size_t b = 0; b < blocks; ++b)
      for (int m = 0; m < M; ++m)
        sum[static_cast<std::size_t>(m)] += Partials[b * M + static_cast<std::size_t>(m)];
    return sum;
  }

  /// y = s y + a x (s == 0: y = a x; x null: no a x term), then returns z . y (z null: 0);
  /// one parallel pass over the nd values.
  double ScaleAddDot(double s, double a, const double* x, double* y, const double* z)
  {
    return BlockedSums<1>(NumValues,
      [&](std::size_t i0, std::size_t i1, double* out)
      {
        if (s == 0.0)
          for (std::size_t i = i0; i < i1; ++i)
            y[i] = x ? a * x[i] : 0.0;
        else if (x)
          for (std::size_t i = i0; i < i1; ++i)
            y[i] = s * y[i] + a * x[i];
        else if (s != 1.0)
          for (std::size_t i = i0; i < i1; ++i)
            y[i] *= s;
        out[0] = z ? Dot(z + i0, y + i0, i1 - i0) : 0.0;
      })[0];
  }

  /// Sum of the two largest displacements between `x` and `ref` (no pair can have closed in
  /// by more than this); infinity when `ref` is unset.
  double TwoLargestMoves(const std::vector<double>& x, const std::vector<double>& ref)
  {
    if (ref.size() != x.size())
      return std::numeric_limits<double>::infinity();
    // Per block of particles its two largest squared displacements, then of all blocks.
    const std::size_t perBlock = std::max<std::size_t>(1, kBlock / static_cast<std::size_t>(Dim));
    const std::size_t blocks = (N + perBlock - 1) / perBlock;
    Partials.resize(2 * blocks);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks, 1),
      [&](const tbb::blocked_range<std::size_t>& r)
      {
        for (std::size_t b = r.begin(); b != r.end(); ++b)
        {
          double m1 = 0.0, m2 = 0.0;
          for (std::size_t p = b * perBlock, e = std::min(N, (b + 1) * perBlock); p < e; ++p)
          {
            const Eigen::Map<const Vec> u(x.data() + p * static_cast<std::size_t>(Dim), Dim);
            const Eigen::Map<const Vec> v(ref.data() + p * static_cast<std::size_t>(Dim), Dim);
            const double d2 = (u - v).squaredNorm();
            if (d2 > m2)
            {
              m2 = std::min(d2, m1);
              m1 = std::max(d2, m1);
            }
          }
          Partials[2 * b] = m1;
          Partials[2 * b + 1] = m2;
        }
      });
    double m1 = 0.0, m2 = 0.0; // two largest squared displacements
    for (double d2 : Partials)
      if (d2 > m2)
      {
        m2 = std::min(d2, m1);
        m1 = std::max(d2, m1);
      }
    return std::sqrt(m1) + std::sqrt(m2);
  }

  /// Two-level Verlet lists. The inner lists (radius Cutoff + Skin, used by the energy) are
  /// refiltered from the outer lists (radius Cutoff + Skin + OuterSkin, kd-tree) when two
  /// particles may have closed in by more than Skin; the outer lists are rebuilt when that
  /// may be by more than OuterSkin since their build, so every pair closer than Cutoff stays
  /// listed. Lists are sorted by index, so results do not depend on when they were rebuilt.
  void EnsureNeighbours(const std::vector<double>& x)
  {
    if (TwoLargestMoves(x, ListPositions) <= Skin)
      return;
    if (TwoLargestMoves(x, OuterPositions) > OuterSkin)
      BuildOuter(x);
    ListPositions = x;
    const double r = Cutoff + Skin;
    const double r2 = r * r;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, N),
      [&](const tbb::blocked_range<std::size_t>& rg)
      {
        for (std::size_t p = rg.begin(); p != rg.end(); ++p)
        {
          const Eigen::Map<const Vec> xp(x.data() + p * static_cast<std::size_t>(Dim), Dim);
          // Into the outer list's slot (a superset), branch-free.
          std::uint32_t* out = Inner.data() + OuterStart[p];
          std::uint32_t count = 0;
          for (std::uint32_t q : Outer[p])
          {
            const Eigen::Map<const Vec> xq(x.data() + q * static_cast<std::size_t>(Dim), Dim);
            out[count] = q;
            count += (xp - xq).squaredNorm() < r2 ? 1 : 0;
          }
          InnerCount[p] = count;
        }
      });
  }

  /**
   * Energy (returned) and projected gradients; per-particle outputs, serial sum. The kernel
   * is shifted by its value at the cutoff, so the energy is continuous in the positions and
   * does not depend on the neighbour lists.
   */
  double Evaluate(const std::vector<double>& x, const std::vector<std::int32_t>& cells,
    const std::vector<double>& bary, const std::vector<std::int32_t>& edges,
    std::vector<double>* grad)
  {
    ++Evaluations;
    EnsureNeighbours(x);
    const double inv4s2 = 1.0 / (4.0 * Sigma * Sigma);
    const double rc2 = Cutoff * Cutoff;
    double shift = 0.0;
    GaussianKernel(&rc2, &shift, 1, inv4s2, std::numeric_limits<double>::infinity());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, N),
      [&](const tbb::blocked_range<std::size_t>& r)
      {
        double d2[kExpChunk], w[kExpChunk];
        for (std::size_t p = r.begin(); p != r.end(); ++p)
        {
          const Eigen::Map<const Vec> xp(x.data() + p * static_cast<std::size_t>(Dim), Dim);
          Vec g = Vec::Zero(Dim);
          double e = 0.0;
          const std::uint32_t* list = Inner.data() + OuterStart[p];
          const std::size_t count = InnerCount[p];
          // In chunks: distances, then the kernel of the whole chunk (vectorised exp), then
          // the sums in list order.
          for (std::size_t j0 = 0; j0 < count; j0 += kExpChunk)
          {
            const std::size_t m = std::min(count - j0, kExpChunk);
            for (std::size_t j = 0; j < m; ++j)
            {
              const Eigen::Map<const Vec> xq(
                x.data() + list[j0 + j] * static_cast<std::size_t>(Dim), Dim);
              d2[j] = (xp - xq).squaredNorm();
            }
            GaussianKernel(d2, w, m, inv4s2, rc2);
            for (std::size_t j = 0; j < m; ++j)
            {
              if (d2[j] >= rc2)
                continue;
              const Eigen::Map<const Vec> xq(
                x.data() + list[j0 + j] * static_cast<std::size_t>(Dim), Dim);
              e += w[j] - shift;
              g -= (2.0 * inv4s2 * w[j]) * (xp - xq);
            }
          }
          PerParticle[p] = 0.5 * e;
          if (grad)
          {
            Eigen::Map<Vec> gp(grad->data() + p * static_cast<std::size_t>(Dim), Dim);
            if (Kind[p] == 0)
              gp = ProjectGradient(Data(p, cells[p], 0), bary.data() + 4 * p, g);
            else if (Kind[p] == 1)
            {
              double len = 0.0;
              const Vec u = EdgeDirection(edges[p], &len);
              gp = u.dot(g) * u; // along the feature line only
            }
            else
              gp.setZero(); // corners do not move
          }
        }
      });
    double sum = 0.0;
    for (double v : PerParticle)
      sum += v;
    return sum;
  }

  /// Mean number of neighbours closer than the cutoff.
  double MeanNeighbours(const std::vector<double>& x)
  {
    EnsureNeighbours(x);
    std::size_t total = 0;
    for (std::size_t p = 0; p < N; ++p)
      for (std::uint32_t j = 0; j < InnerCount[p]; ++j)
      {
        const std::uint32_t q = Inner[OuterStart[p] + j];
        double d2 = 0.0;
        for (int d = 0; d < Dim; ++d)
          d2 += std::pow(x[p * static_cast<std::size_t>(Dim) + static_cast<std::size_t>(d)] -
              x[q * static_cast<std::size_t>(Dim) + static_cast<std::size_t>(d)],
            2);
        total += d2 < Cutoff * Cutoff ? 1 : 0;
      }
    return static_cast<double>(total) / static_cast<double>(N);
  }

  void Run(const ParticleSamplerOptions& opt, ParticleSamplerResult& res)
  {
    N = res.Sites.NumSites();
    Kind = res.FeatureKind.data();
    Outer.resize(N);
    InnerCount.assign(N, 0);
    PerParticle.assign(N, 0.0);
    CellCache.assign(2 * N, CellData());
    const int total = opt.WarmupIterations + opt.Iterations;
    int done = 0;
    // Warm-up at the narrower kernel (harder repulsion: the nearest-neighbour distances even
    // out faster), then the paper's kernel.
    if (opt.WarmupIterations > 0)
    {
      SetKernel(res.Sigma * opt.WarmupKernelWidthFactor / opt.KernelWidthFactor, opt);
      res.WarmupIterationsDone =
        Minimise(opt, opt.WarmupIterations, done, total, res.WarmupEnergy, res);
      done += res.WarmupIterationsDone;
    }
    if (!res.Aborted)
    {
      SetKernel(res.Sigma, opt);
      res.IterationsDone = Minimise(opt, opt.Iterations, done, total, res.Energy, res);
    }
    else
    {
      SetKernel(res.Sigma, opt);
      res.Energy.push_back(
        Evaluate(res.Sites.Coords, res.Sites.CellIds, res.Sites.Bary, res.FeatureEdge, nullptr));
    }
    res.MeanNeighbours = MeanNeighbours(res.Sites.Coords);
    res.EnergyEvaluations = Evaluations;
    res.NeighbourRebuilds = Rebuilds;
    if (opt.Progress)
      opt.Progress(1.0);
  }

  /// Kernel width sigma, cutoff c sigma, list skin sigma; forces a list rebuild.
  void SetKernel(double sigma, const ParticleSamplerOptions& opt)
  {
    Sigma = sigma;
    Cutoff = opt.NeighbourCutoff * Sigma;
    // Skins tuned on cube2 (5000 sites): a thin inner skin keeps the energy loops short
    // (the inner lists are rebuilt most iterations, cheaply), the outer one makes grid
    // builds rare (about one in 9 evaluations).
    Skin = 0.5 * Sigma;
    OuterSkin = 2.0 * Sigma;
    ListPositions.clear();
    OuterPositions.clear();
  }

  template <class P>
  static void ClearHistory(std::deque<P>& hist, std::vector<P>& spare)
  {
    for (auto& pr : hist)
      spare.push_back(std::move(pr));
    hist.clear();
  }

  /**
   * Projected L-BFGS on the sites in res.Sites at the current kernel: at most `iterations`
   * iterations, energies appended to `energyOut` (the start value first). `done` / `total`
   * scale the progress callback. Returns the iterations done.
   */
  int Minimise(const ParticleSamplerOptions& opt, int iterations, int done, int total,
    std::vector<double>& energyOut, ParticleSamplerResult& res)
  {
    const std::size_t nd = N * static_cast<std::size_t>(Dim);
    std::vector<double>& x = res.Sites.Coords;
    std::vector<std::int32_t>& cells = res.Sites.CellIds;
    std::vector<double>& bary = res.Sites.Bary;
    std::vector<std::int32_t>& edges = res.FeatureEdge;

    std::vector<double> g(nd), xt(nd), gt(nd), bt(bary.size());
    std::vector<std::int32_t> ct(N), et(edges);
    Eigen::VectorXd dir(nd);
    struct Pair
    {
      Eigen::VectorXd S, Y;
      double Sy = 0.0, Yy = 0.0; // s.y and |y|^2, kept from the acceptance test
    };
    std::deque<Pair> hist;
    std::vector<Pair> spare; // storage of dropped pairs, reused (no 2 x nd allocation per step)
    std::vector<double> alpha;

    double energy = Evaluate(x, cells, bary, edges, &g);
    energyOut.push_back(energy);
    int failures = 0, itDone = 0;
    for (int it = 0; it < iterations; ++it)
    {
      if (opt.Progress && !opt.Progress(static_cast<double>(done + it) / total))
      {
        res.Aborted = true;
        break;
      }
      // Two-loop recursion, each update of dir fused with the next dot product (pending:
      // dir = ps dir + pa px, applied in the next pass).
      NumValues = nd;
      double* d = dir.data();
      const std::size_t nh = hist.size();
      alpha.assign(nh, 0.0);
      double ps = 0.0, pa = -1.0;
      const double* px = g.data();
      double gDir = 0.0; // g . dir once dir is final
      if (nh > 0)
      {
        for (std::size_t h = nh; h-- > 0;)
        {
          alpha[h] = ScaleAddDot(ps, pa, px, d, hist[h].S.data()) / hist[h].Sy;
          ps = 1.0;
          pa = -alpha[h];
          px = hist[h].Y.data();
        }
        const double gamma = hist.back().Sy / hist.back().Yy;
        ps = gamma;
        pa *= gamma;
        for (std::size_t h = 0; h < nh; ++h)
        {
          const double beta = ScaleAddDot(ps, pa, px, d, hist[h].Y.data()) / hist[h].Sy;
          ps = 1.0;
          pa = alpha[h] - beta;
          px = hist[h].S.data();
        }
        gDir = ScaleAddDot(ps, pa, px, d, g.data());
      }
      if (!(gDir < 0.0))
      {
        // First step, or not a descent direction: steepest descent moving the average
        // particle by sigma / 2.
        if (nh > 0)
          ClearHistory(hist, spare);
        const double rms =
          std::sqrt(ScaleAddDot(1.0, 0.0, nullptr, g.data(), g.data()) / static_cast<double>(N));
        if (rms <= 0.0 && nh == 0)
          break;
        ScaleAddDot(0.0, -0.5 * Sigma / std::max(rms, 1e-300), g.data(), d, nullptr);
      }
      // Trust region per particle: no particle jumps more than one sigma per step.
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, N),
        [&](const tbb::blocked_range<std::size_t>& r)
        {
          for (std::size_t p = r.begin(); p != r.end(); ++p)
          {
            auto dp = dir.segment(static_cast<Eigen::Index>(p) * Dim, Dim);
            const double len = dp.norm();
            if (len > Sigma)
              dp *= Sigma / len;
          }
        });

      bool accepted = false;
      double step = 1.0, trialEnergy = energy;
      for (int ls = 0; ls < 12 && !accepted; ++ls, step *= 0.5)
      {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, N),
          [&](const tbb::blocked_range<std::size_t>& r)
          {
            for (std::size_t p = r.begin(); p != r.end(); ++p)
            {
              std::int32_t c = cells[p];
              double* b = bt.data() + 4 * p;
              std::copy_n(bary.data() + 4 * p, 4, b);
              const Vec d = step * Vec(dir.segment(static_cast<Eigen::Index>(p) * Dim, Dim));
              et[p] = edges[p];
              const CellData& cd = Kind[p] == 0 ? Walk(p, c, b, d)
                : (Kind[p] == 1 ? WalkLine(p, c, b, et[p], d) : Data(p, c, 0));
              ct[p] = c;
              Eigen::Map<Vec>(xt.data() + p * static_cast<std::size_t>(Dim), Dim) =
                Position(cd, b);
            }
          });
        trialEnergy = Evaluate(xt, ct, bt, et, &gt);
        const double slope = BlockedSums<1>(nd,
          [&](std::size_t i0, std::size_t i1, double* out)
          {
            double acc[4] = { 0.0, 0.0, 0.0, 0.0 };
            std::size_t i = i0;
            for (; i + 4 <= i1; i += 4)
              for (std::size_t k = 0; k < 4; ++k)
                acc[k] += g[i + k] * (xt[i + k] - x[i + k]);
            for (; i < i1; ++i)
              acc[0] += g[i] * (xt[i] - x[i]);
            out[0] = (acc[0] + acc[1]) + (acc[2] + acc[3]);
          })[0];
        accepted = trialEnergy <= energy + 1e-4 * slope && trialEnergy < energy;
      }
      if (!accepted)
      {
        energyOut.push_back(energy);
        itDone = it + 1;
        if (hist.empty() || ++failures >= 2)
          break; // converged as far as the line search can tell
        ClearHistory(hist, spare);
        continue;
      }
      failures = 0;
      Pair pr;
      if (!spare.empty())
      {
        pr = std::move(spare.back());
        spare.pop_back();
      }
      pr.S.resize(static_cast<Eigen::Index>(nd));
      pr.Y.resize(static_cast<Eigen::Index>(nd));
      const std::array<double, 2> products = BlockedSums<2>(nd,
        [&](std::size_t i0, std::size_t i1, double* out)
        {
          double* sv = pr.S.data();
          double* yv = pr.Y.data();
          for (std::size_t i = i0; i < i1; ++i)
          {
            sv[i] = xt[i] - x[i];
            yv[i] = gt[i] - g[i];
          }
          out[0] = Dot(sv + i0, yv + i0, i1 - i0);
          out[1] = Dot(yv + i0, yv + i0, i1 - i0);
        });
      pr.Sy = products[0];
      pr.Yy = products[1];
      if (pr.Sy > 1e-10 * pr.Yy)
      {
        hist.push_back(std::move(pr));
        if (static_cast<int>(hist.size()) > opt.History)
        {
          spare.push_back(std::move(hist.front()));
          hist.pop_front();
        }
      }
      else
        spare.push_back(std::move(pr));
      x.swap(xt);
      g.swap(gt);
      bary.swap(bt);
      cells.swap(ct);
      edges.swap(et);
      energy = trialEnergy;
      energyOut.push_back(energy);
      itDone = it + 1;
    }
    return itDone;
  }

private:
  const SimplexMesh& Mesh;
  const Embedding& Emb;
  const VertexCells& VC;
  const SharpFeatures* Features; // nullptr: no feature particles
  const std::int8_t* Kind = nullptr; // per particle: 0 free, 1 feature line, 2 corner
  const int Dim;
  static constexpr std::int32_t kUnknown = -2;
  std::unique_ptr<std::atomic<std::int32_t>[]> NbrMemo; // face neighbours, kUnknown: not yet
  std::size_t N = 0;
  double Sigma = 1.0;
  double Cutoff = 5.0;
  double Skin = 1.0;
  int Evaluations = 0;
  int Rebuilds = 0;
  std::vector<CellData> CellCache; // 2 per particle
  double OuterSkin = 2.0;
  std::vector<double> ListPositions;  // positions at the last inner list build
  std::vector<double> OuterPositions; // positions at the last kd-tree build
  std::vector<std::vector<std::uint32_t>> Outer;
  /// Inner lists, CSR in the outer lists' layout: particle p's are the first InnerCount[p]
  /// of Inner[OuterStart[p] ..].
  std::vector<std::size_t> OuterStart;
  std::vector<std::uint32_t> Inner, InnerCount;
  std::vector<double> Proj;  // principal coordinates (3 per particle)
  std::vector<double> GridX; // positions in grid order
  std::vector<std::uint32_t> GridStart, GridItems, ParticleCell; // outer-list grid (CSR)
  std::vector<double> PerParticle;
  static constexpr std::size_t kBlock = 4096; ///< values per block of the parallel sums
  std::size_t NumValues = 0;                  ///< nd, the length of ScaleAddDot's vectors
  std::vector<double> Partials;               ///< per-block partial sums
};

template <int D>
void RunDim(const SimplexMesh& mesh, const Embedding& emb, const VertexCells& nb,
  const SharpFeatures* features, const ParticleSamplerOptions& opt, ParticleSamplerResult& res)
{
  if (mesh.SimplexDim == 2)
    Sampler<D, 2>(mesh, emb, nb, features).Run(opt, res);
  else
    Sampler<D, 3>(mesh, emb, nb, features).Run(opt, res);
}

/// 30-bit Morton code of a point in the box [lo, lo + ext] (2 or 3 coordinates).
std::uint32_t Morton(const double* p, const double* lo, const double* ext, int m)
{
  const int bits = m == 3 ? 10 : 15;
  std::uint32_t code = 0;
  std::uint32_t q[3] = { 0, 0, 0 };
  for (int d = 0; d < m; ++d)
  {
    const double t = ext[d] > 0.0 ? (p[d] - lo[d]) / ext[d] : 0.0;
    q[d] = static_cast<std::uint32_t>(std::clamp(t, 0.0, 1.0) * ((1u << bits) - 1));
  }
  for (int b = bits - 1; b >= 0; --b)
    for (int d = 0; d < m; ++d)
      code = (code << 1) | ((q[d] >> b) & 1u);
  return code;
}

/// Uniform barycentrics on `nv` vertices (gaps of sorted uniforms).
void UniformBary(Rng& rng, int nv, double* b)
{
  double cut[5] = { 0.0, 0.0, 0.0, 0.0, 0.0 };
  for (int j = 1; j < nv; ++j)
    cut[j] = rng.Uniform();
  for (int a = 2; a < nv; ++a) // insertion sort of the nv - 1 uniforms
    for (int c = a; c > 1 && cut[c] < cut[c - 1]; --c)
      std::swap(cut[c], cut[c - 1]);
  cut[nv] = 1.0;
  for (int j = 0; j < nv; ++j)
    b[j] = cut[j + 1] - cut[j];
}

/**
 * Jittered stratified draw of `count` items with probability proportional to `weight`, in
 * the given item order: the i-th draw falls in the i-th of `count` equal slices of the
 * cumulative weight, so every run of consecutive items holding weight W receives W / w̄ ± 1
 * draws (items sorted along a space-filling curve: no large-scale density fluctuations).
 * Random mode draws i.i.d. instead. Returns item indices (into `order`'s values).
 */
std::vector<std::size_t> StratifiedDraw(const std::vector<std::size_t>& order,
  const std::vector<double>& weight, std::size_t count, bool stratified, Rng& rng)
{
  std::vector<double> cdf(order.size());
  double total = 0.0;
  for (std::size_t i = 0; i < order.size(); ++i)
    cdf[i] = (total += weight[order[i]]);
  std::vector<std::size_t> out(count);
  for (std::size_t i = 0; i < count; ++i)
  {
    const double u = stratified
      ? (static_cast<double>(i) + rng.Uniform()) / static_cast<double>(count) * total
      : rng.Uniform() * total;
    auto j = static_cast<std::size_t>(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin());
    j = std::min(j, order.size() - 1);
    while (weight[order[j]] <= 0.0 && j > 0) // never a degenerate item
      --j;
    out[i] = order[j];
  }
  return out;
}

/**
 * Best-candidate start: sites placed one at a time, each the farthest (in R^Dim) from the
 * sites already placed among m = InitialCandidates candidates drawn proportionally to the
 * embedded measure; a candidate with no site within r = spacing (|mesh| / n)^{1/k} is taken
 * at once (dart throwing with a fallback; r 0.75 / 0.9 / 1.2 spacings gave starts as good
 * or worse). Neighbours come from a grid on the 3 principal coordinates of the embedded
 * vertices (a projection only shortens distances: no site within r is missed).
 * Serial: deterministic for a seed.
 */
void BestCandidateSites(const SimplexMesh& mesh, const Embedding& emb,
  const std::vector<double>& meas, const ParticleSamplerOptions& opt, Rng& rng,
  const SiteSet& placed, ParticleSamplerResult& res)
{
  const int k = mesh.SimplexDim, nv = k + 1, dim = emb.Dim;
  // Sites 0..nf-1 of the search are the already placed (feature) ones, not output.
  const std::size_t nf = placed.NumSites();
  const std::size_t nc = mesh.NumCells(), n = opt.NumSites, np = mesh.NumPoints();
  const int m = opt.InitialCandidates;
  const auto ud = static_cast<std::size_t>(dim);
  std::vector<double> cdf(nc);
  double total = 0.0;
  for (std::size_t c = 0; c < nc; ++c)
    cdf[c] = (total += meas[c]);
  const double r = std::pow(total / static_cast<double>(n), 1.0 / k);
  const double r2 = r * r;

  // Principal axes of the embedded vertices (stack-sized vectors: no allocation per vertex).
  using VecD = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxDim, 1>;
  using MatD = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, kMaxDim,
    kMaxDim>;
  VecD mean = VecD::Zero(dim);
  for (std::size_t v = 0; v < np; ++v)
    mean += Eigen::Map<const VecD>(emb.At(v), dim);
  mean /= static_cast<double>(np);
  MatD cov = MatD::Zero(dim, dim);
  for (std::size_t v = 0; v < np; ++v)
  {
    const VecD c = Eigen::Map<const VecD>(emb.At(v), dim) - mean;
    cov.noalias() += c * c.transpose();
  }
  Eigen::SelfAdjointEigenSolver<MatD> eig(cov);
  Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::RowMajor, 3, kMaxDim> axes =
    Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::RowMajor, 3, kMaxDim>::Zero(3, dim);
  const int kp = std::min(3, dim);
  for (int a = 0; a < kp; ++a)
    if (eig.info() == Eigen::Success)
      axes.row(a) = eig.eigenvectors().col(dim - 1 - a).transpose().normalized();
    else
      axes(a, a) = 1.0;
  double lo[3], hi[3];
  for (std::size_t v = 0; v < np; ++v)
  {
    const Eigen::Vector3d y = axes * Eigen::Map<const VecD>(emb.At(v), dim);
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = v == 0 ? y[a] : std::min(lo[a], y[a]);
      hi[a] = v == 0 ? y[a] : std::max(hi[a], y[a]);
    }
  }
  long long g[3];
  const double h = GridCellSide(lo, hi, r, n, g);
  std::vector<std::int32_t> head(static_cast<std::size_t>(g[0] * g[1] * g[2]), -1), next(n, -1);

  SiteSet& s = res.Sites;
  std::vector<double> x(n * ud), bary(4 * n);
  std::vector<std::int32_t> cell(n);
  std::vector<double> cx(ud);
  double bx[kMaxDim], bb[4] = { 0, 0, 0, 0 };
  auto gridKey = [&](const double* px, long long q[3])
  {
    const Eigen::Vector3d y = axes * Eigen::Map<const VecD>(px, dim);
    for (int a = 0; a < 3; ++a)
      q[a] = std::clamp(static_cast<long long>((y[a] - lo[a]) / h), 0LL, g[a] - 1);
    return (q[0] * g[1] + q[1]) * g[2] + q[2];
  };
  for (std::size_t i = 0; i < nf; ++i)
  {
    std::copy_n(placed.At(i), ud, x.data() + i * ud);
    long long q[3];
    const long long key = gridKey(placed.At(i), q);
    next[i] = head[static_cast<std::size_t>(key)];
    head[static_cast<std::size_t>(key)] = static_cast<std::int32_t>(i);
  }
  for (std::size_t i = nf; i < n; ++i)
  {
    double best = -1.0;
    std::size_t bestCell = 0;
    long long bestKey = 0;
    for (int j = 0; j < m; ++j)
    {
      auto c = static_cast<std::size_t>(
        std::upper_bound(cdf.begin(), cdf.end(), rng.Uniform() * total) - cdf.begin());
      c = std::min(c, nc - 1);
      while (meas[c] <= 0.0 && c > 0)
        --c;
      double b[4] = { 0, 0, 0, 0 };
      UniformBary(rng, nv, b);
      const std::int32_t* ids = mesh.Cell(c);
      std::fill(cx.begin(), cx.end(), 0.0);
      for (int v = 0; v < nv; ++v)
      {
        const double* e = emb.At(static_cast<std::size_t>(ids[v]));
        for (int d = 0; d < dim; ++d)
          cx[static_cast<std::size_t>(d)] += b[v] * e[d];
      }
      const Eigen::Vector3d y = axes * Eigen::Map<const VecD>(cx.data(), dim);
      long long q[3];
      for (int a = 0; a < 3; ++a)
        q[a] = std::clamp(static_cast<long long>((y[a] - lo[a]) / h), 0LL, g[a] - 1);
      double dmin = r2;
      for (long long a0 = std::max(0LL, q[0] - 1); a0 <= std::min(g[0] - 1, q[0] + 1); ++a0)
        for (long long a1 = std::max(0LL, q[1] - 1); a1 <= std::min(g[1] - 1, q[1] + 1); ++a1)
          for (long long a2 = std::max(0LL, q[2] - 1); a2 <= std::min(g[2] - 1, q[2] + 1); ++a2)
            for (std::int32_t t = head[static_cast<std::size_t>((a0 * g[1] + a1) * g[2] + a2)];
                 t >= 0; t = next[static_cast<std::size_t>(t)])
            {
              const double* xt = x.data() + static_cast<std::size_t>(t) * ud;
              double d2 = 0.0;
              for (int d = 0; d < dim; ++d)
              {
                const double w = xt[d] - cx[static_cast<std::size_t>(d)];
                d2 += w * w;
              }
              dmin = std::min(dmin, d2);
            }
      if (dmin > best)
      {
        best = dmin;
        bestCell = c;
        bestKey = (q[0] * g[1] + q[1]) * g[2] + q[2];
        std::copy(cx.begin(), cx.end(), bx);
        std::copy(b, b + 4, bb);
      }
      if (dmin >= r2) // nothing within r: accept (dart throwing)
        break;
    }
    std::copy(bx, bx + dim, x.data() + i * ud);
    std::copy(bb, bb + 4, bary.data() + 4 * i);
    cell[i] = static_cast<std::int32_t>(bestCell);
    next[i] = head[static_cast<std::size_t>(bestKey)];
    head[static_cast<std::size_t>(bestKey)] = static_cast<std::int32_t>(i);
  }
  // The new sites in cell order (cache-friendly walks; ties keep placement order).
  std::vector<std::pair<std::int32_t, std::size_t>> order(n - nf);
  for (std::size_t i = nf; i < n; ++i)
    order[i - nf] = { cell[i], i };
  std::sort(order.begin(), order.end());
  for (std::size_t i = 0; i < n - nf; ++i)
  {
    const std::size_t o = order[i].second;
    s.CellIds[i] = cell[o];
    std::copy_n(bary.data() + 4 * o, 4, s.Bary.data() + 4 * i);
    std::copy_n(x.data() + o * ud, ud, s.Coords.data() + i * ud);
  }
}

/**
 * Initial sites: cells drawn proportionally to their embedded measure (stratified along a
 * Morton order of the input-space cell centroids when options.StratifiedInitialSites),
 * uniform barycentrics inside the cell; sites ordered by cell id.
 */
void InitialSites(const SimplexMesh& mesh, const Embedding& emb, const std::vector<double>& meas,
  const ParticleSamplerOptions& opt, const FeatureSitePlacement& placed, ParticleSamplerResult& res)
{
  const int k = mesh.SimplexDim, nv = k + 1, dim = emb.Dim, m = mesh.AmbientDim;
  const std::size_t nc = mesh.NumCells(), n = opt.NumSites;
  const std::size_t nfixed = placed.Sites.NumSites(), nfree = n - nfixed;
  std::vector<std::size_t> cellOrder(nc);
  for (std::size_t c = 0; c < nc; ++c)
    cellOrder[c] = c;
  if (opt.StratifiedInitialSites)
  {
    double lo[3] = { 0, 0, 0 }, hi[3] = { 0, 0, 0 }, ext[3] = { 0, 0, 0 };
    for (int d = 0; d < m; ++d)
    {
      lo[d] = std::numeric_limits<double>::infinity();
      hi[d] = -lo[d];
    }
    for (std::size_t v = 0; v < mesh.NumPoints(); ++v)
      for (int d = 0; d < m; ++d)
      {
        lo[d] = std::min(lo[d], mesh.Point(v)[d]);
        hi[d] = std::max(hi[d], mesh.Point(v)[d]);
      }
    for (int d = 0; d < m; ++d)
      ext[d] = hi[d] - lo[d];
    std::vector<std::pair<std::uint32_t, std::size_t>> keys(nc);
    for (std::size_t c = 0; c < nc; ++c)
    {
      const std::int32_t* ids = mesh.Cell(c);
      double p[3] = { 0, 0, 0 };
      for (int j = 0; j < nv; ++j)
        for (int d = 0; d < m; ++d)
          p[d] += mesh.Point(ids[j])[d] / nv;
      keys[c] = { Morton(p, lo, ext, m), c };
    }
    std::sort(keys.begin(), keys.end());
    for (std::size_t c = 0; c < nc; ++c)
      cellOrder[c] = keys[c].second;
  }

  Rng rng(opt.Seed);
  // Best-candidate start: the free sites placed by BestCandidateSites around the feature
  // sites, merged in below.
  ParticleSamplerResult best;
  const bool bestCandidate = opt.InitialCandidates > 1;
  if (bestCandidate)
  {
    best.Sites.Dim = dim;
    best.Sites.CellIds.resize(nfree);
    best.Sites.Bary.assign(4 * nfree, 0.0);
    best.Sites.Coords.assign(nfree * static_cast<std::size_t>(dim), 0.0);
    BestCandidateSites(mesh, emb, meas, opt, rng, placed.Sites, best);
  }
  std::vector<std::pair<std::size_t, std::size_t>> draws(n); // (cell, draw index)
  if (bestCandidate)
    for (std::size_t i = 0; i < nfree; ++i)
      draws[i] = { static_cast<std::size_t>(best.Sites.CellIds[i]), i };
  else
  {
    const std::vector<std::size_t> chosen =
      StratifiedDraw(cellOrder, meas, nfree, opt.StratifiedInitialSites, rng);
    for (std::size_t i = 0; i < nfree; ++i)
      draws[i] = { chosen[i], i };
  }
  // Feature sites after the free draws (indices nfree..n-1), sorted in with them.
  for (std::size_t j = 0; j < nfixed; ++j)
    draws[nfree + j] = { static_cast<std::size_t>(placed.Sites.CellIds[j]), nfree + j };
  // Particles in cell order: neighbouring cells are usually close in memory, which makes the
  // walks, tree queries and energy sums cache friendly (ties keep draw order).
  std::sort(draws.begin(), draws.end());
  SiteSet& s = res.Sites;
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::size_t c = draws[i].first;
    double* b = s.Bary.data() + 4 * i;
    s.CellIds[i] = static_cast<std::int32_t>(c);
    if (draws[i].second >= nfree)
    {
      const std::size_t j = draws[i].second - nfree;
      std::copy_n(placed.Sites.Bary.data() + 4 * j, 4, b);
      std::copy_n(placed.Sites.At(j), dim, s.Coords.data() + i * static_cast<std::size_t>(dim));
      res.FeatureEdge[i] = placed.Edge[j];
      res.FeatureKind[i] = static_cast<std::int8_t>(placed.Edge[j] < 0 ? 2 : 1);
      continue;
    }
    if (bestCandidate)
    {
      const std::size_t j = draws[i].second;
      std::copy_n(best.Sites.Bary.data() + 4 * j, 4, b);
      std::copy_n(best.Sites.At(j), dim, s.Coords.data() + i * static_cast<std::size_t>(dim));
      continue;
    }
    UniformBary(rng, nv, b);
    const std::int32_t* ids = mesh.Cell(c);
    for (int j = 0; j < nv; ++j)
      for (int d = 0; d < dim; ++d)
        s.Coords[i * static_cast<std::size_t>(dim) + static_cast<std::size_t>(d)] +=
          b[j] * emb.At(static_cast<std::size_t>(ids[j]))[d];
  }
}

} // namespace



ParticleSamplerResult SampleParticles(
  const SimplexMesh& mesh, const Embedding& embedding, const ParticleSamplerOptions& opt)
{
  const auto t0 = std::chrono::steady_clock::now();
  CheckInputs(mesh, embedding);
  if (opt.NumSites == 0)
    throw InputError("SampleParticles: NumSites must be at least 1");
  if (opt.NumSites > 8 * mesh.NumPoints())
    throw InputError("SampleParticles: NumSites (" + std::to_string(opt.NumSites) +
      ") exceeds 8 x the number of mesh points (" + std::to_string(8 * mesh.NumPoints()) +
      "); refine the input mesh or ask for fewer sites");
  if (opt.Iterations < 0 || opt.WarmupIterations < 0 || !(opt.KernelWidthFactor > 0.0) ||
    !std::isfinite(opt.KernelWidthFactor) || !(opt.WarmupKernelWidthFactor > 0.0) ||
    !std::isfinite(opt.WarmupKernelWidthFactor) || !(opt.NeighbourCutoff > 0.0) ||
    !std::isfinite(opt.NeighbourCutoff) || opt.History < 1 || opt.MaxThreads < 0 ||
    opt.InitialCandidates < 1 || !std::isfinite(opt.FeatureAngle) || !(opt.FeatureAngle > 0.0) ||
    !std::isfinite(opt.FeatureSpacingFactor) || opt.FeatureSpacingFactor < 0.0)
    throw InputError("SampleParticles: Iterations >= 0, WarmupIterations >= 0, History >= 1, "
                     "InitialCandidates >= 1, MaxThreads >= 0, FeatureAngle > 0, "
                     "FeatureSpacingFactor >= 0 and a positive, finite "
                     "KernelWidthFactor, "
                     "WarmupKernelWidthFactor and NeighbourCutoff are required");

  const int k = mesh.SimplexDim, dim = embedding.Dim;
  const std::size_t nc = mesh.NumCells(), n = opt.NumSites;
  const std::vector<double> meas = EmbeddedCellMeasures(mesh, embedding);
  double total = 0.0;
  for (std::size_t c = 0; c < nc; ++c)
    total += meas[c];
  if (!(total > 0.0) || !std::isfinite(total))
    throw InputError("SampleParticles: the embedded mesh has zero (or non-finite) measure");

  ParticleSamplerResult res;
  res.EmbeddedMeasure = total;
  res.Sigma = opt.KernelWidthFactor * std::pow(total / static_cast<double>(n), 1.0 / k);
  SiteSet& s = res.Sites;
  s.Dim = dim;
  s.CellIds.resize(n);
  s.Bary.assign(4 * n, 0.0);
  s.Coords.assign(n * static_cast<std::size_t>(dim), 0.0);
  res.FeatureKind.assign(n, 0);
  res.FeatureEdge.assign(n, -1);

  // Sharp features: corner and feature-line particles placed first, the rest drawn as usual.
  SharpFeatures features;
  FeatureSitePlacement placed;
  placed.Sites.Dim = dim;
  if (opt.PreserveSharpFeatures && opt.FeatureAngle < 180.0)
  {
    features = DetectSharpFeatures(mesh, opt.FeatureAngle);
    if (!features.Corners.empty() || features.NumEdges() > 0)
    {
      const double factor = opt.FeatureSpacingFactor > 0.0 ? opt.FeatureSpacingFactor
                                                           : (k == 3 ? 1.26 : 1.075);
      placed = PlaceFeatureSites(
        mesh, embedding, features, factor * std::pow(total / static_cast<double>(n), 1.0 / k));
      // Too few sites for the features (a coarse sampling of a domain with many corners or
      // long edges): keep what fits in half of the sites, and say so.
      const std::size_t lineSites = placed.Sites.NumSites() - placed.NumCorners;
      if (2 * placed.Sites.NumSites() > n)
      {
        const bool cornersFit = 2 * placed.NumCorners <= n;
        res.FeatureWarning = std::to_string(n) + " sites are too few for the sharp features (" +
          std::to_string(placed.NumCorners) + " corners and " + std::to_string(lineSites) +
          " sites on feature lines would take more than half): " +
          (cornersFit ? "only the corners are kept" : "features ignored") +
          "; ask for more sites to keep them";
        placed.Sites.CellIds.resize(cornersFit ? placed.NumCorners : 0);
        placed.Sites.Bary.resize(4 * placed.Sites.CellIds.size());
        placed.Sites.Coords.resize(placed.Sites.CellIds.size() * static_cast<std::size_t>(dim));
        placed.Edge.resize(placed.Sites.CellIds.size());
        placed.NumCorners = placed.Sites.CellIds.size();
      }
      res.NumCornerSites = placed.NumCorners;
      res.NumFeatureLineSites = placed.Sites.NumSites() - placed.NumCorners;
    }
  }
  InitialSites(mesh, embedding, meas, opt, placed, res);

  auto run = [&]()
  {
    const VertexCells nbrs = BuildVertexCells(mesh);
    const SharpFeatures* featurePtr = placed.Sites.NumSites() > 0 ? &features : nullptr;
    switch (dim)
    {
      case 2:
        RunDim<2>(mesh, embedding, nbrs, featurePtr, opt, res);
        break;
      case 3:
        RunDim<3>(mesh, embedding, nbrs, featurePtr, opt, res);
        break;
      case 4:
        RunDim<4>(mesh, embedding, nbrs, featurePtr, opt, res);
        break;
      case 5:
        RunDim<5>(mesh, embedding, nbrs, featurePtr, opt, res);
        break;
      case 6:
        RunDim<6>(mesh, embedding, nbrs, featurePtr, opt, res);
        break;
      case 8:
        RunDim<8>(mesh, embedding, nbrs, featurePtr, opt, res);
        break;
      default:
        RunDim<Eigen::Dynamic>(mesh, embedding, nbrs, featurePtr, opt, res);
        break;
    }
  };
  if (opt.MaxThreads > 0)
  {
    tbb::task_arena arena(opt.MaxThreads);
    arena.execute(run);
  }
  else
    run();
  res.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

} // namespace av
