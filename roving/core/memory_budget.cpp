// Available memory from /proc/meminfo and the cgroup (v2) limit.
#include "roving/core/memory_budget.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

#include "roving/core/error.h"

namespace roving {
namespace {

// A number of bytes from "123", "64M", "2G"; nullopt-like max() when malformed.
std::size_t parse_bytes(const std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  double scale = 1;
  if (end && *end) {
    switch (*end) {
      case 'K':
      case 'k': scale = 1024.0; break;
      case 'M':
      case 'm': scale = 1024.0 * 1024; break;
      case 'G':
      case 'g': scale = 1024.0 * 1024 * 1024; break;
      default: return std::numeric_limits<std::size_t>::max();
    }
  }
  if (!(value > 0)) return std::numeric_limits<std::size_t>::max();
  return static_cast<std::size_t>(std::min(value * scale, 1e19));
}

std::size_t read_number(const char* path) {
  std::ifstream file(path);
  std::string text;
  if (!(file >> text) || text == "max") return std::numeric_limits<std::size_t>::max();
  return parse_bytes(text);
}

}  // namespace

std::size_t available_memory() {
  std::size_t available = std::numeric_limits<std::size_t>::max();
  std::ifstream meminfo("/proc/meminfo");
  for (std::string line; std::getline(meminfo, line);) {
    std::istringstream words(line);
    std::string key;
    std::size_t kib = 0;
    if (words >> key >> kib && key == "MemAvailable:") available = kib * 1024;
  }
  const std::size_t limit = read_number("/sys/fs/cgroup/memory.max");
  const std::size_t used = read_number("/sys/fs/cgroup/memory.current");
  if (limit != std::numeric_limits<std::size_t>::max() && used != std::numeric_limits<std::size_t>::max()) {
    available = std::min(available, limit > used ? limit - used : 0);
  }
  if (const char* cap = std::getenv("ROVING_MEMORY_LIMIT")) available = std::min(available, parse_bytes(cap));
  return available;
}

void require_memory(const std::string& stage, double bytes, const std::string& what) {
  const std::size_t available = available_memory();
  if (bytes > static_cast<double>(available)) {
    constexpr double kGiB = 1024.0 * 1024 * 1024;
    throw Error(fmt::format("{}: needs about {:.3g} GiB for {}; about {:.3g} GiB is available", stage,
                            bytes / kGiB, what, available / kGiB));
  }
}

}  // namespace roving
