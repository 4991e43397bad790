// IBSM: both models drawn unlit from cameras on a Fibonacci sphere, compared pixel by pixel.
#include "roving/gl_methods/image_based.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "roving/core/colour_statistics.h"
#include "roving/core/error.h"
#include "roving/core/stopwatch.h"
#include "surface_shades.h"

namespace roving {
namespace {

// A renderer holding `mesh` shaded as mmetric shades it (its texture alone where it has one,
// bilinear and clamped; else its vertex colours), or white.
std::unique_ptr<DepthRenderer> shaded_renderer(const TriangleMesh& mesh, GlBackend backend) {
  auto renderer = make_depth_renderer(backend);
  SurfaceShades shades;
  if (mesh.has_colour()) {
    shades = surface_shades(mesh, ShadeRule::AsMmetric);
  } else {
    shades.materials.resize(1);
    shades.corners.assign(3 * mesh.triangle_count(), TileShade{1, 1, 1, 0, 0});
  }
  renderer->upload_materials(shades.materials);
  renderer->upload_shaded_model(mesh, shades.corners, shades.face_materials);
  return renderer;
}

// glm::lookAt's frame, as mmetric builds it: up is y, or z for a camera on the y axis. mmetric
// samples each pixel at its lower left corner, GL at its centre: the view moves half a pixel down
// and left, so that GL's pixel centres fall on mmetric's sample points.
OrthoCamera camera_towards(const Vec3& centre, const Vec3& direction, double radius, int resolution) {
  OrthoCamera camera;
  camera.forward = -direction;
  const Vec3 up = (direction.cwiseAbs() - Vec3::UnitY()).norm() < 1e-6 ? Vec3::UnitZ() : Vec3::UnitY();
  camera.right = camera.forward.cross(up).normalized();
  camera.up = camera.right.cross(camera.forward);
  camera.half_width = camera.half_height = camera.half_depth = radius;
  camera.centre = centre - (radius / resolution) * (camera.right + camera.up);
  return camera;
}

// mmetric prints 99.99 dB for images that agree, and never more.
constexpr double kPsnrCap = 99.99;

double psnr(double mse) {
  return std::min(kPsnrCap, colour_psnr(mse));  // peak 255
}

// mmetric's Y'CbCr: BT.709's coefficients as it rounds them (to 4 decimals), on 0-255 code values.
// Its offsets of 128 cancel in a difference.
Vec3 ycbcr_as_mmetric(const Vec3& rgb) {
  return {0.2126 * rgb.x() + 0.7152 * rgb.y() + 0.0722 * rgb.z(),
          -0.1146 * rgb.x() - 0.3854 * rgb.y() + 0.5 * rgb.z(),
          0.5 * rgb.x() - 0.4542 * rgb.y() - 0.0458 * rgb.z()};
}

}  // namespace

std::vector<Vec3> fibonacci_directions(int count) {
  std::vector<Vec3> directions;
  const double golden_angle = M_PI * (3 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double y = 1 - 2.0 * i / (count - 1), radius = std::sqrt(std::max(0.0, 1 - y * y));
    const double theta = golden_angle * i;
    directions.emplace_back(std::cos(theta) * radius, y, std::sin(theta) * radius);
  }
  return directions;
}

ImageBasedResult image_based_comparison(const TriangleMesh& reference, const TriangleMesh& test,
                                        const ImageBasedOptions& options) {
  if (options.views < 2 || options.views > 1000) {
    throw Error(fmt::format("--ibsm-views: expected 2 to 1000 cameras, found {}", options.views));
  }
  if (options.resolution < 16) {
    throw Error(fmt::format("--ibsm-resolution: expected at least 16 pixels, found {}", options.resolution));
  }
  const Stopwatch watch;
  ImageBasedResult result;
  result.views = options.views;
  result.resolution = options.resolution;
  result.colour = reference.has_colour() && test.has_colour();
  result.box_ratio = 100 * test.bounding_box().diagonal() / reference.bounding_box().diagonal();
  BoundingBox box = reference.bounding_box();
  box.extend(test.bounding_box().min);
  box.extend(test.bounding_box().max);
  const double radius = 1.01 * 0.5 * box.diagonal();  // 1% more: the models do not touch the border

  const auto renderer_a = shaded_renderer(reference, options.backend);
  const auto renderer_b = shaded_renderer(test, options.backend);
  if (options.resolution > renderer_a->max_framebuffer_size()) {
    throw Error(
        fmt::format("--ibsm-resolution: expected at most {} (this GL's largest framebuffer), found {}",
                    renderer_a->max_framebuffer_size(), options.resolution));
  }
  std::vector<float> depth_a, depth_b;
  std::vector<Colour> colour_a, colour_b;
  Vec3 rgb_sse = Vec3::Zero(), ycbcr_sse = Vec3::Zero();
  double depth_sse = 0;
  const auto code = [](const Colour& c) {  // as an 8-bit frame buffer stores it
    return Vec3(std::round(std::clamp(double(c.x()), 0.0, 255.0)),
                std::round(std::clamp(double(c.y()), 0.0, 255.0)),
                std::round(std::clamp(double(c.z()), 0.0, 255.0)));
  };
  for (const Vec3& direction : fibonacci_directions(options.views)) {
    const OrthoCamera camera = camera_towards(box.centre(), direction, radius, options.resolution);
    renderer_a->render_shaded_view(camera, options.resolution, options.cull_back_faces, depth_a, colour_a);
    renderer_b->render_shaded_view(camera, options.resolution, options.cull_back_faces, depth_b, colour_b);
    for (std::size_t i = 0; i < depth_a.size(); ++i) {
      const bool a = depth_a[i] < 1.0f, b = depth_b[i] < 1.0f;
      if (a != b) ++result.unmatched_pixels;
      if (!a || !b) continue;
      ++result.matched_pixels;
      // mmetric's depth is clip-space z, 1 / r a model unit, and it divides a difference by the far
      // plane's |z|, 3: a fraction of 3 r. Ours is a fraction of the view's depth, 2 r.
      const double dz = (double(depth_a[i]) - double(depth_b[i])) * 2 / 3;
      depth_sse += dz * dz;
      if (!result.colour) continue;
      const Vec3 ca = code(colour_a[i]), cb = code(colour_b[i]);
      rgb_sse += (ca - cb).cwiseAbs2();
      ycbcr_sse += (ycbcr_as_mmetric(ca) - ycbcr_as_mmetric(cb)).cwiseAbs2();
    }
  }
  const double n = static_cast<double>(result.matched_pixels);
  result.unmatched_percent = n > 0 ? 100.0 * double(result.unmatched_pixels) / n : 100.0;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  result.depth_psnr =
      n > 0 ? (depth_sse > 0 ? std::min(kPsnrCap, 10 * std::log10(n / depth_sse)) : kPsnrCap) : nan;
  if (result.colour && n > 0) {
    for (int c = 0; c < 3; ++c) {
      result.rgb_mse[c] = rgb_sse[c] / n;
      result.ycbcr_mse[c] = ycbcr_sse[c] / n;
      result.psnr_ycbcr[c] = psnr(result.ycbcr_mse[c]);
      result.psnr_rgb_channels[c] = psnr(result.rgb_mse[c]);
    }
    result.psnr_rgb = psnr((result.rgb_mse[0] + result.rgb_mse[1] + result.rgb_mse[2]) / 3);
    result.psnr_ycbcr_611 = psnr((6 * result.ycbcr_mse[0] + result.ycbcr_mse[1] + result.ycbcr_mse[2]) / 8);
  } else {
    result.rgb_mse.fill(nan), result.ycbcr_mse.fill(nan), result.psnr_ycbcr.fill(nan);
    result.psnr_rgb_channels.fill(nan);
    result.psnr_rgb = result.psnr_ycbcr_611 = nan;
  }
  result.seconds = watch.seconds();
  return result;
}

}  // namespace roving
