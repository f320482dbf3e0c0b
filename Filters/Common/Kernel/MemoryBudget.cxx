// SPDX-License-Identifier: BSD-3-Clause
#include "MemoryBudget.h"

#include "InputError.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

namespace av
{
namespace
{
constexpr std::size_t kNoLimit = std::numeric_limits<std::size_t>::max();

/// The value (kB) of line `key` in /proc/meminfo, or kNoLimit.
std::size_t MemInfoBytes(const char* key)
{
  std::ifstream in("/proc/meminfo");
  std::string name;
  std::size_t kb = 0;
  std::string unit;
  while (in >> name >> kb)
  {
    std::getline(in, unit);
    if (name == key)
      return kb * 1024;
  }
  return kNoLimit;
}

/// The current virtual size of this process (first field of /proc/self/statm, in pages).
std::size_t VirtualSizeBytes()
{
  std::ifstream in("/proc/self/statm");
  std::size_t pages = 0;
  if (!(in >> pages))
    return 0;
  return pages * static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
}

/// A number file such as memory.max ("max" or absent: kNoLimit).
std::size_t ReadLimitFile(const std::string& path)
{
  std::ifstream in(path);
  std::string word;
  if (!(in >> word) || word == "max")
    return kNoLimit;
  char* end = nullptr;
  const unsigned long long v = std::strtoull(word.c_str(), &end, 10);
  return end && *end == '\0' ? static_cast<std::size_t>(v) : kNoLimit;
}

/// The cgroup of this process ("0::/path" for v2), or "".
std::string CgroupV2Path()
{
  std::ifstream in("/proc/self/cgroup");
  std::string line;
  while (std::getline(in, line))
  {
    if (line.rfind("0::", 0) == 0)
      return line.substr(3);
  }
  return "";
}

std::size_t CgroupRoom()
{
  const std::string rel = CgroupV2Path();
  std::size_t limit = ReadLimitFile("/sys/fs/cgroup" + rel + "/memory.max");
  std::size_t used = ReadLimitFile("/sys/fs/cgroup" + rel + "/memory.current");
  if (limit == kNoLimit)
  {
    limit = ReadLimitFile("/sys/fs/cgroup/memory/memory.limit_in_bytes"); // cgroup v1
    used = ReadLimitFile("/sys/fs/cgroup/memory/memory.usage_in_bytes");
    if (limit >= (std::size_t(1) << 60))
      return kNoLimit; // v1 reports "no limit" as a huge number
  }
  if (limit == kNoLimit)
    return kNoLimit;
  return used == kNoLimit || used >= limit ? (used == kNoLimit ? limit : 0) : limit - used;
}
} // namespace

std::size_t MemoryLimits::Available() const
{
  return std::min({ this->MemAvailable, this->AddressSpace, this->Cgroup });
}

std::string MemoryLimits::Describe() const
{
  const std::size_t a = this->Available();
  if (a == kNoLimit)
    return "no known limit";
  const char* which = a == this->AddressSpace ? "address-space limit, ulimit -v"
    : a == this->Cgroup                       ? "cgroup memory limit"
                                              : "MemAvailable";
  return FormatBytes(static_cast<double>(a)) + " available (" + which + ")";
}

MemoryLimits CurrentMemoryLimits()
{
  MemoryLimits m{ MemInfoBytes("MemAvailable:"), kNoLimit, CgroupRoom() };
  rlimit as{};
  if (getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY)
  {
    const std::size_t used = VirtualSizeBytes();
    const std::size_t cap = static_cast<std::size_t>(as.rlim_cur);
    m.AddressSpace = used < cap ? cap - used : 0;
  }
  if (const char* env = std::getenv("AV_MEMORY_LIMIT_MB"))
  {
    const double mb = std::atof(env);
    if (mb > 0)
      m.MemAvailable = std::min(m.MemAvailable, static_cast<std::size_t>(mb * 1048576.0));
  }
  return m;
}

std::string FormatBytes(double bytes)
{
  char buf[64];
  if (bytes >= 1e9)
    std::snprintf(buf, sizeof(buf), "%.2f GB", bytes / 1e9);
  else
    std::snprintf(buf, sizeof(buf), "%.0f MB", bytes / 1e6);
  return buf;
}

void RequireMemory(double bytes, const std::string& what)
{
  const MemoryLimits limits = CurrentMemoryLimits();
  const std::size_t available = limits.Available();
  if (available != kNoLimit && bytes > static_cast<double>(available))
  {
    throw InputError(what + " needs about " + FormatBytes(bytes) + ", but only " +
      limits.Describe() + ": use a smaller input (fewer vertices or sites) or more memory");
  }
}

} // namespace av
