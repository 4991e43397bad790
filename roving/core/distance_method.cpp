// Shared checks and the build-then-measure helper of the distance-method interface.
#include "roving/core/distance_method.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "roving/core/error.h"

namespace roving {

const char* to_string(Semantics semantics) {
  switch (semantics) {
    case Semantics::FirstHit: return "first-hit";
    case Semantics::Nearest: return "nearest";
    case Semantics::Closest: return "closest";
  }
  return "?";
}

Semantics parse_semantics(const std::string& text) {
  for (Semantics s : {Semantics::FirstHit, Semantics::Nearest, Semantics::Closest}) {
    if (text == to_string(s)) return s;
  }
  throw Error(fmt::format("--semantics: expected first-hit, nearest or closest, found '{}'", text));
}

const char* to_string(CameraGeometry geometry) {
  switch (geometry) {
    case CameraGeometry::Cpu: return "cpu";
    case CameraGeometry::Gpu: return "gpu";
    case CameraGeometry::Compute: return "compute";
  }
  return "?";
}

CameraGeometry parse_camera_geometry(const std::string& text) {
  for (CameraGeometry g : {CameraGeometry::Cpu, CameraGeometry::Gpu, CameraGeometry::Compute}) {
    if (text == to_string(g)) return g;
  }
  throw Error(fmt::format("--camera-geometry: expected cpu, gpu or compute, found '{}'", text));
}

std::string MaxErrorSpec::to_string() const {
  return percent_of_diagonal ? fmt::format("{}% of diagonal", value) : fmt::format("{}", value);
}

MaxErrorSpec parse_max_error(const std::string& text) {
  MaxErrorSpec spec;
  std::string number = text;
  spec.percent_of_diagonal = !number.empty() && number.back() == '%';
  if (spec.percent_of_diagonal) number.pop_back();
  std::size_t used = 0;
  bool parsed = false;
  try {
    spec.value = std::stod(number, &used);
    parsed = used == number.size() && !number.empty();
  } catch (const std::exception&) {
  }
  if (!parsed || !std::isfinite(spec.value) || !(spec.value > 0) ||
      (spec.percent_of_diagonal && spec.value > 100)) {
    throw Error(
        fmt::format("--max-error: expected a length > 0 or a percentage of the diagonal in "
                    "(0%, 100%], found '{}'",
                    text));
  }
  return spec;
}

std::size_t GlReport::resolved(Resolution how) const {
  return earlier_resolved[static_cast<std::size_t>(how)] +
         static_cast<std::size_t>(std::count(resolved_by.begin(), resolved_by.end(), how));
}

void GlReport::add_block(const GlReport& block) {
  for (const Resolution how : {Resolution::Unresolved, Resolution::View, Resolution::Camera}) {
    earlier_resolved[static_cast<std::size_t>(how)] = resolved(how) + block.resolved(how);
  }
  resolved_by.clear();
  // What the method made of each block alike: its renderer, views and precision.
  renderer = block.renderer;
  views_h = block.views_h, views_v = block.views_v, resolution = block.resolution;
  axis_views = block.axis_views;
  view_pixel_size = block.view_pixel_size, view_depth_step = block.view_depth_step;
  camera_half_width = block.camera_half_width, camera_depth_step = block.camera_depth_step;
  camera_geometry = block.camera_geometry;
  thin_cameras += block.thin_cameras;
  faces_chosen_in_pass += block.faces_chosen_in_pass;
  faces_left_to_cpu += block.faces_left_to_cpu;
  views_rendered += block.views_rendered;
  sample_cameras += block.sample_cameras;
  camera_build_seconds += block.camera_build_seconds;
  camera_render_seconds += block.camera_render_seconds;
  view_cpu_seconds += block.view_cpu_seconds;
  view_draw_seconds += block.view_draw_seconds;
}

std::size_t DistanceResult::hit_count() const {
  return static_cast<std::size_t>(std::count(hit.begin(), hit.end(), std::uint8_t{1}));
}

SignCounts sign_counts(const DistanceResult& result) {
  SignCounts counts;
  for (std::size_t k = 0; k < result.hit.size(); ++k) {
    if (!result.hit[k]) continue;
    const double d = result.signed_distance[k];
    ++(d > 0 ? counts.positive : d < 0 ? counts.negative : counts.zero);
  }
  return counts;
}

bool DistanceMethod::supports(Semantics semantics) const {
  const auto all = supported_semantics();
  return std::find(all.begin(), all.end(), semantics) != all.end();
}

void validate_options(const DistanceMethod& method, const DistanceOptions& options) {
  if (!(options.max_error > 0) || !std::isfinite(options.max_error)) {
    throw Error(fmt::format("--max-error: expected a finite value > 0, found {}", options.max_error));
  }
  if (!method.supports(options.semantics)) {
    std::string supported;
    for (Semantics s : method.supported_semantics()) {
      supported += (supported.empty() ? "" : ", ") + std::string(to_string(s));
    }
    throw Error(fmt::format("--semantics: method '{}' computes {}; found '{}'", method.name(), supported,
                            to_string(options.semantics)));
  }
}

DistanceResult measure_distances(DistanceMethod& method, const TriangleMesh& test, const SampleSet& samples,
                                 const DistanceOptions& options) {
  validate_options(method, options);
  const double build_seconds = method.build(test);
  DistanceResult result = method.measure(samples, options);
  method.release();
  result.build_seconds = build_seconds;
  return result;
}

}  // namespace roving
