// SPDX-License-Identifier: BSD-3-Clause
// SliverPerturbation: moves the sites of sliver tetrahedra of a restricted Delaunay mesh apart
// along the sliver's flat direction, keeping every site on the embedded mesh (not in the
// paper; see Filters/Delaunay/README.md). The caller recomputes the RVD / RDT of the moved sites.
#ifndef av_SliverPerturbation_h
#define av_SliverPerturbation_h

#include "RestrictedDelaunay.h"
#include "SimplexMesh.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{

/// Options of PerturbSliverSites.
struct SliverPerturbationOptions
{
  /// A dual tetrahedron whose smallest dihedral angle, measured with the sites' embedded
  /// coordinates, is below this (degrees) is a sliver (§5.2 counts < 15 deg as bad).
  double MinDihedralDegrees = 15.0;
  /// Each sliver pushes its four sites this fraction of its mean embedded edge length away
  /// from its best-fit plane (a site of several slivers gets the sum of the pushes).
  double StepFraction = 0.07;
  /// ComputeElementAdjacency(mesh) if the caller has it (nullptr: computed here).
  const std::vector<std::int32_t>* ElementAdjacency = nullptr;
  /// Per site, nonzero: never moved (e.g. the sampler's corner and feature-line sites, which
  /// a push would take off their feature). nullptr: every site may move.
  const std::vector<std::uint8_t>* FixedSites = nullptr;
};

/// Output of PerturbSliverSites.
struct SliverPerturbationResult
{
  SiteSet Sites;                ///< same count and order as the input, moved ones updated
  std::size_t NumSlivers = 0;   ///< slivers found in the input mesh
  std::size_t NumMovedSites = 0;
  std::vector<double> MinDihedral; ///< per cell of the input RDT, degrees (embedded coordinates)
};

/**
 * For every sliver of `rdt` (a tet mesh whose point ids are site ids), the four sites are
 * centered, the normal n of their best-fit plane is the third principal direction in R^Dim,
 * and each site moves by +-StepFraction * (mean edge length) * n, on the side it already is:
 * the sliver's two crossing diagonals move apart and the tet gets volume. A move is a walk on
 * the embedded mesh (the displacement projected onto each element's tangent space, crossing
 * element faces; it stops at the domain boundary), so a moved site stays on the mesh with a
 * valid cell id and barycentric coordinates. Sites of no sliver keep their exact values.
 * Triangle meshes are returned unchanged (NumSlivers 0). Deterministic (serial).
 * Throws InputError when sizes do not match (sites vs embedding, RDT point ids out of range,
 * FixedSites not one per site).
 */
SliverPerturbationResult PerturbSliverSites(const SimplexMesh& mesh, const Embedding& embedding,
  const SiteSet& sites, const RestrictedDelaunayMesh& rdt,
  const SliverPerturbationOptions& options = SliverPerturbationOptions());

/// Smallest dihedral angle (degrees) of the tetrahedron p0..p3 in R^dim (0 if degenerate).
double MinDihedralAngle(const double* p0, const double* p1, const double* p2, const double* p3, int dim);

} // namespace av

#endif
