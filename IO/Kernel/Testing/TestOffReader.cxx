// SPDX-License-Identifier: BSD-3-Clause
// OFF parser: content of a small file (quad fanned into two triangles, comments, colors),
// and every malformed variant rejected with the line number, never a crash.
#include "OffReader.h"
#include "AnisoTestChecks.h"

#include <string>

int TestOffReader(int, char*[])
{
  const std::string good = "OFF\n# a unit square and a triangle\n5 2 0\n"
                           "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0.5 1\n"
                           "4 0 1 2 3 255 0 0\n3 0 1 4\n";
  const av::SimplexMesh m = av::ParseOff(good, "good.off");
  AV_CHECK(m.NumPoints() == 5);
  AV_CHECK(m.NumCells() == 3);
  AV_CHECK(m.AmbientDim == 3 && m.SimplexDim == 2);
  AV_CHECK(m.Cells[3] == 0 && m.Cells[4] == 2 && m.Cells[5] == 3); // fan of the quad
  AV_CHECK(m.Cells[6] == 0 && m.Cells[7] == 1 && m.Cells[8] == 4);
  AV_CHECK_NEAR(m.Points[14], 1.0, 0.0);

  AV_CHECK_THROWS(av::ParseOff("", "e.off"));
  AV_CHECK_THROWS(av::ParseOff("PLY\n", "e.off"));
  AV_CHECK_THROWS(av::ParseOff("OFF\n3 1 0\n0 0 0\n1 0 0\n", "e.off"));          // truncated
  AV_CHECK_THROWS(av::ParseOff("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", "e.off")); // index
  AV_CHECK_THROWS(av::ParseOff("OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "e.off"));
  AV_CHECK_THROWS(av::ParseOff("OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n", "e.off"));
  AV_CHECK_THROWS(av::ParseOff("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "e.off")); // 2-gon
  AV_CHECK_THROWS(av::ParseOff("OFF\n99999999999 1 0\n0 0 0\n", "e.off"));         // huge count
  try
  {
    av::ParseOff("OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n", "e.off");
  }
  catch (const av::InputError& e)
  {
    AV_CHECK_MSG(std::string(e.what()).find("e.off:4:") != std::string::npos, e.what());
  }
  // Every truncation of the good file parses or throws InputError (no crash, no hang).
  for (std::size_t n = 0; n < good.size(); ++n)
  {
    try
    {
      av::ParseOff(good.substr(0, n), "cut.off");
    }
    catch (const av::InputError&)
    {
    }
  }
  return AV_TEST_RESULT();
}
