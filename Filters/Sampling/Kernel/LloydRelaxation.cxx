// SPDX-License-Identifier: BSD-3-Clause
// LloydRelaxation: Lloyd steps on the restricted Voronoi diagram (piece centroids by fanning,
// exact closest points on the embedded elements) and the CVT energy.
#include "LloydRelaxation.h"

#include "MeshTopology.h"
#include "RestrictedVoronoi.h"
#include "Stopwatch.h"

#include <Eigen/Dense>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace av
{
namespace
{
using SmallMat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 5, 5>;
using SmallVec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 5, 1>;

/// Per element: input-space -> barycentric map, Gram of the embedded vertices, measure.
struct ElementData
{
  int K = 3, Amb = 3, Dim = 8;
  std::vector<double> Inv;  ///< K x Amb per element: (x - p0) -> (l1..lK)
  std::vector<double> Gram; ///< (K+1)^2 per element: e_i . e_j
  std::vector<double> Measure; ///< embedded measure
  std::vector<std::uint8_t> Boundary; ///< bit a: facet opposite local vertex a is on the boundary
};

ElementData Precompute(const SimplexMesh& mesh, const Embedding& emb)
{
  ElementData d;
  d.K = mesh.SimplexDim;
  d.Amb = mesh.AmbientDim;
  d.Dim = emb.Dim;
  const int K = d.K, A = d.Amb, V = K + 1;
  const std::size_t nc = mesh.NumCells();
  d.Inv.assign(nc * K * A, 0.0);
  d.Gram.assign(nc * V * V, 0.0);
  d.Measure = EmbeddedCellMeasures(mesh, emb);
  const std::vector<std::int32_t> adj = ComputeElementAdjacency(mesh);
  d.Boundary.assign(nc, 0);
  for (std::size_t c = 0; c < nc; ++c)
    for (int a = 0; a < V; ++a)
      if (adj[c * V + a] < 0)
        d.Boundary[c] |= static_cast<std::uint8_t>(1 << a);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nc), [&](const auto& r) {
    for (std::size_t c = r.begin(); c != r.end(); ++c)
    {
      const std::int32_t* v = mesh.Cell(c);
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3> e(A, K);
      for (int j = 0; j < K; ++j)
        for (int a = 0; a < A; ++a)
          e(a, j) = mesh.Point(v[j + 1])[a] - mesh.Point(v[0])[a];
      // Pseudo-inverse (E^T E)^{-1} E^T: also right for triangles on a 3D surface.
      const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3> g = e.transpose() * e;
      const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3> inv =
        g.ldlt().solve(e.transpose());
      for (int j = 0; j < K; ++j)
        for (int a = 0; a < A; ++a)
          d.Inv[(c * K + j) * A + a] = inv(j, a);
      for (int i = 0; i < V; ++i)
        for (int j = i; j < V; ++j)
        {
          const double* pi = emb.At(v[i]);
          const double* pj = emb.At(v[j]);
          double s = 0.0;
          for (int k = 0; k < d.Dim; ++k)
            s += pi[k] * pj[k];
          d.Gram[c * V * V + i * V + j] = d.Gram[c * V * V + j * V + i] = s;
        }
    }
  });
  return d;
}

/// Barycentric coordinates (K+1) of an input-space point in element c.
void ToBary(const SimplexMesh& mesh, const ElementData& d, std::size_t c, const double* x,
  double* lambda)
{
  const double* p0 = mesh.Point(mesh.Cell(c)[0]);
  double sum = 0.0;
  for (int j = 0; j < d.K; ++j)
  {
    double s = 0.0;
    for (int a = 0; a < d.Amb; ++a)
      s += d.Inv[(c * d.K + j) * d.Amb + a] * (x[a] - p0[a]);
    lambda[j + 1] = s;
    sum += s;
  }
  lambda[0] = 1.0 - sum;
}

