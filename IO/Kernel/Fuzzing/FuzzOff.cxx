// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the OFF surface parser. Any input must either parse or throw InputError,
// and an accepted surface must only hold triangles with valid vertex indices.
#include "OffReader.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string text(reinterpret_cast<const char*>(data), size);
  av::SimplexMesh mesh;
  try
  {
    mesh = av::ParseOff(text, "fuzz.off");
  }
  catch (const av::InputError&)
  {
    return 0;
  }
  if (mesh.Points.size() % 3 != 0 || mesh.Cells.size() % 3 != 0)
  {
    __builtin_trap();
  }
  const std::size_t nv = mesh.Points.size() / 3;
  for (const std::int32_t id : mesh.Cells)
  {
    if (id < 0 || static_cast<std::size_t>(id) >= nv)
    {
      __builtin_trap();
    }
  }
  return 0;
}
