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
  int Step = 0, Resolution = 0, Sites = 2000, Dim = 8, Iterations = 50, SampleIterations = 150;
  int WarmupIterations = 100, Seed = 1, Smooth = 0, Refine = 0, RepairRounds = 10,
      ImproveRounds = 1, OdtIterations = 3;
  int MaxIterations = 500;          // embedding: run to convergence up to this many
  std::string Solver = "auto";      // embedding global step: auto | direct | iterative
  double FeatureAngle = 30.0;
  bool Features = true;
  double Mu = 100.0, Shrink = 0.8, MinEigenvalue = 1e-3, MaxAnisotropy = 25.0;
  bool TensorAsMetric = false, Clamp = false, Quiet = false, Repair = true;
  bool RepairNonManifold = false, DoubleSolve = false;
};

/// Prints "anisovoronoi: error: <message>" on stderr and exits with `code` (2: bad command line).
[[noreturn]] void Fail(const std::string& message, int code = 1);

/// Parses argv (prints the usage and exits for --help; Fail(..., 2) on a bad command line).
Options ParseCommandLine(int argc, char* argv[]);

} // namespace avcli

#endif
