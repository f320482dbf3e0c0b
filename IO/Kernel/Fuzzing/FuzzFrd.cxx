// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the CalculiX .frd parser. Any input must either parse or throw InputError,
// and what parses must be self-consistent (offsets, node indices, result sizes), since the VTK
// reader builds cells and arrays from it without checking again.
#include "FrdReader.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string text(reinterpret_cast<const char*>(data), size);
  av::FrdData frd;
  try
  {
    frd = av::ParseFrd(text, "fuzz.frd");
  }
  catch (const av::InputError&)
  {
    return 0;
  }
  const std::size_t nodes = frd.NumNodes();
  const std::size_t elements = frd.NumElements();
  if (frd.Points.size() != 3 * nodes || frd.Offsets.size() != elements + 1 ||
    frd.ElementTypes.size() != elements || frd.IsCornerNode.size() != nodes)
  {
    __builtin_trap();
  }
  for (std::size_t e = 0; e < elements; ++e)
  {
    const std::int64_t n = frd.Offsets[e + 1] - frd.Offsets[e];
    if (n != av::FrdNodesPerElement(frd.ElementTypes[e]) ||
      av::FrdToVTKNodeOrder(frd.ElementTypes[e]) == nullptr)
    {
      __builtin_trap();
    }
  }
  for (const std::int32_t id : frd.Connectivity)
  {
    if (id < 0 || static_cast<std::size_t>(id) >= nodes)
    {
      __builtin_trap();
    }
  }
  for (const av::FrdResult& r : frd.Results)
  {
    if (r.NumComponents < 1 || r.Values.size() != nodes * static_cast<std::size_t>(r.NumComponents))
    {
      __builtin_trap();
    }
  }
  frd.Steps();
  return 0;
}
