// SPDX-License-Identifier: BSD-3-Clause
// Internal to the Voronoi kernel: ElementFrame, the element being clipped (vertices, centroid,
// bounding radius, measures) and its cached squared distances to the sites.
#ifndef av_RestrictedVoronoiElementFrame_h
#define av_RestrictedVoronoiElementFrame_h

#include "RestrictedVoronoiContext.h"
#include "RestrictedVoronoiPrimitives.h"
#include "SimplexMesh.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{
namespace rvd
{

/// K: simplex dimension (2, 3); DIM: embedding dimension (> 0: compile time, -1: runtime).
template <int K, int DIM>
struct ElementFrame
{
  static constexpr int NV = K + 1;

  const SimplexMesh& Mesh;
  const Embedding& Emb;
  const SiteSet& Sites;
  int Dim;

  std::int32_t Elem = -1;
  const double* EV[4]; // embedded vertices
  const double* XV[4]; // input-space vertices
  double L[4][4];      // squared embedded edge lengths
  std::vector<double> Centroid;
  double Rho = 0.0; // bounding radius about the centroid (rounded up)
  double ElemMeasure = 0.0, ElemEmbMeasure = 0.0;

  ElementFrame(const SimplexMesh& m, const Embedding& e, const SiteSet& s)
    : Mesh(m)
    , Emb(e)
    , Sites(s)
    , Dim(e.Dim)
  {
  }

  /// Makes element e the current one: what a whole-element piece needs (vertices, measures);
  /// LoadClipping adds the rest.
  void LoadVertices(std::int32_t e)
  {
    Elem = e;
    const std::int32_t* cell = Mesh.Cell(e);
    for (int a = 0; a < NV; ++a)
    {
      EV[a] = Emb.At(cell[a]);
      XV[a] = Mesh.Point(cell[a]);
    }
    ElemMeasure = SimplexMeasure(XV, K, Mesh.AmbientDim);
    ElemEmbMeasure = SimplexMeasureT<DIM>(EV, K, Dim);
  }

  /// The rest of Load for the clipping: edge lengths, centroid, bounding radius.
  void LoadClipping()
  {
    for (int a = 0; a < NV; ++a)
      for (int b = 0; b < NV; ++b)
        L[a][b] = Dist2<DIM>(EV[a], EV[b], Dim);
    Centroid.assign(Dim, 0.0);
    for (int a = 0; a < NV; ++a)
      for (int d = 0; d < Dim; ++d)
        Centroid[d] += EV[a][d] / NV;
    Rho = 0.0;
    for (int a = 0; a < NV; ++a)
      Rho = std::max(Rho, std::sqrt(Dist2<DIM>(EV[a], Centroid.data(), Dim)));
    Rho *= 1.0 + 1e-12;
  }

  const double* SiteP(std::int32_t s) const { return Sites.Coords.data() + std::size_t(s) * Dim; }

  /// Squared distances element vertices -> site s (cached per element).
  const double* DRow(Context<K>& C, std::int32_t s) const
  {
    const int sl = C.SlotOf(s);
    auto& ss = C.Slots[sl];
    if (!ss.HasD)
    {
      const double* p = SiteP(s);
      for (int a = 0; a < NV; ++a)
        ss.D[a] = Dist2<DIM>(EV[a], p, Dim);
      ss.HasD = true;
    }
    return ss.D;
  }

  /// Distance centroid -> site, cached per element.
  double DCentroid(Context<K>& C, std::int32_t s) const
  {
    const int sl = C.SlotOf(s);
    auto& ss = C.Slots[sl];
    if (ss.Dc < 0.0)
      ss.Dc = std::sqrt(Dist2<DIM>(Centroid.data(), SiteP(s), Dim));
    return ss.Dc;
  }

  /// Squared distance centroid -> site, cached per element.
  double DCentroid2(Context<K>& C, std::int32_t s) const
  {
    const double d = DCentroid(C, s);
    return d * d;
  }
};

} // namespace rvd
} // namespace av

#endif
