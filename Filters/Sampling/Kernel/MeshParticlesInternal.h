// SPDX-License-Identifier: BSD-3-Clause
// MeshParticlesInternal: particles on an embedded simplicial mesh as (cell, barycentrics): the
// per-particle cell cache, the tangent projection of gradients and the walks of moves.
#ifndef av_MeshParticlesInternal_h
#define av_MeshParticlesInternal_h

#include "FaceNeighbors.h"
#include "FeatureSites.h"
#include "SamplerDimensions.h"
#include "SharpFeatures.h"
#include "SimplexMesh.h"

#include <Eigen/Dense>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace av
{
namespace sampling
{

/**
 * The particles of the sampler on the embedded mesh (cells of `mesh` at the vertex positions of
 * `emb`, simplex dimension K, embedding dimension D or Eigen::Dynamic): a particle is a cell
 * and barycentric coordinates. Projects gradients onto the feasible tangent cone of a particle
 * and walks moves across cell faces (free particles) or along feature lines.
 */
template <int D, int K>
class MeshParticles
{
  static constexpr int NV = K + 1;

public:
  using Vec = PointVector<D>;

  /**
   * Per-particle copy of the data of one cell: the embedded vertices, face neighbors, the
   * degeneracy flag and the inverse Gram matrix of the full cell. Every particle keeps two
   * (its accepted cell and the trial cell of the line search): the hot loops then read this
   * contiguous per-particle record instead of gathering cell ids, neighbors and vertices
   * from three mesh-sized tables (L2 misses dominated the tangent projections).
   */
  struct CellData
  {
    std::int32_t Cell = -1;
    std::int32_t Ids[NV];
    std::int32_t Nbrs[NV];
    bool Degenerate = false;
    bool InverseOk = false; ///< Gram matrix of the full cell invertible (det > 0, finite)
    Eigen::Matrix3d GramInv = Eigen::Matrix3d::Identity(); ///< of the K edges v_j - v_0
    double V[NV][MaxDimOf<D>] = {};
  };

  MeshParticles(const SimplexMesh& mesh,
    const Embedding& emb,
    const VertexCells& vc,
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

  /// Room for n particles' cell caches (emptied).
  void Resize(std::size_t n) { CellCache.assign(2 * n, CellData()); }

  Eigen::Map<const Vec> Vertex(const CellData& cd, int i) const
  {
    return Eigen::Map<const Vec>(cd.V[i], Dim);
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
    const Eigen::Map<const Vec> b(
      Emb.At(static_cast<std::size_t>(Features->Edges[2 * ue + 1])), Dim);
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
  const CellData& WalkLine(std::size_t p,
    std::int32_t& cell,
    double* b,
    std::int32_t& edge,
    const Vec& d)
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
   * current cell, walked across faces into neighbors (the rest of d is re-projected there),
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
      int hit = -1;
      double t = 0.0;
      if (!StepToFace(active, db, b, t, hit))
        return *cd;
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
      ToNeighborBary(from, next.Ids, b);
      for (int j = 0; j < NV; ++j)
        active[j] = false;
      prev = cell;
      cell = nb;
      cd = &next;
    }
    return *cd;
  }

private:
  /// Copies cell `cell` into `cd` (degeneracy and the full-cell inverse computed here, only
  /// for the cells particles visit).
  void Fill(std::int32_t cell, CellData& cd) const
  {
    const std::int32_t* ids = Mesh.Cell(static_cast<std::size_t>(cell));
    cd.Cell = cell;
    for (int i = 0; i < NV; ++i)
    {
      cd.Ids[i] = ids[i];
      // Face neighbors only of the cells particles visit (all 240k of cube2 took 8% of the
      // run), memoized: a cell is refilled often. Concurrent fills store the same value.
      auto& memo = NbrMemo[static_cast<std::size_t>(cell) * NV + static_cast<std::size_t>(i)];
      std::int32_t nb = memo.load(std::memory_order_relaxed);
      if (nb == kUnknown)
      {
        nb = FaceNeighbor(Mesh, VC, static_cast<std::size_t>(cell), i);
        memo.store(nb, std::memory_order_relaxed);
      }
      cd.Nbrs[i] = nb;
      std::copy_n(Emb.At(static_cast<std::size_t>(ids[i])), Dim, cd.V[i]);
    }
    {
      Eigen::Matrix<double, D, K, Eigen::ColMajor, MaxDimOf<D>, K> e(Dim, K);
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

  /**
   * Least-squares barycentric change (sum 0, zero on `active` vertices) whose embedded
   * displacement best matches d in the cell; returns false for a degenerate cell. One
   * function on purpose: it is the hottest part of the walks and projections.
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
   * Advances the barycentrics b along db up to the first face a free coordinate reaches
   * (t in [0, 1] of the step, `hit` its local index, -1 when the whole step fits); false when
   * db is zero (nothing to walk).
   */
  static bool StepToFace(const bool active[NV], const double db[NV], double* b, double& t, int& hit)
  {
    double scale = 0.0;
    for (int i = 0; i < NV; ++i)
      scale += std::abs(db[i]);
    if (scale <= 1e-300)
      return false;
    t = 1.0;
    hit = -1;
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
    return true;
  }

  /// Rewrites barycentrics b of a point on the face shared by cells with vertex ids `from` and
  /// `to` in the cell `to`.
  static void ToNeighborBary(const std::int32_t from[NV], const std::int32_t to[NV], double* b)
  {
    double nbBary[NV];
    for (int j = 0; j < NV; ++j)
    {
      nbBary[j] = 0.0;
      for (int i = 0; i < NV; ++i)
        if (from[i] == to[j])
          nbBary[j] = b[i];
    }
    for (int j = 0; j < NV; ++j)
      b[j] = nbBary[j];
  }

  const SimplexMesh& Mesh;
  const Embedding& Emb;
  const VertexCells& VC;
  const SharpFeatures* Features; // nullptr: no feature particles
  const int Dim;
  static constexpr std::int32_t kUnknown = -2;
  std::unique_ptr<std::atomic<std::int32_t>[]> NbrMemo; // face neighbors, kUnknown: not yet
  std::vector<CellData> CellCache;                      // 2 per particle
};

} // namespace sampling
} // namespace av

#endif
