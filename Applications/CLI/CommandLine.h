// SPDX-License-Identifier: BSD-3-Clause
// CommandLine: the options of the anisovoronoi tool, their parsing and the one-line failure.
#ifndef avcli_CommandLine_h
#define avcli_CommandLine_h

#include <string>

namespace avcli
{

/// What the command line asks for (defaults as in --help).
struct Options
{
  std::string Input, Metric, Sol, OutputDir;
  std::string MeditOutput;  ///< -o FILE.mesh|.meshb: the mesh and its metric .sol|.solb
  bool FormatMedit = false; ///< --format medit: also mesh.mesh + mesh.sol in OutputDir
  int Step = 0, Resolution = 0, Sites = 2000, Dim = 8, Iterations = 50, SampleIterations = 150;
  int WarmupIterations = 100, Seed = 1, Smooth = 0, Refine = 0, RepairRounds = 10,
      ImproveRounds = 1, OdtIterations = 3;
  int MaxIterations = 500;          // embedding: run to convergence up to this many
  std::string Solver = "auto";      // embedding global step: auto | direct | iterative
  std::string ElementMetric = "mean"; // embedding: mean | edges
  double FeatureAngle = 30.0;
  std::string
    FeaturePatches; // surfaces: cell array of patch ids whose borders are the feature lines
  std::string FeatureCorners; // with it: point array, nonzero = corner
  double AdaptLength = 1.5; ///< --adapt-length: L_bg of the adapted background
  /// --adapt: always; --no-adapt: never; default: tensor: fields on a mesh coarser than the output
  std::string Adapt = "auto";
  bool Features = true;
  double Mu = 100.0, Shrink = 0.8, MinEigenvalue = 1e-3, MaxAnisotropy = 25.0;
  double MaxStretch = 10.0; ///< curvature: cap on s2 / s1 (0 = none)
  bool TensorAsMetric = false, Clamp = false, Quiet = false, Repair = true;
  bool ValidDual = true;
  bool RepairNonManifold = true, DoubleSolve = false, ImproveMesh = true, SeparateBodies = true;
  bool ImproveBoundary = true; // the mesh improvement also works on the tet boundary
  int MeanSmoothingSweeps = 2; // the mesh improvement's mean-quality sweeps
  bool ScaleFreeRegularizer = false; // --scale-free-regularizer: E_reg in units of the extent
  bool KeepFeatureSites = false; // surfaces: the ODT steps keep the crease sites on the creases
  bool CloseBoundaryNotches = true; // surfaces: close the notches of the open boundary
  /// Metric preparation (on for tensor:ARRAY; metric, preset and .sol inputs only when a
  /// preparation option is given, PrepareAsked). SitesGiven: --sites was on the command line.
  double HMin = 0.0, HMax = 0.0, HGrad = 1.3, SizeBlend = 0.5, MinCellsAcross = 1.25;
  std::string SizeMode = "tensor";
  bool Gradation = true, PrepareAsked = false, SitesGiven = false;
};

/// Prints "anisovoronoi: error: <message>" on stderr and exits with `code` (2: bad command line).
[[noreturn]] void Fail(const std::string& message, int code = 1);

/// Parses argv (prints the usage and exits for --help; Fail(..., 2) on a bad command line).
Options ParseCommandLine(int argc, char* argv[]);

} // namespace avcli

#endif
