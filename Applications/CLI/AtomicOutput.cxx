// SPDX-License-Identifier: BSD-3-Clause
#include "AtomicOutput.h"

#include "CommandLine.h"

#include <cstdio>
#include <filesystem>
#include <system_error>
#include <unistd.h>
#include <utility>

namespace avcli
{
namespace fs = std::filesystem;

namespace
{
/// `path` with its folder's symbolic links resolved (the file itself need not exist).
fs::path Resolved(const std::string& path)
{
  std::error_code ec;
  const fs::path p = fs::absolute(path, ec);
  const fs::path resolved = fs::weakly_canonical(p, ec);
  return ec ? p.lexically_normal() : resolved;
}
} // namespace

AtomicOutput::AtomicOutput(std::vector<std::string> inputs)
  : Inputs(std::move(inputs))
{
}

void AtomicOutput::RefuseInput(const std::string& path) const
{
  const fs::path output = Resolved(path);
  for (const std::string& input : this->Inputs)
  {
    if (input.empty())
      continue;
    std::error_code ec;
    // Same path once links are resolved, or another name of the same file (hard link).
    if (output == Resolved(input) || fs::equivalent(output, input, ec))
      Fail("the output '" + path + "' is the input file '" + input +
        "': choose another --output-dir (inputs are never overwritten)");
  }
}

std::string AtomicOutput::TemporaryPath(const std::string& path)
{
  const fs::path p(path);
  // The extension stays last: some writers choose the format by it (.meshb vs .mesh).
  return (p.parent_path() /
    ("." + p.stem().string() + ".tmp-" + std::to_string(static_cast<long>(getpid())) +
      p.extension().string()))
    .string();
}

void AtomicOutput::Write(const std::string& path,
  const std::function<bool(const std::string&)>& write) const
{
  this->RefuseInput(path);
  const std::string temporary = TemporaryPath(path);
  bool written = false;
  std::string why;
  try
  {
    written = write(temporary);
  }
  catch (const std::exception& e)
  {
    why = std::string(": ") + e.what();
  }
  if (!written)
  {
    std::remove(temporary.c_str());
    Fail("cannot write " + path + why);
  }
  // rename() replaces the directory entry at once: readers see the old file or the new one.
  if (std::rename(temporary.c_str(), path.c_str()) != 0)
  {
    std::remove(temporary.c_str());
    Fail("cannot rename " + temporary + " to " + path);
  }
}

} // namespace avcli
