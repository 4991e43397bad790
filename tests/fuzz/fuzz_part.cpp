// libFuzzer harness for a shard's part (measure --shard-out): the bytes are written to a file, whose
// description and arrays are read as `roving merge` reads them. A roving::Error is a clean refusal;
// a crash, a sanitizer report, a hang or an allocation over the limit is a finding.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "roving/core/error.h"
#include "roving/formats/outputs/shard_part.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "/tmp/roving-fuzz-" + std::to_string(::getpid()) + ".part";
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) std::abort();
  std::fwrite(data, 1, size, file);
  std::fclose(file);
  try {
    const roving::PartHeader part = roving::read_part_header(path);
    std::vector<double> distance[2], weights[2], agreement[2];
    std::vector<std::uint8_t> hit[2];
    std::vector<roving::Colour> reference_colour[2], test_colour[2];
    std::vector<roving::PartArrays> into;
    for (int i = 0; i < 2; ++i) {
      into.push_back({&distance[i], &hit[i], &weights[i], &agreement[i], &reference_colour[i], &test_colour[i]});
    }
    roving::append_part_arrays(part, into);
  } catch (const roving::Error&) {
  }
  return 0;
}
