// SPDX-License-Identifier: BSD-3-Clause
// MemoryBudget: how much memory this process may still allocate, so that a kernel can refuse
// a problem too big for the machine with a clear message (and its estimate) before the big
// allocations, instead of dying in the OOM killer or on a failed allocation deep inside a
// library.
#ifndef av_MemoryBudget_h
#define av_MemoryBudget_h

#include <cstddef>
#include <string>

namespace av
{

/// What limits the memory of this process now (bytes; SIZE_MAX when a limit is absent).
struct MemoryLimits
{
  std::size_t MemAvailable;      ///< /proc/meminfo MemAvailable
  std::size_t AddressSpace;      ///< RLIMIT_AS (ulimit -v) minus the current virtual size
  std::size_t Cgroup;            ///< cgroup v2 memory.max (or v1 limit) minus the current usage
  std::size_t Available() const; ///< the smallest of the three
  std::string Describe() const;  ///< "1.2 GB available (ulimit -v)" or similar
};

/// Reads the limits (Linux /proc and /sys; every limit absent elsewhere).
MemoryLimits CurrentMemoryLimits();

/**
 * Throws InputError when `bytes` (an estimate of what `what` is about to allocate) exceeds
 * the memory available now: "<what> needs about X GB, but only Y GB is available (...)".
 * AV_MEMORY_LIMIT_MB in the environment lowers the budget further (tests, shared machines).
 */
void RequireMemory(double bytes, const std::string& what);

/// "1.23 GB", "456 MB": a byte count for messages.
std::string FormatBytes(double bytes);

} // namespace av

#endif
