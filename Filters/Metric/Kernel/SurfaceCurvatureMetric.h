// SPDX-License-Identifier: BSD-3-Clause
// SurfaceCurvatureMetric: the curvature-adapted surface metric of the paper (Eq. 19) from a
// triangle surface alone. VTK-free.
#ifndef av_SurfaceCurvatureMetric_h
#define av_SurfaceCurvatureMetric_h

#include "SimplexMesh.h"

#include <cstddef>
#include <vector>

namespace av
{

/// Parameters of SurfaceCurvatureMetric (defaults in brackets).
struct SurfaceCurvatureMetricOptions
{
  /// Floor on |K| so that flat directions keep a finite stretch: |K| >= CurvatureThreshold / L,
  /// L the bounding-box diagonal (scale-free) [0.1].
  double CurvatureThreshold = 0.1;
  /// Laplacian smoothing of the stretch factors and of the principal direction field
  /// (one-ring averages, Alliez et al. 2003) [5].
  int SmoothingIterations = 5;
  /// Cap on the stretch ratio s2 / s1; 0 = no cap [10].
  double MaxStretch = 10.0;
  /// Sharp creases: an edge whose two triangles' normals differ by more than this (degrees) is a
  /// crease, and the normal differences that estimate curvature are not taken across it, so a
  /// CAD edge is not read as a curvature of (dihedral angle) / (edge length) and the patches on
  /// either side keep their own curvature. 180 = no creases (the surface is treated as smooth
  /// everywhere) [180: off by default; on the real CAD surfaces 30-90 made turbine worse and
  /// fandisk no better, Filters/Metric/README.md].
  double CreaseAngle = 180.0;
};

/// Per-vertex output of SurfaceCurvatureMetric. Vectors hold 3 values per vertex.
struct SurfaceCurvatureMetricResult
{
  /// Eq. 19: M = v_min v_min^T + (s2/s1)^2 v_max v_max^T (rank 2, zero along the normal).
  MetricField Metric;
  std::vector<double> MinCurvature;  ///< principal curvature of smaller magnitude (signed)
  std::vector<double> MaxCurvature;  ///< principal curvature of larger magnitude (signed)
  std::vector<double> MinDirection;  ///< v_min (after smoothing), unit, tangent
  std::vector<double> MaxDirection;  ///< v_max (after smoothing), unit, tangent
  std::vector<double> Normals;       ///< area-weighted vertex normals, unit
  std::vector<double> StretchRatio;  ///< s2 / s1 after smoothing and cap
  double CurvatureFloor = 0.0;       ///< the absolute |K| floor used
  std::size_t NumCreaseEdges = 0;    ///< edges found sharper than CreaseAngle
};

/**
 * @brief Curvature metric of a triangle surface (AmbientDim 3, SimplexDim 2, open or closed).
 *
 * Principal curvatures and directions per vertex by per-face second fundamental form fits
 * (normal differences along the three edges, Rusinkiewicz 2004; each corner uses the normal of
 * its wedge, the faces around the vertex not separated by a crease edge) averaged over the one-ring
 * (weights: area / 3) and projected onto the vertex tangent plane. Then s1 = sqrt(|K_min|),
 * s2 = sqrt(|K_max|) with the floor, smoothing, cap, and Eq. 19. The metric's smallest
 * tangent eigenvalue is 1, so no global scale is needed. Faces should be consistently
 * oriented (normals are averaged).
 * Throws InputError on: wrong dimensions, empty mesh, ids out of range, NaN/Inf,
 * zero-area triangles, vertices used by no triangle, invalid options.
 */
SurfaceCurvatureMetricResult SurfaceCurvatureMetric(
  const SimplexMesh& surface, const SurfaceCurvatureMetricOptions& options);

/**
 * Unit vertex normals of a consistently oriented triangle surface (3 per vertex), with Max's
 * weights as the curvature metric uses them. Throws InputError as SurfaceCurvatureMetric does.
 */
std::vector<double> SurfaceVertexNormals(const SimplexMesh& surface);

} // namespace av

#endif
