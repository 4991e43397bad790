// One of N parts of a list (batch's pairs) or of one pair's samples (measure --shard): the I-th of N
// contiguous slices, so that the parts together are the whole in order, whatever N.
#pragma once

#include <cstddef>
#include <string>
#include <utility>

namespace roving {

struct Shard {
  std::size_t index = 0, count = 1;

  // [first, last) of `total` items that this shard takes.
  std::pair<std::size_t, std::size_t> range(std::size_t total) const;
};

// Parses "I/N" (0 <= I < N, e.g. $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT); throws roving::Error
// naming `option` and what was found otherwise.
Shard parse_shard(const std::string& option, const std::string& text);

}  // namespace roving
