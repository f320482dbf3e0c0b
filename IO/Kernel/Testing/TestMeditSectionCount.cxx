// SPDX-License-Identifier: BSD-3-Clause
// MeditSectionCountError, the count check of both Medit readers: exact fits pass (ASCII: the
// last token needs no separator), one entry more, a negative count or a count of a corrupted
// header are refused with a message that names the section.
#include "AnisoTestChecks.h"
#include "MeditSectionCount.h"

#include <cstdint>
#include <limits>
#include <string>

int TestMeditSectionCount(int, char*[])
{
  // ASCII: 3 entries of 2 tokens are "1 2\n3 4\n5 6" at the least, 11 bytes.
  const std::size_t text = av::MeditTextEntryBytes(2);
  AV_CHECK(text == 4);
  AV_CHECK(av::MeditSectionCountError("Edges", 3, text, 11, 1).empty());
  std::string msg = av::MeditSectionCountError("Edges", 3, text, 10, 1);
  AV_CHECK_MSG(msg.find("Edges:") == 0 && msg.find("truncated") != std::string::npos, msg);
  // Binary: lines of exactly `entryBytes` bytes, no slack.
  AV_CHECK(av::MeditSectionCountError("Vertices", 2, 28, 56).empty());
  AV_CHECK(!av::MeditSectionCountError("Vertices", 3, 28, 56).empty());
  AV_CHECK(av::MeditSectionCountError("Vertices", 0, 28, 0).empty());
  msg = av::MeditSectionCountError("Tetrahedra", -5, 20, 1000);
  AV_CHECK_MSG(msg.find("Tetrahedra:") == 0 && msg.find("negative") != std::string::npos, msg);
  msg = av::MeditSectionCountError("Triangles", std::numeric_limits<std::int64_t>::max(), 16, 64);
  AV_CHECK_MSG(msg.find("Triangles:") == 0 && msg.find("truncated") != std::string::npos, msg);
  return AV_TEST_RESULT();
}
