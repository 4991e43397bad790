// libFuzzer harness for Tanks and Temples crop volumes (Open3D's SelectionPolygonVolume JSON): the
// bytes are written to a file, read as --tnt-crop reads it, and a few points are tested against
// what was read. A roving::Error is a clean refusal; a crash, a sanitizer report, a hang or an
// allocation over the limit is a finding.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "roving/core/error.h"
#include "roving/reconstruction/crop_volume.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "/tmp/roving-fuzz-" + std::to_string(::getpid()) + ".json";
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) std::abort();
  std::fwrite(data, 1, size, file);
  std::fclose(file);
  try {
    const roving::CropVolume crop = roving::read_crop_volume(path);
    for (const roving::Vec3& p : {roving::Vec3(0, 0, 0), roving::Vec3(0.5, 0.5, 0.5), roving::Vec3(-1, 2, 1e300)}) {
      (void)crop.contains(p);
    }
  } catch (const roving::Error&) {
  }
  return 0;
}
