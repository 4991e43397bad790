// What the three GL methods share: the scene (renderer, uploaded model, culling grid), option
// checks, and the --views parser.
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include "agreement.h"
#include "gl_passes.h"
#include "hit_colour.h"
#include "roving/core/error.h"
#include "roving/core/stopwatch.h"
#include "roving/gl_methods/gl_methods.h"

namespace roving {

void parse_views(const std::string& text, int& h, int& v) {
  const auto x = text.find('x');
  const auto parse = [&](std::string_view part, int& value) {
    const auto [end, error] = std::from_chars(part.data(), part.data() + part.size(), value);
    return !part.empty() && error == std::errc() && end == part.data() + part.size() && value >= 1 &&
           value <= 720;
  };
  if (x == std::string::npos || !parse(std::string_view(text).substr(0, x), h) ||
      !parse(std::string_view(text).substr(x + 1), v)) {
    throw Error(fmt::format("--views: expected HxV with H and V in 1..720 (e.g. 24x12), found '{}'", text));
  }
}

void parse_views(const std::string& text, GlMethodOptions& options) {
  options.auto_views = text.rfind("auto", 0) == 0;
  if (text == "auto") return;
  try {
    parse_views(options.auto_views && text.size() > 5 && text[4] == ':' ? text.substr(5) : text,
                options.views_h, options.views_v);
  } catch (const Error&) {
    throw Error(fmt::format(
        "--views: expected HxV with H and V in 1..720 (e.g. 24x12), auto, or auto:HxV, found '{}'", text));
  }
}

std::vector<Vec3> view_directions(int h, int v) {
  std::vector<Vec3> directions;
  directions.reserve(static_cast<std::size_t>(h) * v);
  for (int j = 0; j < v; ++j) {
    const double latitude = (-90.0 + 180.0 * (j + 0.5) / v) * M_PI / 180;
    for (int i = 0; i < h; ++i) {
      const double longitude = 360.0 * (i + 0.5) / h * M_PI / 180;
      directions.emplace_back(std::cos(latitude) * std::cos(longitude),
                              std::cos(latitude) * std::sin(longitude), std::sin(latitude));
    }
  }
  return directions;
}

std::vector<Vec3> axis_directions() {
  return {Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitY(), -Vec3::UnitY(), Vec3::UnitZ(), -Vec3::UnitZ()};
}

bool axis_normals(const SampleSet& samples) {
  return std::all_of(samples.normals.begin(), samples.normals.end(), [](const Vec3& n) {
    return n.cwiseAbs().maxCoeff() == 1.0 && n.cwiseAbs().sum() == 1.0;
  });
}

namespace {

// atan2(y, x) to within 0.0015 radians (0.09 degrees; 0 for 0, 0), a third of the smallest cell
// --views allows (0.25 degrees): enough to find n's cell to within one, and far cheaper.
double rough_atan2(double y, double x) {
  const double ax = std::abs(x), ay = std::abs(y), high = std::max(ax, ay);
  if (high == 0) return 0;
  const double a = std::min(ax, ay) / high;
  double angle = M_PI / 4 * a - a * (a - 1) * (0.2447 + 0.0663 * a);
  if (ay > ax) angle = M_PI / 2 - angle;
  if (x < 0) angle = M_PI - angle;
  return y < 0 ? -angle : angle;
}

}  // namespace

std::uint32_t nearest_direction(const std::vector<Vec3>& directions, int h, int v, const Vec3& n) {
  std::uint32_t best = 0;
  double best_dot = -2;
  const auto compare = [&](std::uint32_t d) {
    const double dot = directions[d].dot(n);
    if (dot > best_dot || (dot == best_dot && d < best)) best_dot = dot, best = d;
  };
  // With 3 or more columns every row's nearest direction is in the column whose longitude is
  // nearest n's (the rows' latitudes are within +-90 degrees), and along that column's meridian
  // the nearest is the row whose latitude is nearest n's angle from the equator in that
  // meridian's plane. Float may put either one cell off: the 3 x 3 cells around are compared,
  // and column 0, which a near-pole n may tie with every column of a row. Too few columns, and
  // normals that are not finite or so short that the products underflow, compare them all.
  if (h < 3 || !n.allFinite() || !(n.cwiseAbs().maxCoeff() > 1e-100)) {
    for (std::uint32_t d = 0; d < directions.size(); ++d) compare(d);
    return best;
  }
  double longitude = rough_atan2(n.y(), n.x());
  if (longitude < 0) longitude += 2 * M_PI;
  const int i = std::clamp(static_cast<int>(longitude / (2 * M_PI / h)), 0, h - 1);
  const Vec3& centre = directions[i];  // column i's direction in row 0: its meridian's plane
  const double along = (n.x() * centre.x() + n.y() * centre.y()) /
                       std::sqrt(centre.x() * centre.x() + centre.y() * centre.y());
  const double latitude = rough_atan2(n.z(), along);
  const int j = std::clamp(static_cast<int>(std::floor((latitude + M_PI / 2) / (M_PI / v))), 0, v - 1);
  for (int row = std::max(j - 1, 0); row <= std::min(j + 1, v - 1); ++row) {
    for (const int column : {(i + h - 1) % h, i, (i + 1) % h, 0})
      compare(static_cast<std::uint32_t>(row * h + column));
  }
  return best;
}

void GlScene::build(GlBackend backend, const TriangleMesh& test_model, CameraGeometry camera_geometry) {
  if (!renderer) renderer = make_depth_renderer(backend, camera_geometry == CameraGeometry::Compute);
  renderer->upload_model(test_model, camera_geometry != CameraGeometry::Cpu);
  cameras = camera_geometry;
  grid = std::make_unique<TriangleGrid>(test_model);
  if (cameras == CameraGeometry::Compute) renderer->upload_grid(grid->buckets());
  clusters.reset();
  shades = {};
  test = &test_model;
}

void GlScene::prepare_colour() {
  if (!shades.corners.empty()) return;
  shades = surface_shades(*test);
  renderer->upload_materials(shades.materials);
}

void GlScene::release() {
  grid.reset();
  clusters.reset();
  blind.reset();
  test = nullptr;
}

std::string GlScene::renderer_name() const {
  const RendererInfo info = renderer->info();
  return fmt::format("{}: {} ({})", info.backend, info.renderer, info.version);
}

double GlMethod::build(const TriangleMesh& test) {
  if (options_.resolution < 1) {
    throw Error(
        fmt::format("--resolution: expected a positive number of pixels, found {}", options_.resolution));
  }
  const Stopwatch watch;
  scene_.build(options_.backend, test, options_.camera_geometry);
  if (options_.resolution > scene_.renderer->max_framebuffer_size()) {
    throw Error(fmt::format("--resolution: expected at most {} (this GL's largest framebuffer), found {}",
                            scene_.renderer->max_framebuffer_size(), options_.resolution));
  }
  return watch.seconds();
}

DistanceResult GlMethod::measure(const SampleSet& samples, const DistanceOptions& options) {
  if (!scene_.test) throw Error(name() + ": measure() called before build()");
  validate_options(*this, options);
  const Stopwatch watch;
  GlReport report;
  report.renderer = scene_.renderer_name();
  report.resolved_by.assign(samples.size(), Resolution::Unresolved);
  report.views_h = options_.views_h;
  report.views_v = options_.views_v;
  report.resolution = options_.resolution;
  report.camera_geometry = options_.camera_geometry;
  report.views_culled = options_.cull_views;
  DistanceResult result;
  result.signed_distance.assign(samples.size(), 0.0);
  result.hit.assign(samples.size(), 0);
  // Colour from the frame buffer, beside the depth (the paper's Section 1).
  Coloured coloured;
  if (options.colour && scene_.test->has_colour()) {
    scene_.prepare_colour();
    result.hit_colour.assign(samples.size(), Colour::Constant(std::numeric_limits<float>::quiet_NaN()));
    result.colour_source = "drawn in the frame buffer";
    coloured = [&](std::uint32_t k, const Colour& colour) { result.hit_colour[k] = colour; };
  }
  if (options.faces) result.hit_face.assign(samples.size(), kFaceLeft);
  scene_.faces_asked = options.faces;
  resolve(
      samples, options.max_error, report,
      [&](std::uint32_t k, double d, Resolution how, std::uint32_t face) {
        result.hit[k] = 1;
        result.signed_distance[k] = d;
        report.resolved_by[k] = how;
        if (options.faces) result.hit_face[k] = face;
      },
      coloured);
  // The face at each hit where asked (normal consistency, the correspondences' barycentric
  // coordinates) and the pass did not choose it: by the exact rule near the pass's d, as the
  // colour's face is chosen (hit_colour.h). A camera's d is good to the cameras' bound; a view's
  // bound depends on its angle, which is not kept, so a view's hit is looked for along the whole
  // line (its first hit).
  if (options.faces) {
    const double camera_window = roving_tolerance(report);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.size(), 256),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t k = range.begin(); k != range.end(); ++k) {
                          if (!result.hit[k]) result.hit_face[k] = 0;
                          if (!result.hit[k] || result.hit_face[k] != kFaceLeft) continue;
                          const double window =
                              report.resolved_by[k] == Resolution::Camera ? camera_window : 2 * options.max_error;
                          result.hit_face[k] = hit_face(scene_, samples, static_cast<std::uint32_t>(k),
                                                        result.signed_distance[k], options.max_error, window)
                                                   .face;
                        }
                      });
  }
  result.query_seconds = watch.seconds();
  result.gl = std::move(report);
  return result;
}

}  // namespace roving
