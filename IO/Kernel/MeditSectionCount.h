// SPDX-License-Identifier: BSD-3-Clause
// MeditSectionCount: the one check of the entry count that a Medit section announces, shared
// by the ASCII (.mesh/.sol) and the binary (.meshb/.solb) readers.
#ifndef av_MeditSectionCount_h
#define av_MeditSectionCount_h

#include <cstddef>
#include <cstdint>
#include <string>

namespace av
{

/**
 * Why `count` entries of section `section` cannot be in the rest of the file, or "" when they
 * can: the count must not be negative, and `bytesLeft` bytes must hold `count` entries of at
 * least `entryBytes` bytes each, the last one `lastEntrySlack` bytes shorter (ASCII: no
 * separator after the last token). Checked before anything is allocated, so that a corrupted
 * header cannot make a reader allocate huge arrays. The reader adds where (line or byte).
 */
std::string MeditSectionCountError(const std::string& section,
  std::int64_t count,
  std::size_t entryBytes,
  std::size_t bytesLeft,
  std::size_t lastEntrySlack = 0);

/// The least bytes of an ASCII entry of `tokens` tokens: one character and one separator each.
inline std::size_t MeditTextEntryBytes(std::size_t tokens)
{
  return 2 * tokens;
}

} // namespace av

#endif
