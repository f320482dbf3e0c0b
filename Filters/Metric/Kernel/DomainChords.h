// SPDX-License-Identifier: BSD-3-Clause
// DomainChords: how thick the domain of a volume (or flat 2D) mesh is at each vertex, along a
// fixed set of directions, so that the metric preparation can keep a few cells across thin
// parts. VTK-free.
#ifndef av_DomainChords_h
#define av_DomainChords_h

#include "SimplexMesh.h"

#include <cstddef>
#include <vector>

namespace av
{

/// Chords of the domain through each vertex.
struct DomainChords
{
  int Dimension = 3;              ///< 3 (tets) or 2 (flat triangles)
  std::vector<double> Directions; ///< NumDirections x Dimension unit vectors
  std::vector<double> Chord;      ///< NumPoints x NumDirections lengths (+inf: thick)
  std::size_t NumDirections() const
  {
    return Directions.size() / static_cast<std::size_t>(Dimension);
  }
};

/**
 * For each vertex, the length of the segment of the domain along each direction through an
 * interior point next to it (the centroid of its largest element): the ray is walked from
 * element to element both ways (ComputeElementAdjacency) until it leaves the domain through a
 * boundary facet, so concave parts and holes count. Rays that cut a convex edge or corner
 * near the vertex are short too: the chords bound the distance between boundary parts seen
 * from the vertex, a local feature size, not only the thickness of thin parts (measured: the
 * sizes this gives near edges and corners are what raise the mesh quality on the CalculiX
 * parts; a filter that dropped oblique exits lost most of it). Directions: 13 in 3D (the 3 axes, 6
 * face and 4 body diagonals of a cube: any direction is within 27.4 deg of one), 8 in 2D (every
 * 22.5 deg). A walk that crosses more than `maxSteps` elements gives +inf (that chord is long
 * compared with the elements). Volume tets (SimplexDim = AmbientDim = 3) or flat triangles
 * (SimplexDim 2, AmbientDim 2, or AmbientDim 3 with one z); otherwise an InputError.
 */
DomainChords ComputeDomainChords(const SimplexMesh& mesh, int maxSteps = 256);

} // namespace av

#endif
