// Viewpoint sampling (paper Section 4.3): one whole-model orthographic view per direction with
// samples, read at each sample's pixel.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "gl_passes.h"
#include "roving/gl_methods/gl_methods.h"

namespace roving {
namespace {

// The view's depth at (u, v) in [0, 1]^2 of the image: bilinear between the four pixel centres
// around it when all four are drawn and within `smooth_span` of each other (one smooth patch;
// exact on a plane), else the pixel whose square holds the point. nullopt where nothing is drawn.
std::optional<double> read_depth(const std::vector<float>& depth, int resolution, double u, double v,
                                 bool bilinear, double smooth_span) {
  const auto at = [&](int i, int j) { return double(depth[static_cast<std::size_t>(j) * resolution + i]); };
  const int i = std::clamp(static_cast<int>(std::floor(u * resolution)), 0, resolution - 1);
  const int j = std::clamp(static_cast<int>(std::floor(v * resolution)), 0, resolution - 1);
  const double nearest = at(i, j);
  if (nearest >= 1.0) return std::nullopt;
  if (!bilinear) return nearest;
  // Pixel centres sit at integer + 0.5: interpolate between the centres that bracket the point.
  const double x = u * resolution - 0.5, y = v * resolution - 0.5;
  const int i0 = static_cast<int>(std::floor(x)), j0 = static_cast<int>(std::floor(y));
  if (i0 < 0 || j0 < 0 || i0 + 1 >= resolution || j0 + 1 >= resolution) return nearest;
  const double z00 = at(i0, j0), z10 = at(i0 + 1, j0), z01 = at(i0, j0 + 1), z11 = at(i0 + 1, j0 + 1);
  const double low = std::min({z00, z10, z01, z11}), high = std::max({z00, z10, z01, z11});
  if (high >= 1.0 || high - low > smooth_span) return nearest;
  const double fx = x - i0, fy = y - j0;
  return (1 - fy) * ((1 - fx) * z00 + fx * z10) + fy * ((1 - fx) * z01 + fx * z11);
}

}  // namespace

std::vector<std::optional<double>> view_sample(GlScene& scene, const SampleSet& samples, double max_error,
                                               const GlMethodOptions& options, GlReport& report) {
  // Voxel references have only axis normals: then the 6 axis views suffice (Section 4.3).
  const bool axis_normals = std::all_of(samples.normals.begin(), samples.normals.end(), [](const Vec3& n) {
    return n.cwiseAbs().maxCoeff() == 1.0 && n.cwiseAbs().sum() == 1.0;
  });
  const std::vector<Vec3> directions =
      axis_normals ? axis_directions() : view_directions(options.views_h, options.views_v);
  report.axis_views = axis_normals;
  // Each sample goes to the direction nearest its normal.
  std::vector<std::uint32_t> direction_of(samples.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t k = range.begin(); k != range.end(); ++k) {
                        std::uint32_t best = 0;
                        double best_dot = -2;
                        for (std::uint32_t d = 0; d < directions.size(); ++d) {
                          const double dot = directions[d].dot(samples.normals[k]);
                          if (dot > best_dot) best_dot = dot, best = d;
                        }
                        direction_of[k] = best;
                      }
                    });
  std::vector<std::vector<std::uint32_t>> groups(directions.size());
  for (std::uint32_t k = 0; k < samples.size(); ++k) groups[direction_of[k]].push_back(k);

  // One view box for all directions: the sphere around M_C and the samples, widened by h.
  BoundingBox box = scene.test->bounding_box();
  for (const Vec3& x : samples.positions) box.extend(x);
  const double radius = 0.5 * box.diagonal() + max_error;
  const int resolution = options.resolution;
  report.view_pixel_size = 2 * radius / resolution;
  report.view_depth_step = 2 * radius * std::ldexp(1.0, -24);

  // Four neighbouring depths are one smooth patch when they differ by less than a surface at
  // 80 degrees to the view would over two pixels (in normalised depth).
  const double smooth_span = 2 * report.view_pixel_size * std::tan(80 * M_PI / 180) / (2 * radius);
  std::vector<std::optional<double>> out(samples.size());
  std::vector<float> depth;
  for (std::size_t d = 0; d < directions.size(); ++d) {
    if (groups[d].empty()) continue;
    ++report.views_rendered;
    // The camera looks against the direction, at the surfaces facing it.
    const OrthoCamera camera =
        OrthoCamera::looking_along(-directions[d], box.centre(), radius, radius, radius);
    scene.renderer->render_view(camera, resolution, depth);
    for (std::uint32_t k : groups[d]) {
      const Vec3 q = camera.to_normalised(samples.positions[k]);
      const std::optional<double> seen =
          read_depth(depth, resolution, 0.5 * q.x() + 0.5, 0.5 * q.y() + 0.5, options.bilinear, smooth_span);
      if (!seen) continue;  // nothing drawn there
      // Along the view direction: positive where M_C is nearer the camera than the sample.
      const double along_view = (q.z() - *seen) * 2 * radius;
      // The occlusion test: another part of M_C in front shows as a difference beyond h.
      if (std::abs(along_view) > max_error) continue;
      // To the normal: a surface parallel to M_R's at distance d meets the view line at d / cos.
      out[k] = options.cosine_correction ? along_view * directions[d].dot(samples.normals[k]) : along_view;
    }
  }
  return out;
}

namespace {

class ViewpointSampling final : public GlMethod {
 public:
  using GlMethod::GlMethod;
  std::string name() const override { return "viewpoint"; }

  void resolve(const SampleSet& samples, double max_error, GlReport& report, const Record& record) override {
    const auto d = view_sample(scene_, samples, max_error, options_, report);
    for (std::uint32_t k = 0; k < samples.size(); ++k) {
      if (d[k]) record(k, *d[k], Resolution::View);
    }
  }
};

}  // namespace

std::unique_ptr<DistanceMethod> make_viewpoint_sampling(const GlMethodOptions& options) {
  return std::make_unique<ViewpointSampling>(options);
}

}  // namespace roving
