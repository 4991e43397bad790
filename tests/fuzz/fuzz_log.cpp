// libFuzzer harness for Tanks and Temples' camera files: the bytes are written to a file and read
// both as --tnt-trajectory (and --tnt-reference-trajectory) reads a trajectory and as --tnt-mapping
// reads a frame mapping; where both succeed, the mapping picks the trajectory's cameras as the
// registration does. A roving::Error is a clean refusal; a crash, a sanitizer report, a hang or an
// allocation over the limit is a finding.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>

#include "roving/core/error.h"
#include "roving/reconstruction/tanks_and_temples_registration.h"
#include "roving/reconstruction/trajectory_log.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "/tmp/roving-fuzz-" + std::to_string(::getpid()) + ".log";
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) std::abort();
  std::fwrite(data, 1, size, file);
  std::fclose(file);
  roving::TanksAndTemplesTrajectories t;
  std::optional<std::vector<std::size_t>> mapping;
  try {
    t.reconstruction = roving::read_trajectory_log(path);
  } catch (const roving::Error&) {
  }
  try {
    mapping = roving::read_frame_mapping(path);
  } catch (const roving::Error&) {
  }
  if (t.reconstruction.empty() || !mapping) return 0;
  t.reference = t.reconstruction;
  t.mapping = *mapping;
  try {
    (void)roving::matched_camera_centres(t, {path, path});
  } catch (const roving::Error&) {
  }
  return 0;
}
