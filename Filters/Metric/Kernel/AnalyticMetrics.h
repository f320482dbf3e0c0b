// SPDX-License-Identifier: BSD-3-Clause
// AnalyticMetrics: the closed-form metric fields of the paper's experiments (Fig. 4, §6.3-6.5,
// Tab. 5), rebuilt so that the embedding can be checked against the paper's numbers.
#ifndef av_AnalyticMetrics_h
#define av_AnalyticMetrics_h

#include "SimplexMesh.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace av
{

/**
 * The analytic presets. Every metric has the form M = I + (S^2 - 1) u u^T: stretch S(x) along the
 * unit direction u(x), 1 across it (the paper's R^T diag(S^2, 1, 1) R).
 *
 * - Gaussian2D: 2D domain [-1, 1]^2, M = I + grad h grad h^T for the Gaussian height field
 *   h(x, y) = a exp(-(x^2 + y^2) / (2 s^2)), s = 0.3, a = s e^{1/2} sqrt(3.85^2 - 1) = 1.83893.
 *   |grad h| peaks at r = s with value a e^{-1/2} / s, so the stretch sqrt(1 + |grad h|^2) spans
 *   [1, 3.85] exactly as in Fig. 4, and (x, y, h(x, y)) is an exact isometric 3D embedding.
 *   (The paper gives neither a, s nor the domain: these are our choice.)
 * - Cube1: [0, 1]^3, M = diag(S^2, 1, 1), S = 1 + 9x (the paper writes "S = 10x, S in [1, 10]";
 *   10x vanishes at x = 0, so we take the linear map of [0, 1] onto [1, 10]).
 * - Cube2: [0, 1]^3, M = diag(S^2, 1, 1), S = 0.2 (0.0025 + 0.2 (1 - e^{-|x - 0.5|}))^{-0.8}
 *   (verbatim; S in [1.491, 24.14], the paper rounds to [1, 25]; the peak at x = 0.5 is sharp).
 * - Cube3: [1, 11]^3, S = 2 (0.1 + 2 (1 - e^{-0.01 |x^2 + y^2 - 49|}))^{-1} (the paper's
 *   unbalanced parenthesis closed after the bracket; S in [1.10, 20]), stretched along the radial
 *   direction u = (x / r, y / r, 0), r = sqrt(x^2 + y^2) (cylindrical rotation field).
 * - SphereCylindrical: unit ball, u = (x / r, y / r, 0), S = 1 + 4 r (the paper gives only
 *   S in [1, 5]; on the axis r = 0 the metric is the identity, so u is irrelevant there).
 * - SphereCosine: unit ball, S = 10 along u = normalize(2 cos 4x, 1, 0); 1 along
 *   normalize(1, -2 cos 4x, 0) and along z (verbatim).
 */
enum class AnalyticPreset
{
  Gaussian2D,
  Cube1,
  Cube2,
  Cube3,
  SphereCylindrical,
  SphereCosine
};

/// All presets, in the order above.
std::vector<AnalyticPreset> AllAnalyticPresets();

/// Lower-case name: "gaussian2d", "cube1", "cube2", "cube3", "sphere-cyl", "sphere-cos".
std::string AnalyticPresetName(AnalyticPreset preset);

/// Inverse of AnalyticPresetName (also accepts "spherecylindrical" / "spherecosine");
/// throws InputError listing the valid names.
AnalyticPreset AnalyticPresetFromName(const std::string& name);

/// Where a preset lives and the input mesh the paper (or we) use for it.
struct AnalyticDomain
{
  int AmbientDim = 3;      ///< 2 for Gaussian2D, 3 otherwise
  bool IsBall = false;     ///< unit ball (mesh it with TetGen) instead of a box
  double Lo[3] = { 0, 0, 0 }; ///< box corner (ball: bounding box)
  double Hi[3] = { 1, 1, 1 };
  double Radius = 1.0;     ///< ball radius
  int GridVertices[3] = { 21, 21, 21 }; ///< recommended structured grid (boxes)
  std::size_t BallVertices = 0;         ///< recommended TetGen vertex count (balls)
  double PaperStretchMin = 1.0; ///< stretch range quoted by the paper
  double PaperStretchMax = 1.0;
};

/// Domain and recommended mesh size of a preset (Cube2/Cube3: 101 x 21 x 21 = 44,541 vertices as
/// in Tab. 5; Cube1: 21^3 = 9,261; Gaussian2D: 101 x 101; spheres: 50,000 TetGen vertices).
AnalyticDomain RecommendedDomain(AnalyticPreset preset);

/// Stretch S and unit stretch direction u at point p (p has 2 values for Gaussian2D, else 3).
void AnalyticStretchAt(AnalyticPreset preset, const double* p, double& stretch, Eigen::Vector3d& direction);

/// The metric tensor at p (3x3; for Gaussian2D the 2x2 block, third row/column zero).
Eigen::Matrix3d AnalyticMetricAt(AnalyticPreset preset, const double* p);

/**
 * The preset sampled at every vertex of the mesh (packed XX, YY, ZZ, XY, YZ, XZ). Throws
 * InputError when the mesh's AmbientDim does not match the preset (2 for Gaussian2D, else 3).
 */
MetricField EvaluateAnalyticMetric(AnalyticPreset preset, const SimplexMesh& mesh);

/// Height field of the Gaussian2D preset (its exact isometric embedding is (x, y, h)).
double GaussianHeight(double x, double y);

/// Gradient of GaussianHeight.
Eigen::Vector2d GaussianHeightGradient(double x, double y);

} // namespace av

#endif