/// Signed lambda-space measure fraction of a fan simplex (vertices given by barycentrics).
double FanFraction(int K, const double* a, const double* b, const double* c, const double* dd)
{
  if (K == 2)
  {
    return (b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]);
  }
  Eigen::Matrix3d m;
  for (int i = 0; i < 3; ++i)
  {
    m(i, 0) = b[i + 1] - a[i + 1];
    m(i, 1) = c[i + 1] - a[i + 1];
    m(i, 2) = dd[i + 1] - a[i + 1];
  }
  return m.determinant();
}

/// Closest point of z to the embedded simplex of element c (exact: every face is tried).
/// Returns the squared distance minus |z|^2 and writes the barycentrics.
double ClosestOnElement(const SimplexMesh& mesh, const Embedding& emb, const ElementData& d,
  std::size_t c, const double* z, double* best)
{
  const int V = d.K + 1;
  const std::int32_t* v = mesh.Cell(c);
  double q[4];
  for (int i = 0; i < V; ++i)
  {
    const double* p = emb.At(v[i]);
    double s = 0.0;
    for (int k = 0; k < d.Dim; ++k)
      s += p[k] * z[k];
    q[i] = s;
  }
  const double* G = d.Gram.data() + c * V * V;
  double bestPhi = std::numeric_limits<double>::infinity();
  int idx[4];
  for (int mask = 1; mask < (1 << V); ++mask)
  {
    int m = 0;
    for (int i = 0; i < V; ++i)
      if (mask & (1 << i))
        idx[m++] = i;
    double lam[4] = { 0, 0, 0, 0 };
    if (m == 1)
    {
      lam[idx[0]] = 1.0;
    }
    else
    {
      // KKT of min l^T G l - 2 q^T l subject to sum l = 1 on the face.
      SmallMat kkt(m + 1, m + 1);
      SmallVec rhs(m + 1);
      for (int a = 0; a < m; ++a)
      {
        for (int b = 0; b < m; ++b)
          kkt(a, b) = G[idx[a] * V + idx[b]];
        kkt(a, m) = kkt(m, a) = 1.0;
        rhs(a) = q[idx[a]];
      }
      kkt(m, m) = 0.0;
      rhs(m) = 1.0;
      const SmallVec sol = kkt.fullPivLu().solve(rhs);
      bool ok = sol.allFinite();
      for (int a = 0; a < m && ok; ++a)
      {
        ok = sol(a) >= -1e-12;
        lam[idx[a]] = std::max(0.0, sol(a));
      }
      if (!ok)
        continue;
      double s = 0.0;
      for (int a = 0; a < V; ++a)
        s += lam[a];
      for (int a = 0; a < V; ++a)
        lam[a] /= s;
    }
    double phi = 0.0;
    for (int a = 0; a < V; ++a)
    {
      double ga = 0.0;
      for (int b = 0; b < V; ++b)
        ga += G[a * V + b] * lam[b];
      phi += lam[a] * (ga - 2.0 * q[a]);
    }
    if (phi < bestPhi)
    {
      bestPhi = phi;
      std::copy(lam, lam + 4, best);
    }
  }
  return bestPhi;
}

/// Pieces of the diagram grouped by site (CSR: Order[Offsets[s] .. Offsets[s + 1]) are site
/// s's pieces), in element order: the per-site sums are deterministic.
struct SitePieces
{
  std::vector<std::int64_t> Offsets, Order;
};

SitePieces GroupPiecesBySite(const RestrictedVoronoiDiagram& rvd, std::size_t ns)
{
  const std::size_t np = rvd.NumPieces();
  SitePieces g;
  g.Offsets.assign(ns + 1, 0);
  for (std::size_t p = 0; p < np; ++p)
    ++g.Offsets[rvd.PieceSite[p] + 1];
  for (std::size_t s = 0; s < ns; ++s)
    g.Offsets[s + 1] += g.Offsets[s];
  g.Order.resize(np);
  std::vector<std::int64_t> fill(g.Offsets.begin(), g.Offsets.end() - 1);
  for (std::size_t p = 0; p < np; ++p)
    g.Order[fill[rvd.PieceSite[p]]++] = static_cast<std::int64_t>(p);
  return g;
}

