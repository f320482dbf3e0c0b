// SPDX-License-Identifier: BSD-3-Clause
// AtomicOutput: how the anisovoronoi tool writes every output file. Each is written to a
// temporary name in its own folder and renamed over the final name only once complete, so an
// interrupted or failed run never leaves a truncated file that looks complete; and no output
// may be one of the run's input files (same path after resolving symbolic links, or a hard
// link to it), so a run never overwrites what it reads.
#ifndef avcli_AtomicOutput_h
#define avcli_AtomicOutput_h

#include <functional>
#include <string>
#include <vector>

namespace avcli
{

class AtomicOutput
{
public:
  /// `inputs`: the files the run reads (empty names are ignored).
  explicit AtomicOutput(std::vector<std::string> inputs);

  /// Fail()s with a clear message when `path` is (or would replace) one of the inputs.
  void RefuseInput(const std::string& path) const;

  /// Writes `path` through `write(temporaryPath)`, which returns false (or throws) on failure;
  /// on success renames the temporary file to `path`, else removes it and Fail()s.
  void Write(const std::string& path, const std::function<bool(const std::string&)>& write) const;

  /// The temporary name of `path`: hidden, in the same folder (the rename stays atomic), unique
  /// per process, with the same extension.
  static std::string TemporaryPath(const std::string& path);

private:
  std::vector<std::string> Inputs;
};

} // namespace avcli

#endif
