// SPDX-License-Identifier: BSD-3-Clause
// ReferenceEmbedding: exact isometric embeddings of the analytic presets whose metric depends on
// one coordinate only, to tell how much of a mesh's quality loss comes from the embedding solver
// and how much from sampling / the dual mesh / the quality measure (not in the paper).
#ifndef av_ReferenceEmbedding_h
#define av_ReferenceEmbedding_h

#include "AnalyticMetrics.h"
#include "SimplexMesh.h"

namespace av
{

/// True for the presets that ComputeReferenceEmbedding supports: Gaussian2D, Cube1, Cube2,
/// Cube3 and SphereCylindrical (not SphereCosine: its stretch direction turns along x).
bool HasReferenceEmbedding(AnalyticPreset preset);

/**
 * The exact isometric embedding of a preset, evaluated at the mesh vertices:
 * - Gaussian2D: (x, y, h(x, y)), the Gaussian height field (3 coordinates at least);
 * - Cube1, Cube2 (stretch S(x) along x): (x, y, z, H(x)), H' = sqrt(S^2 - 1);
 * - Cube3, SphereCylindrical (stretch S(r) along the radius r = |(x, y)|): (x, y, z, H(r)).
 * For a point moving with velocity v the last coordinate changes at H' (u . v), so the
 * pull-back of the smooth map is I + (S^2 - 1) u u^T = M exactly; only the piecewise-linear
 * interpolation on the mesh and the quadrature of H (a table of 65,536 Simpson panels in a
 * variable that smooths the slope's square-root zero where S = 1; absolute error about 1e-10 on
 * Cube1) differ from the metric. The remaining coordinates up to
 * `dim` are 0; the first AmbientDim are the input points, as with the solver.
 * Throws InputError for an unsupported preset, a mesh of the wrong AmbientDim, dim smaller
 * than AmbientDim + 1, a stretch below 1 (no real H') or non-finite input points.
 */
Embedding ComputeReferenceEmbedding(AnalyticPreset preset, const SimplexMesh& mesh, int dim);

} // namespace av

#endif