/// Moments of one piece in its element's barycentric coordinates: signed lambda-space measure
/// F, F times the mean of |E l - s|^2 (M) and the first moment C of the barycentrics.
struct PieceMoments
{
  double F = 0.0, M = 0.0, C[4] = { 0, 0, 0, 0 };
};

/// The moments of piece p of `rvd` about `site` (ss = |site|^2), from the piece fanned into
/// triangles / tetrahedra. lam: scratch for the barycentrics of the piece's vertices.
PieceMoments FanPiece(const SimplexMesh& mesh, const Embedding& emb, const ElementData& d,
  const RestrictedVoronoiDiagram& rvd, std::size_t p, const double* site, double ss,
  std::vector<double>& lam)
{
  const int K = d.K, V = K + 1, Dim = d.Dim, A = d.Amb;
  const std::size_t c = static_cast<std::size_t>(rvd.PieceElement[p]);
  const std::int32_t* cv = mesh.Cell(c);
  const std::int64_t v0 = rvd.PieceVertexOffsets[p], v1 = rvd.PieceVertexOffsets[p + 1];
  lam.resize(static_cast<std::size_t>((v1 - v0) * V));
  for (std::int64_t i = v0; i < v1; ++i)
    ToBary(mesh, d, c, rvd.Points.data() + i * A, lam.data() + (i - v0) * V);
  const double* G = d.Gram.data() + c * V * V;
  double h[4] = { 0, 0, 0, 0 };
  for (int i = 0; i < V; ++i)
  {
    const double* e = emb.At(cv[i]);
    for (int k = 0; k < Dim; ++k)
      h[i] += e[k] * site[k];
  }
  // quad(l) = |E l - s|^2 = l^T G l - 2 h^T l + |s|^2 (l need not sum to 1).
  auto quad = [&](const double* l, double scale) {
    double r2 = 0.0;
    for (int a = 0; a < V; ++a)
    {
      double ga = 0.0;
      for (int b = 0; b < V; ++b)
        ga += G[a * V + b] * l[b];
      r2 += l[a] * (ga - 2.0 * scale * h[a]);
    }
    return r2 + scale * scale * ss;
  };
  PieceMoments m;
  auto addSimplex = [&](const double* a, const double* b, const double* cc, const double* dd) {
    const double f = FanFraction(K, a, b, cc, dd);
    const double* vs[4] = { a, b, cc, dd };
    double sumL[4] = { 0, 0, 0, 0 }, q = 0.0;
    for (int i = 0; i < V; ++i)
    {
      q += quad(vs[i], 1.0);
      for (int j = 0; j < V; ++j)
        sumL[j] += vs[i][j];
    }
    q += quad(sumL, static_cast<double>(V));
    m.F += f;
    m.M += f * q;
    for (int j = 0; j < V; ++j)
      m.C[j] += f * sumL[j] / V;
  };
  auto L = [&](std::int64_t id) { return lam.data() + (id - v0) * V; };
  if (K == 2)
  {
    for (std::int64_t i = v0 + 1; i + 1 < v1; ++i)
      addSimplex(L(v0), L(i), L(i + 1), nullptr);
    return m;
  }
  const std::int64_t f0 = rvd.PieceFaceOffsets[p], f1 = rvd.PieceFaceOffsets[p + 1];
  const double* apex = L(rvd.FaceVertices[rvd.FaceOffsets[f0]]);
  for (std::int64_t f = f0; f < f1; ++f)
  {
    const std::int64_t a = rvd.FaceOffsets[f], b = rvd.FaceOffsets[f + 1];
    for (std::int64_t i = a + 1; i + 1 < b; ++i)
      addSimplex(apex, L(rvd.FaceVertices[a]), L(rvd.FaceVertices[i]),
        L(rvd.FaceVertices[i + 1]));
  }
  return m;
}

