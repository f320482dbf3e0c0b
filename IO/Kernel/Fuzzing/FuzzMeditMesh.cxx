// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the Medit .mesh parser. Any input must either parse or throw InputError;
// a parsed mesh must survive a format + parse round trip unchanged in size.
#include "MeditIO.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string text(reinterpret_cast<const char*>(data), size);
  av::MeditMesh mesh;
  try
  {
    mesh = av::ParseMeditMesh(text, "fuzz.mesh");
  }
  catch (const av::InputError&)
  {
    return 0; // the clean rejection every malformed file must get
  }
  // What the writer makes of an accepted mesh must read back (an InputError here is a bug,
  // and libFuzzer reports the uncaught exception as a crash).
  const av::MeditMesh again = av::ParseMeditMesh(av::FormatMeditMesh(mesh), "round-trip.mesh");
  if (again.Mesh.Points.size() != mesh.Mesh.Points.size() ||
    again.Mesh.Cells.size() != mesh.Mesh.Cells.size() || again.Faces.size() != mesh.Faces.size() ||
    again.Edges.size() != mesh.Edges.size())
  {
    __builtin_trap();
  }
  return 0;
}
