// SPDX-License-Identifier: BSD-3-Clause
// Replays every input that a fuzzer of the file parsers once found a crash with
// (IO/Kernel/Fuzzing/regressions/, by extension .mesh .sol .frd .off): each must now be
// rejected with a clean InputError that names the file, never accepted or thrown otherwise.
#include "AnisoTestChecks.h"
#include "FrdReader.h"
#include "MeditIO.h"
#include "OffReader.h"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

namespace
{

std::string ReadBytes(const std::filesystem::path& p)
{
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Parses `text` with the parser of the extension; returns the InputError message, or "" if
/// the input was accepted. Any other exception escapes and fails the test.
std::string Rejection(const std::string& ext, const std::string& text, const std::string& name)
{
  try
  {
    if (ext == ".mesh")
      av::ParseMeditMesh(text, name);
    else if (ext == ".sol")
      av::ParseMeditSol(text, name);
    else if (ext == ".frd")
      av::ParseFrd(text, name);
    else if (ext == ".off")
      av::ParseOff(text, name);
  }
  catch (const av::InputError& e)
  {
    return e.what();
  }
  return "";
}

} // namespace

int TestFuzzRegressions(int, char* argv[])
{
  const std::filesystem::path dir =
    std::filesystem::path(argv[1]) / ".." / "IO" / "Kernel" / "Fuzzing" / "regressions";
  AV_CHECK_MSG(std::filesystem::is_directory(dir), "no folder " << dir);
  int replayed = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
  {
    const std::string ext = entry.path().extension().string();
    if (ext != ".mesh" && ext != ".sol" && ext != ".frd" && ext != ".off")
      continue;
    const std::string name = entry.path().filename().string();
    const std::string message = Rejection(ext, ReadBytes(entry.path()), name);
    AV_CHECK_MSG(!message.empty(), name << " was accepted");
    AV_CHECK_MSG(message.find(name) != std::string::npos, name << ": message " << message);
    std::cout << name << ": " << message << "\n";
    ++replayed;
  }
  AV_CHECK(replayed > 0);
  return AV_TEST_RESULT();
}
