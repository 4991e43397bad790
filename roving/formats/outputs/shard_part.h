// A shard's part (`roving measure --shard I/N --shard-out PART`, merged by `roving merge`): a first
// line naming the format, one line of JSON describing the measurement and its slices, then per
// direction the samples' d (float64), hit (uint8), weight (float64) and, where the description
// says so, |n . n'| (float64) and REF's and TEST's colours (3 float32 each), little-endian. This file reads and writes the layout; what the
// description holds is the merge's (roving/cli/merge.h).
#pragma once

#include <cstdint>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "roving/core/texture.h"

namespace roving {

// One direction's per-sample arrays, to write.
struct PartColumns {
  const std::vector<double>* signed_distance = nullptr;
  const std::vector<std::uint8_t>* hit = nullptr;
  const std::vector<double>* weights = nullptr;
  const std::vector<double>* agreement = nullptr;  // empty: not carried
  const std::vector<Colour>* reference_colour = nullptr;  // null or empty: not carried
  const std::vector<Colour>* test_colour = nullptr;
};

// One direction's per-sample arrays, to append to.
struct PartArrays {
  std::vector<double>* signed_distance = nullptr;
  std::vector<std::uint8_t>* hit = nullptr;
  std::vector<double>* weights = nullptr;
  std::vector<double>* agreement = nullptr;
  std::vector<Colour>* reference_colour = nullptr;
  std::vector<Colour>* test_colour = nullptr;
};

// One direction of a part as its description gives it.
struct PartDirection {
  std::size_t count = 0, first = 0;
  bool agreement = false;
  bool colour = false;
};

struct PartHeader {
  std::string path;
  nlohmann::json description;
  std::vector<PartDirection> directions;
  std::uint64_t arrays_at = 0;  // where the arrays start in the file
};

// Writes a part: `description` must hold "directions", each with "samples" {"count", "first"},
// "normal_agreement" and "colour" (whether `columns` carries them); "byte_order" is added.
void write_part(std::FILE* out, nlohmann::json description, const std::vector<PartColumns>& columns);

// Reads a part's first two lines and checks the file's size against them; throws roving::Error
// naming the file and what is wrong (not a part, a damaged description, a truncated file).
PartHeader read_part_header(const std::string& path);

// Appends each direction's arrays to `into` (one per direction), checked: hit flags 0 or 1, finite
// distances, finite areas >= 0, |n . n'| in [0, 1], colours on [0, 255] or NaN (none); throws
// roving::Error naming a damaged part.
void append_part_arrays(const PartHeader& part, const std::vector<PartArrays>& into);

}  // namespace roving
