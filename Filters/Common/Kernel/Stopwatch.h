// SPDX-License-Identifier: BSD-3-Clause
// Stopwatch: wall-clock seconds of a stage, for the timings that kernels, filters, the CLI and
// the benchmark report.
#ifndef av_Stopwatch_h
#define av_Stopwatch_h

#include <chrono>

namespace av
{

/// Starts at construction; Seconds() is the wall time since then (or since Restart()).
class Stopwatch
{
public:
  Stopwatch()
    : Start(std::chrono::steady_clock::now())
  {
  }
  void Restart() { this->Start = std::chrono::steady_clock::now(); }
  double Seconds() const
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - this->Start).count();
  }

private:
  std::chrono::steady_clock::time_point Start;
};

} // namespace av

#endif
