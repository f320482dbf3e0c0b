// SPDX-License-Identifier: BSD-3-Clause
// DomainAngleBound: how small the domain's own dihedral angles are in the metric. Where the
// boundary meets itself at an angle alpha along an edge, every tet mesh of that domain has a
// tet with a dihedral angle of at most alpha there, so no mesh improvement can push theta_min
// (paper §5.2) above the smallest such alpha.
#ifndef av_DomainAngleBound_h
#define av_DomainAngleBound_h

#include "SimplexMesh.h"

#include <cstddef>

namespace av
{

/// The result of ComputeDomainAngleBound.
struct DomainAngleBound
{
  /// The smallest interior angle of the domain at a boundary edge, in the metric, degrees; 90
  /// when none is below 90 (a larger angle can always be split into tets with better angles).
  double MinAngle = 90.0;
  std::size_t NumBoundaryEdges = 0;
  std::size_t NumBelow15 = 0; ///< boundary edges whose angle is below 15 degrees (the §5.2 bar)
  std::size_t NumBelow20 = 0; ///< ... below 20 degrees
};

/**
 * For each boundary edge (a, b) of the tet mesh (an edge of a face that one tet has), the sum
 * of the dihedral angles at (a, b) of the tets around it, after the mapping A = (M_a^{1/2} +
 * M_b^{1/2}) / 2 of the edge (as the §5.1 edge length): the domain's interior angle there in
 * the metric. A mesh of the same domain evaluated as EvaluateMeshQuality does maps each tet by
 * the mean root of its four vertices instead, so near a strongly varying metric the bound is
 * approximate. `metric`: one 6-value SPD metric per point (MetricField order). Throws InputError
 * on wrong sizes, bad ids, non-finite values or a mesh that is not made of tets.
 */
DomainAngleBound ComputeDomainAngleBound(const SimplexMesh& tets, const MetricField& metric);

} // namespace av

#endif
