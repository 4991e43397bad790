// libFuzzer harness for one file format (ROVING_FUZZ_EXTENSION): the bytes are written to a file
// of that extension and loaded as a user's model would be, then sampled (a texture, decoded). Any
// roving::Error is a clean refusal; a crash, a sanitizer report, a hang or an allocation over the limit is a
// finding.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "roving/core/error.h"
#include "roving/formats/texture_io.h"
#include "roving/representations/model.h"

namespace {

std::string scratch_path() {
  return "/tmp/roving-fuzz-" + std::to_string(::getpid()) + "." ROVING_FUZZ_EXTENSION;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // The memory budget refuses what the fuzzer's -rss_limit_mb would otherwise report.
  ::setenv("ROVING_MEMORY_LIMIT", "1G", 1);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = scratch_path();
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) std::abort();
  std::fwrite(data, 1, size, file);
  std::fclose(file);
  try {
    if constexpr (ROVING_FUZZ_TEXTURE) {
      (void)roving::read_texture(path);
      return 0;
    }
    const roving::Model model = roving::load_model(path);
    roving::SampleSpec spec;
    (void)roving::reference_samples(model, spec);
  } catch (const roving::Error&) {
    // A clean, named refusal: what bad input must get.
  }
  return 0;
}
