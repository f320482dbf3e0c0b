// SPDX-License-Identifier: BSD-3-Clause
// FeatureSiteLookup: which feature edge of a triangle surface a site lies on. The sampler puts
// a feature-line site on an edge of its triangle (the barycentric coordinate opposite that edge
// is exactly 0), so the lookup is one hash probe per zero coordinate. Shared by the feature-edge
// recovery and the crease slide of the final mesh improvement.
#ifndef av_FeatureSiteLookup_h
#define av_FeatureSiteLookup_h

#include "RestrictedDelaunay.h"
#include "SharpFeatures.h"
#include "SimplexMesh.h"

#include <cstdint>
#include <unordered_map>

namespace av
{

class FeatureSiteLookup
{
public:
  /// `features` must outlive the lookup.
  explicit FeatureSiteLookup(const SharpFeatures& features);

  /// The index (into features.Edges / 2) of the feature edge (u, v), either order; -1 if none.
  std::int32_t Find(std::int32_t u, std::int32_t v) const;

  /// The feature edge holding site s of `sites` (on triangles of `mesh`): the first edge of its
  /// triangle whose opposite barycentric coordinate is exactly 0 and which is a feature edge;
  /// -1 if none (or a bad cell id). `t`, if given: the site's parameter along that edge from
  /// its first point (the order of features.Edges).
  std::int32_t EdgeOfSite(
    const SimplexMesh& mesh, const SiteSet& sites, std::size_t s, double* t = nullptr) const;

private:
  const SharpFeatures& Features;
  std::unordered_map<std::uint64_t, std::int32_t> Index; // (smaller id, larger id) -> edge
};

} // namespace av

#endif
