// SPDX-License-Identifier: BSD-3-Clause
// BodySeparation: moves the embeddings of separate bodies apart in R^m, so that the sampler, the
// restricted Voronoi diagram and its dual treat each body as its own domain.
#ifndef av_BodySeparation_h
#define av_BodySeparation_h

#include "SimplexMesh.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{

/**
 * Bodies of a mesh (cells connected through shared points: `pointBody` and `numBodies` from
 * LabelBodies) that touch or nearly
 * touch in space, as in an FE contact assembly, also touch in the embedding, and a site of one
 * body then owns Voronoi pieces of the other: the dual mesh joins them partly, with pinched
 * boundaries and flat tets across the contact. Each body is a domain of its own (its metric and
 * embedding are independent), so the bodies are translated along the last embedding coordinate
 * (never one of the input's AmbientDim coordinates, which stay the input points) until points of
 * different bodies are at least the largest body's diameter apart in R^m: then every point of a
 * body that holds a site is closer to that site than to any site of another body. Lengths
 * inside a body, and so the §5.1 error, do not change. Throws InputError unless there is one
 * label per embedded point and embedded.Dim > ambientDim.
 */
void SeparateBodies(const std::vector<std::int32_t>& pointBody,
  std::size_t numBodies,
  int ambientDim,
  Embedding& embedded);

} // namespace av

#endif
