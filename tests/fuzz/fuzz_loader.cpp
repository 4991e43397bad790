// libFuzzer harness for one file format (ROVING_FUZZ_EXTENSION): the bytes are written to a file
// of that extension and loaded as a user's model would be, then sampled (a texture, decoded); where
// the format streams (measure --chunk), also read a few faces at a time, whose summary must be the
// whole mesh's where both reads succeed. Any roving::Error is a clean refusal; a crash, a sanitizer
// report, a hang, an allocation over the limit or a summary that differs is a finding.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <optional>

#include "roving/core/error.h"
#include "roving/formats/images_and_matlab/texture_io.h"
#include "roving/formats/meshes/triangle_stream.h"
#include "roving/representations/model.h"
#include "roving/streaming/streamed_measurement.h"

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
    std::optional<roving::StreamedReference> streamed;
    try {
      if (const auto stream = roving::open_triangle_stream(path, 0)) streamed = roving::summarise(*stream, 7);
    } catch (const roving::Error&) {
    }
    const roving::Model model = roving::load_model(path);
    if (streamed && model.type == roving::ModelType::Mesh) {
      const roving::TriangleMesh& whole = model.mesh.mesh;
      const roving::TriangleMesh& summary = streamed->summary;
      if (whole.vertex_count() != summary.vertex_count() || whole.triangle_count() != summary.triangle_count() ||
          whole.unreferenced_vertex_count() != summary.unreferenced_vertex_count() ||
          whole.degenerate_triangle_count() != summary.degenerate_triangle_count() ||
          model.mesh.dropped_repeated_vertex_faces != streamed->dropped_repeated_vertex_faces ||
          model.mesh.triangulated_polygons != streamed->triangulated_polygons ||
          !(whole.total_area() == summary.total_area() || whole.total_area() != whole.total_area()) ||
          whole.bounding_box().min != summary.bounding_box().min ||
          whole.bounding_box().max != summary.bounding_box().max) {
        std::abort();  // streamed and whole reads disagree
      }
    }
    roving::SampleSpec spec;
    (void)roving::reference_samples(model, spec);
  } catch (const roving::Error&) {
    // A clean, named refusal: what bad input must get.
  }
  return 0;
}
