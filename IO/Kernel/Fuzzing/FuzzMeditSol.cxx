// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the Medit .sol parser and its conversion to a metric field. Any input must
// either parse or throw InputError; an accepted solution must survive a format + parse round
// trip with the same number of values.
#include "MeditIO.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string text(reinterpret_cast<const char*>(data), size);
  av::MeditSol sol;
  try
  {
    sol = av::ParseMeditSol(text, "fuzz.sol");
  }
  catch (const av::InputError&)
  {
    return 0;
  }
  const av::MeditSol again = av::ParseMeditSol(av::FormatMeditSol(sol), "round-trip.sol");
  if (again.Fields.size() != sol.Fields.size() || again.NumVertices != sol.NumVertices)
  {
    __builtin_trap();
  }
  for (std::size_t f = 0; f < sol.Fields.size(); ++f)
  {
    if (again.Fields[f].size() != sol.Fields[f].size())
    {
      __builtin_trap();
    }
    try
    {
      av::MetricFromMeditSol(sol, f); // what the CLI and the VTK reader do with the field
    }
    catch (const av::InputError&)
    {
    }
  }
  return 0;
}