/// Site s lies on a boundary facet of its element (barycentric 0 there).
bool OnBoundary(const ElementData& d, const SiteSet& sites, std::size_t s)
{
  const int V = d.K + 1;
  const std::uint8_t bm = d.Boundary[static_cast<std::size_t>(sites.CellIds[s])];
  bool onBoundary = false;
  for (int a = 0; a < V; ++a)
    onBoundary = onBoundary || ((bm & (1 << a)) && sites.Bary[s * 4 + a] <= 1e-12);
  return onBoundary;
}

/**
 * Moves site s of `next` to the closest point of the centroid z on the embedded mesh: the
 * candidate elements are those of its cell plus the site's own element, so the new site is
 * never farther from the centroid than the old one (energy decreases). Returns the move.
 */
double ProjectCentroid(const SimplexMesh& mesh, const Embedding& emb, const ElementData& d,
  const RestrictedVoronoiDiagram& rvd, const SitePieces& pieces, const SiteSet& sites,
  std::size_t s, const std::vector<double>& z, SiteSet& next)
{
  const int V = d.K + 1, Dim = d.Dim;
  double bestPhi = std::numeric_limits<double>::infinity(), bestLam[4] = { 0, 0, 0, 0 };
  std::int32_t bestCell = sites.CellIds[s];
  auto tryCell = [&](std::size_t c) {
    double l[4] = { 0, 0, 0, 0 };
    const double phi = ClosestOnElement(mesh, emb, d, c, z.data(), l);
    if (phi < bestPhi)
    {
      bestPhi = phi;
      bestCell = static_cast<std::int32_t>(c);
      std::copy(l, l + 4, bestLam);
    }
  };
  tryCell(static_cast<std::size_t>(sites.CellIds[s]));
  for (std::int64_t o = pieces.Offsets[s]; o < pieces.Offsets[s + 1]; ++o)
  {
    const std::size_t c = static_cast<std::size_t>(rvd.PieceElement[pieces.Order[o]]);
    if (c != static_cast<std::size_t>(sites.CellIds[s]))
      tryCell(c);
  }
  const std::int32_t* cv = mesh.Cell(static_cast<std::size_t>(bestCell));
  const double* site = sites.At(s);
  double* out = next.Coords.data() + s * Dim;
  double mv = 0.0;
  for (int k = 0; k < Dim; ++k)
  {
    double x = 0.0;
    for (int i = 0; i < V; ++i)
      x += bestLam[i] * emb.At(cv[i])[k];
    mv += (x - site[k]) * (x - site[k]);
    out[k] = x;
  }
  next.CellIds[s] = bestCell;
  for (int i = 0; i < 4; ++i)
    next.Bary[s * 4 + i] = i < V ? bestLam[i] : 0.0;
  return std::sqrt(mv);
}

