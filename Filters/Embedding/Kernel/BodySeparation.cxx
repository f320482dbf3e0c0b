// SPDX-License-Identifier: BSD-3-Clause
#include "BodySeparation.h"

#include "InputError.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace av
{

void SeparateBodies(const std::vector<std::int32_t>& body,
  std::size_t numBodies,
  int ambientDim,
  Embedding& embedded)
{
  const int dim = embedded.Dim;
  if (embedded.NumPoints() != body.size() || dim <= ambientDim)
    throw InputError("SeparateBodies: the embedding must have one point per body label and "
                     "more coordinates than the mesh");
  if (numBodies < 2)
    return;
  // Per body: bounding box in R^m (its diagonal bounds the body's diameter).
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> lo(numBodies * dim, inf), hi(numBodies * dim, -inf);
  for (std::size_t p = 0; p < body.size(); ++p)
  {
    if (body[p] < 0 || static_cast<std::size_t>(body[p]) >= numBodies)
      continue;
    const double* x = embedded.At(p);
    double* l = lo.data() + static_cast<std::size_t>(body[p]) * dim;
    double* h = hi.data() + static_cast<std::size_t>(body[p]) * dim;
    for (int d = 0; d < dim; ++d)
    {
      l[d] = std::min(l[d], x[d]);
      h[d] = std::max(h[d], x[d]);
    }
  }
  double gap = 0.0;
  for (std::size_t b = 0; b < numBodies; ++b)
  {
    if (!(lo[b * dim] <= hi[b * dim]))
      continue; // no point carries this label
    double d2 = 0.0;
    for (int d = 0; d < dim; ++d)
      d2 += (hi[b * dim + d] - lo[b * dim + d]) * (hi[b * dim + d] - lo[b * dim + d]);
    gap = std::max(gap, std::sqrt(d2));
  }
  // Bodies in label order, one after the other along the last coordinate.
  const int axis = dim - 1;
  std::vector<double> shift(numBodies, 0.0);
  double end = hi[axis]; // body 0 has the first cell's points
  for (std::size_t b = 1; b < numBodies; ++b)
  {
    if (!(lo[b * dim] <= hi[b * dim]))
      continue;
    shift[b] = end + gap - lo[b * dim + axis];
    end = hi[b * dim + axis] + shift[b];
  }
  for (std::size_t p = 0; p < body.size(); ++p)
    if (body[p] > 0 && static_cast<std::size_t>(body[p]) < numBodies)
      embedded.Coords[p * static_cast<std::size_t>(dim) + axis] +=
        shift[static_cast<std::size_t>(body[p])];
}

} // namespace av
