// SPDX-License-Identifier: BSD-3-Clause
#include "MeditSectionCount.h"

#include <algorithm>

namespace av
{

std::string MeditSectionCountError(const std::string& section,
  std::int64_t count,
  std::size_t entryBytes,
  std::size_t bytesLeft,
  std::size_t lastEntrySlack)
{
  if (count < 0)
    return section + ": the header announces a negative number of entries (" +
      std::to_string(count) + ")";
  const std::size_t most = (bytesLeft + lastEntrySlack) / std::max<std::size_t>(entryBytes, 1);
  if (static_cast<std::uint64_t>(count) > most)
    return section + ": the header announces " + std::to_string(count) + " entries but only " +
      std::to_string(bytesLeft) + " bytes are left in the file (truncated?)";
  return std::string();
}

} // namespace av