/// One RVD + centroid pass: returns the CVT energy of `sites`; moves them when `next` is set.
double LloydPass(const SimplexMesh& mesh, const Embedding& emb, const ElementData& d,
  const SiteSet& sites, SiteSet* next, double* meanMove, bool keepBoundary,
  std::size_t* numFixed)
{
  RestrictedVoronoiOptions vo;
  vo.ComputeGeometry = true;
  vo.KeepEmbeddedPoints = false; // vertices are mapped through barycentrics instead
  const RestrictedVoronoiDiagram rvd = ComputeRestrictedVoronoi(mesh, emb, sites, vo);

  const std::size_t ns = sites.NumSites();
  const int K = d.K, V = K + 1, Dim = d.Dim;
  const SitePieces pieces = GroupPiecesBySite(rvd, ns);
  std::vector<double> siteEnergy(ns, 0.0), move(ns, 0.0);
  std::vector<char> fixed(ns, 0);
  if (next)
    *next = sites;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, ns), [&](const auto& r) {
    std::vector<double> lam; // barycentrics of one piece's vertices
    std::vector<double> z(Dim);
    for (std::size_t s = r.begin(); s != r.end(); ++s)
    {
      const double* site = sites.At(s);
      double ss = 0.0;
      for (int k = 0; k < Dim; ++k)
        ss += site[k] * site[k];
      std::fill(z.begin(), z.end(), 0.0);
      double wsum = 0.0, energy = 0.0;
      for (std::int64_t o = pieces.Offsets[s]; o < pieces.Offsets[s + 1]; ++o)
      {
        const std::size_t p = static_cast<std::size_t>(pieces.Order[o]);
        const std::size_t c = static_cast<std::size_t>(rvd.PieceElement[p]);
        const PieceMoments m = FanPiece(mesh, emb, d, rvd, p, site, ss, lam);
        if (m.F == 0.0)
          continue;
        const double sign = m.F < 0.0 ? -1.0 : 1.0;
        const double w = sign * m.F * d.Measure[c];
        energy += sign * m.M * d.Measure[c] / ((K + 1) * (K + 2));
        // Embedded centroid of the piece: E (C / F), weighted by its embedded measure.
        const std::int32_t* cv = mesh.Cell(c);
        for (int i = 0; i < V; ++i)
        {
          const double coef = w * m.C[i] / m.F;
          const double* e = emb.At(cv[i]);
          for (int k = 0; k < Dim; ++k)
            z[k] += coef * e[k];
        }
        wsum += w;
      }
      siteEnergy[s] = energy;
      if (!next || wsum <= 0.0)
        continue;
      for (int k = 0; k < Dim; ++k)
        z[k] /= wsum;
      if (keepBoundary && OnBoundary(d, sites, s))
      {
        fixed[s] = 1; // stays: keeps the boundary layer that the particle sampler built
        continue;
      }
      move[s] = ProjectCentroid(mesh, emb, d, rvd, pieces, sites, s, z, *next);
    }
  });
  double total = 0.0, mv = 0.0;
  for (std::size_t s = 0; s < ns; ++s)
  {
    total += siteEnergy[s];
    mv += move[s];
  }
  if (numFixed)
    *numFixed = static_cast<std::size_t>(std::count(fixed.begin(), fixed.end(), 1));
  if (meanMove)
    *meanMove = ns ? mv / static_cast<double>(ns) : 0.0;
  return total;
}
} // namespace

LloydResult RelaxSitesLloyd(const SimplexMesh& mesh, const Embedding& embedding,
  const SiteSet& sites, int iterations, bool keepBoundarySites)
{
  const Stopwatch clock;
  if (iterations < 0)
  {
    throw InputError("RelaxSitesLloyd: the number of Lloyd iterations must be >= 0, got " +
      std::to_string(iterations));
  }
  ValidateRestrictedVoronoiInput(mesh, embedding, sites);
  LloydResult r;
  r.Sites = sites;
  if (iterations > 0)
  {
    const ElementData d = Precompute(mesh, embedding);
    for (int it = 0; it < iterations; ++it)
    {
      SiteSet next;
      double mv = 0.0;
      r.Energy.push_back(LloydPass(mesh, embedding, d, r.Sites, &next, &mv, keepBoundarySites,
        &r.FixedBoundarySites));
      r.MeanMove.push_back(mv);
      r.Sites = std::move(next);
      ++r.IterationsDone;
    }
  }
  r.Seconds = clock.Seconds();
  return r;
}

double ComputeCVTEnergy(const SimplexMesh& mesh, const Embedding& embedding, const SiteSet& sites)
{
  ValidateRestrictedVoronoiInput(mesh, embedding, sites);
  const ElementData d = Precompute(mesh, embedding);
  return LloydPass(mesh, embedding, d, sites, nullptr, nullptr, false, nullptr);
}

} // namespace av
