// One of N parts of a list (batch's pairs) or of one pair's samples (measure --shard): the I-th of N
// contiguous slices, so that the parts together are the whole in order, whatever N.
#pragma once

#include <cstddef>
#include <string>
#include <utility>

namespace roving {

struct Shard {
  std::size_t index = 0, count = 1;

  // [first, last) of `total` items that this shard takes; every boundary but the last a multiple
  // of `run` (a method's independent run: exact roving's camera batch), so that each part is
  // measured as it is within the whole. Never empty while count <= total / run.
  std::pair<std::size_t, std::size_t> range(std::size_t total, std::size_t run = 1) const;
};

// Parses "I/N" (0 <= I < N, e.g. $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT); throws roving::Error
// naming `option` and what was found otherwise.
Shard parse_shard(const std::string& option, const std::string& text);

}  // namespace roving
