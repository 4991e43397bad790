// I/N slices (shard.h).
#include "shard.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>

#include "roving/core/error.h"

namespace roving {

std::pair<std::size_t, std::size_t> Shard::range(std::size_t total, std::size_t run) const {
  // In 128 bits: total * index overflows 64 for a billion samples over a million shards. Each cut
  // goes to the nearest multiple of run, so that cuts total / count >= run apart stay apart (no
  // slice empty while count <= total / run) and a few shards are not all pushed into the last.
  const auto at = [&](std::size_t i) {
    if (i == count) return total;
    const auto even = static_cast<std::size_t>(static_cast<unsigned __int128>(total) * i / count);
    return std::min(total, (even + run / 2) / run * run);
  };
  return {at(index), at(index + 1)};
}

Shard parse_shard(const std::string& option, const std::string& text) {
  Shard shard;
  const std::size_t slash = text.find('/');
  const auto number = [&](std::size_t from, std::size_t to, std::size_t& value) {
    const char* end = text.data() + to;
    const auto [last, error] = std::from_chars(text.data() + from, end, value);
    return from < to && error == std::errc() && last == end;
  };
  if (slash == std::string::npos || !number(0, slash, shard.index) || !number(slash + 1, text.size(), shard.count) ||
      shard.count < 1 || shard.index >= shard.count) {
    throw Error(fmt::format("{}: expected I/N with 0 <= I < N (e.g. 0/4, as Slurm's "
                            "$SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT), found '{}'",
                            option, text));
  }
  return shard;
}

}  // namespace roving
