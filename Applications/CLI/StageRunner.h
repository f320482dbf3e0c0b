// SPDX-License-Identifier: BSD-3-Clause
// StageRunner: updates the anisovoronoi tool's VTK algorithms one stage at a time, with
// progress on stderr, the wall time of each stage and a one-line failure.
#ifndef avcli_StageRunner_h
#define avcli_StageRunner_h

#include <map>
#include <string>

class vtkAlgorithm;

namespace avcli
{

class StageRunner
{
public:
  explicit StageRunner(bool quiet)
    : Quiet(quiet)
  {
  }

  /// Updates `algorithm`; on failure prints its first error and exits (status 1).
  void Run(vtkAlgorithm* algorithm, const std::string& stage);

  /// Wall seconds of each stage run so far (0 for a stage that did not run).
  double SecondsOf(const std::string& stage) const;

private:
  bool Quiet;
  std::map<std::string, double> Seconds;
};

} // namespace avcli

#endif
