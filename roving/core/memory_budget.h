// The memory a stage may ask for, checked before the long work starts, so that a model too
// large for this machine fails at once with its sizes instead of in std::bad_alloc later.
#pragma once

#include <cstddef>
#include <string>

namespace roving {

// Bytes this process can still expect to get: the smaller of the kernel's MemAvailable and
// the cgroup's memory.max less its current use; ROVING_MEMORY_LIMIT (bytes, or with a K, M or
// G suffix) lowers it further, for tests and shared machines.
std::size_t available_memory();

// Throws roving::Error "STAGE: needs about X GiB for WHAT; about Y GiB is available" when
// `bytes` exceeds available_memory().
void require_memory(const std::string& stage, double bytes, const std::string& what);

}  // namespace roving
