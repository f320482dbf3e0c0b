// SPDX-License-Identifier: BSD-3-Clause
// FeatureSites: initial particles on the sharp features of an embedded mesh (one at each
// corner, evenly spaced ones along the feature lines), VTK-free. Paper §4.1: "constrain the
// movement of the particles along the feature edges or fix the feature corners".
#ifndef av_FeatureSites_h
#define av_FeatureSites_h

#include "SharpFeatures.h"
#include "SimplexMesh.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{

/// Sites placed on the features: the corners first, then the line sites chain by chain.
struct FeatureSitePlacement
{
  SiteSet Sites;                   ///< embedded coords, a cell containing each, barycentrics
  std::vector<std::int32_t> Edge;  ///< per site: its feature edge (index into Edges / 2), -1 at corners
  std::size_t NumCorners = 0;      ///< the first NumCorners sites are the corners
  std::size_t NumChains = 0;       ///< feature lines between corners, plus closed loops
  double FeatureLength = 0.0;      ///< embedded length of all feature edges
};

/**
 * Places one site at every corner of `features` and, along each chain of feature edges
 * (between two corners, or a closed loop), round(L / spacing) - 1 sites (L the chain's
 * embedded length; round(L / spacing) on a loop, at least one) at equal embedded arc-length
 * steps. The sites' embedded coordinates interpolate `embedding` linearly on their edge.
 * Throws InputError on a non-positive / non-finite spacing or sizes that do not match.
 */
FeatureSitePlacement PlaceFeatureSites(const SimplexMesh& mesh, const Embedding& embedding,
  const SharpFeatures& features, double spacing);

/// The feature edge that continues edge `edge` through its point `point` (a non-corner point
/// on exactly two feature edges), or -1 (a corner, a free end or a junction).
std::int32_t NextFeatureEdge(const SharpFeatures& features, std::int32_t edge, std::int32_t point);

} // namespace av

#endif
