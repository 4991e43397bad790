// Viewpoint sampling (paper Section 4.3): one whole-model orthographic view per direction with
// samples, read at each sample's pixel.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <mutex>
#include <numeric>

#include "gl_passes.h"
#include "hit_colour.h"
#include "roving/core/error.h"
#include "roving/core/normal_line.h"
#include "roving/core/stopwatch.h"
#include "roving/gl_methods/agreement.h"
#include "roving/gl_methods/gl_methods.h"
#include "roving/gl_methods/view_footprint.h"

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

// Where the sample's normal line meets the surface a view shows, by marching the line
// x + t n from t = h down to -h across the view's depth image: f(t) = (depth seen at the
// point's pixel) - (the point's own depth) is positive while the point is in front of what the
// view shows; its first sign change is the line's first crossing of the visible surface, refined
// by the secant method on bilinear reads. Accepted only where that is certainly the line's
// first crossing of M_C: the whole line above it is in front of the visible surface (so nothing
// M_C draws lies on it), and the crossing lies on one smooth patch (no silhouette or step of
// the view between the last two steps). This replaces the cosine correction, which assumed M_C
// parallel to M_R and read the view along its own, tilted line (up to 10.6 degrees at 24x12):
// near a boundary, a thin part or a voxel step that line can find a surface the normal line
// does not.
class ViewLine {
 public:
  static constexpr double kCreaseDegrees = 20;

  // The view's setup (the camera and size; the pixels drawn are left whole): `depth_scale`:
  // model units per unit of normalised depth; `pixel_size` and `depth_step` (one float step of
  // depth near the far plane) in model units. The same bounds for the compute pass's lookup
  // (DepthRenderer::read_view_lines()).
  static ViewLineSetup setup(const OrthoCamera& camera, int resolution, double h, double smooth_span,
                             double depth_scale, double pixel_size, double depth_step) {
    ViewLineSetup s;
    s.camera = camera;
    s.resolution = resolution;
    s.rect = {0, 0, resolution, resolution};
    s.h = h;
    s.smooth_span = smooth_span;
    s.depth_scale = depth_scale;
    s.crease_limit = std::tan(kCreaseDegrees * M_PI / 180) * pixel_size / depth_scale;
    s.min_distance = 100 * 4 * depth_step;
    s.noise = 16 * depth_step / depth_scale;
    return s;
  }

  ViewLine(const ViewLineSetup& setup, const std::vector<float>& depth)
      : camera_(setup.camera),
        depth_(depth),
        resolution_(setup.resolution),
        smooth_span_(setup.smooth_span),
        depth_scale_(setup.depth_scale),
        crease_limit_(setup.crease_limit),
        min_distance_(setup.min_distance),
        noise_(setup.noise) {}

  std::optional<double> first_crossing(const Vec3& x, const Vec3& n, double h) const {
    // Steps of at most half a pixel across the image, at least 2.
    const Vec3 a = camera_.to_normalised(x + h * n), b = camera_.to_normalised(x - h * n);
    const double pixels = 0.5 * resolution_ * std::hypot(a.x() - b.x(), a.y() - b.y());
    const int steps = std::max(2, static_cast<int>(std::ceil(2 * pixels)));
    double t_previous = h;
    std::optional<double> f_previous = f(x, n, h);
    if (!f_previous || *f_previous < 0) return std::nullopt;  // the top is hidden: can't tell
    for (int k = 1; k <= steps; ++k) {
      const double t = h - 2 * h * k / steps;
      const std::optional<double> f_now = f(x, n, t);
      if (!f_now) return std::nullopt;  // across a silhouette or off M_C's image
      if (*f_now <= 0) {
        const double s = refine(x, n, t, *f_now, t_previous, *f_previous);
        // Bilinear reading cuts the corner of a crease by up to a quarter of the second
        // difference across it: keep that under 2.5% of |d| (and under a 20-degree crease),
        // which only the few samples next to a crease reach (the matrix in gl-accuracy: every
        // pair within 1%; at 1% per sample, twice the cameras for no measurable gain).
        const double limit = std::min(crease_limit_, 0.1 * std::abs(s) / depth_scale_);
        const Vec3 at = camera_.to_normalised(x + s * n);
        if (flat_around(at, limit)) {
          // A float depth image resolves d to a few of its steps: keep only distances at least
          // 100 times that, so a view-resolved d errs by under 1%; nearer ones go to roving,
          // whose camera spans 2h, not the whole model, in the same float.
          if (std::abs(s) < min_distance_) return std::nullopt;
          return s;
        }
        // Too near a gentle crease for bilinear reading at this d: the crease may lie outside
        // the point's cell, and then the cell's plane gives d.
        if (limit == crease_limit_ || !flat_around(at, crease_limit_)) return std::nullopt;
        const std::optional<double> on_facet = on_one_facet(x, n, at);
        if (!on_facet || std::abs(*on_facet) < min_distance_) return std::nullopt;
        return on_facet;
      }
      t_previous = t;
      f_previous = f_now;
    }
    return std::nullopt;  // no crossing in view: roving decides
  }

 private:
  // True where the 4 x 4 pixels around the point are drawn and their second differences along
  // both axes stay below `limit` (normalised depth).
  bool flat_around(const Vec3& q, double limit) const {
    const double u = (0.5 * q.x() + 0.5) * resolution_ - 0.5, v = (0.5 * q.y() + 0.5) * resolution_ - 0.5;
    const int i0 = static_cast<int>(std::floor(u)) - 1, j0 = static_cast<int>(std::floor(v)) - 1;
    if (i0 < 0 || j0 < 0 || i0 + 3 >= resolution_ || j0 + 3 >= resolution_) return false;
    const auto at = [&](int i, int j) {
      return double(depth_[static_cast<std::size_t>(j) * resolution_ + i]);
    };
    for (int a = 0; a < 4; ++a) {
      for (int b = 0; b < 4; ++b) {
        if (at(i0 + a, j0 + b) >= 1.0) return false;
      }
    }
    for (int a = 0; a < 4; ++a) {
      for (int b = 1; b < 3; ++b) {
        if (std::abs(at(i0 + b - 1, j0 + a) - 2 * at(i0 + b, j0 + a) + at(i0 + b + 1, j0 + a)) > limit)
          return false;
        if (std::abs(at(i0 + a, j0 + b - 1) - 2 * at(i0 + a, j0 + b) + at(i0 + a, j0 + b + 1)) > limit)
          return false;
      }
    }
    return true;
  }

  // A triangle mesh's depth image is planar on each facet. Where the 2 x 2 pixels around `at`
  // (normalised) lie on one plane, and along each axis so do the two pixels beyond them on one
  // side or the other, one facet holds their whole cell: a crease through the cell would put a
  // pixel off the plane, or, parallel to an axis, the pixels beyond on both sides. Then the
  // crossing of the line x + t n with that plane, if it lies in the cell, is the line's crossing
  // of the surface, exact but for the pixels' float noise; nullopt otherwise.
  std::optional<double> on_one_facet(const Vec3& x, const Vec3& n, const Vec3& at) const {
    const double u = (0.5 * at.x() + 0.5) * resolution_ - 0.5, v = (0.5 * at.y() + 0.5) * resolution_ - 0.5;
    const int i0 = static_cast<int>(std::floor(u)) - 1, j0 = static_cast<int>(std::floor(v)) - 1;
    // z(i, j) over the 4 x 4 window, the cell between i, j in [1, 2]; flat_around has checked
    // that all 16 are drawn, inside the image.
    const auto z = [&](int i, int j) {
      return double(depth_[static_cast<std::size_t>(j0 + j) * resolution_ + i0 + i]);
    };
    if (std::abs(z(1, 1) - z(2, 1) - z(1, 2) + z(2, 2)) > noise_) return std::nullopt;
    const double gx = 0.5 * (z(2, 1) - z(1, 1) + z(2, 2) - z(1, 2));
    const double gy = 0.5 * (z(1, 2) - z(1, 1) + z(2, 2) - z(2, 1));
    const double c = 0.25 * (z(1, 1) + z(2, 1) + z(1, 2) + z(2, 2)) - 1.5 * (gx + gy);
    const auto plane = [&](double i, double j) { return c + gx * i + gy * j; };
    const auto on_plane = [&](int i, int j) { return std::abs(z(i, j) - plane(i, j)) <= noise_; };
    const bool along_x = (on_plane(0, 1) && on_plane(0, 2)) || (on_plane(3, 1) && on_plane(3, 2));
    const bool along_y = (on_plane(1, 0) && on_plane(2, 0)) || (on_plane(1, 3) && on_plane(2, 3));
    if (!along_x || !along_y) return std::nullopt;
    // The line in the window's coordinates, w(t) = w0 + t dw.
    const auto window = [&](const Vec3& q) {
      return Vec3((0.5 * q.x() + 0.5) * resolution_ - 0.5 - i0, (0.5 * q.y() + 0.5) * resolution_ - 0.5 - j0,
                  q.z());
    };
    const Vec3 w0 = window(camera_.to_normalised(x)), dw = window(camera_.to_normalised(x + n)) - w0;
    const double rate = gx * dw.x() + gy * dw.y() - dw.z();
    if (rate == 0) return std::nullopt;  // the line runs in the plane
    const double t = (w0.z() - plane(w0.x(), w0.y())) / rate;
    const Vec3 w = w0 + t * dw;
    if (!(w.x() >= 1 && w.x() <= 2 && w.y() >= 1 && w.y() <= 2)) return std::nullopt;
    return t;
  }

  // Seen minus own depth at x + t n (normalised depth); nullopt where the view is not one smooth
  // drawn patch around that pixel.
  std::optional<double> f(const Vec3& x, const Vec3& n, double t) const {
    const Vec3 q = camera_.to_normalised(x + t * n);
    const double u = (0.5 * q.x() + 0.5) * resolution_ - 0.5, v = (0.5 * q.y() + 0.5) * resolution_ - 0.5;
    const int i0 = static_cast<int>(std::floor(u)), j0 = static_cast<int>(std::floor(v));
    if (i0 < 0 || j0 < 0 || i0 + 1 >= resolution_ || j0 + 1 >= resolution_) return std::nullopt;
    const auto at = [&](int i, int j) {
      return double(depth_[static_cast<std::size_t>(j) * resolution_ + i]);
    };
    const double z00 = at(i0, j0), z10 = at(i0 + 1, j0), z01 = at(i0, j0 + 1), z11 = at(i0 + 1, j0 + 1);
    const double low = std::min({z00, z10, z01, z11}), high = std::max({z00, z10, z01, z11});
    const double fx = u - i0, fy = v - j0;
    const double seen = (1 - fy) * ((1 - fx) * z00 + fx * z10) + fy * ((1 - fx) * z01 + fx * z11);
    if (high >= 1.0 || high - low > smooth_span_) {
      // Not one smooth drawn patch. Certain only that a point in front of every drawn pixel
      // around is in front of what is there (the line passes over a silhouette or step).
      if (low >= 1.0) return 1.0;
      if (q.z() < low) return low - q.z();
      return std::nullopt;
    }
    return seen - q.z();
  }

  double refine(const Vec3& x, const Vec3& n, double t_low, double f_low, double t_high,
                double f_high) const {
    // Secant steps inside the bracket [t_low, t_high], f(t_low) <= 0 < f(t_high).
    for (int iteration = 0; iteration < 4 && f_high - f_low > 0; ++iteration) {
      const double t = t_high - f_high * (t_high - t_low) / (f_high - f_low);
      const std::optional<double> f_t = f(x, n, t);
      if (!f_t) break;
      if (*f_t <= 0) {
        t_low = t, f_low = *f_t;
      } else {
        t_high = t, f_high = *f_t;
      }
    }
    return f_high - f_low > 0 ? t_high - f_high * (t_high - t_low) / (f_high - f_low) : t_low;
  }

  OrthoCamera camera_;
  const std::vector<float>& depth_;
  int resolution_;
  double smooth_span_, depth_scale_, crease_limit_, min_distance_;
  double noise_;  // normalised depth: a few float steps, what a pixel's depth may err by
};

}  // namespace

void view_sample(GlScene& scene, const SampleSet& samples, const std::vector<std::uint32_t>& candidates,
                 double max_error, const GlMethodOptions& options, GlReport& report,
                 const ProgressFn& progress, const Found& found, const Coloured& coloured,
                 ViewBudget* budget) {
  report.axis_views = axis_normals(samples);
  const ViewGrid grid(report.axis_views, options.views_h, options.views_v);
  const std::vector<Vec3>& directions = grid.directions;
  // Each sample goes to the direction nearest its normal; groups are sized before they are
  // filled, and the per-sample directions freed once grouped.
  std::vector<std::vector<std::uint32_t>> groups(directions.size());
  {
    std::vector<std::uint32_t> direction_of(candidates.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, candidates.size(), 1024),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t i = range.begin(); i != range.end(); ++i) {
                          direction_of[i] = grid.nearest(samples.normals[candidates[i]]);
                        }
                      });
    std::vector<std::size_t> sizes(directions.size(), 0);
    for (const std::uint32_t d : direction_of) ++sizes[d];
    for (std::size_t d = 0; d < directions.size(); ++d) groups[d].reserve(sizes[d]);
    for (std::size_t i = 0; i < candidates.size(); ++i) groups[direction_of[i]].push_back(candidates[i]);
  }
  // Fullest views first: with a budget, the views worth drawing come first.
  std::vector<std::uint32_t> order(directions.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return groups[a].size() > groups[b].size(); });

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
  const std::size_t views =
      std::count_if(groups.begin(), groups.end(), [](const auto& g) { return !g.empty(); });
  // A view to draw: its camera (looking against the direction, at the surfaces facing it) and,
  // when culled, the pixels read and the triangles that can cover them.
  struct View {
    std::uint32_t direction = 0;
    OrthoCamera camera;
    PixelRect rect;
    std::vector<PixelRect> wanted;
    std::vector<std::uint32_t> corners;
    std::vector<float> depth;
    std::unique_ptr<TriangleGrid> blind;  // the faces it cannot draw; null where there are none
    // Looked up on the GPU: the group's samples (position, normal) and the pass's answers.
    std::vector<double> packed;
    std::vector<ViewLineAnswer> answers;
  };
  // `--camera-geometry compute`: the normal lines are looked up in a compute pass on the view
  // as drawn, nothing read back but each sample's answer.
  const bool lines_on_gpu = options.camera_geometry == CameraGeometry::Compute && options.normal_line;
  const auto line_setup = [&](const View& view) {
    ViewLineSetup s = ViewLine::setup(view.camera, resolution, max_error, smooth_span, 2 * radius,
                                      report.view_pixel_size, report.view_depth_step);
    if (options.cull_views) s.rect = view.rect;
    return s;
  };
  const bool colour = static_cast<bool>(coloured);
  std::vector<SampleHit> hits;  // the accepted samples, to be shaded once the views are done
  std::mutex hits_mutex;
  if (options.cull_views && !scene.clusters) scene.clusters = std::make_unique<TriangleClusters>(*scene.test);
  // A view never resolves a sample whose normal line may meet, at or above the view's d, a face
  // the view cannot draw (blind_faces.h): the cameras (cooperative) or nobody (viewpoint) take it.
  if (!scene.blind) scene.blind = std::make_unique<BlindFaces>(*scene.test);
  const double tolerance = kNormalLineTolerance * scene.test->bounding_box().diagonal();
  const auto prepare = [&](View& view, std::uint32_t d) {
    view.direction = d;
    view.camera = OrthoCamera::looking_along(-directions[d], box.centre(), radius, radius, radius);
    const std::vector<std::uint32_t> blind = scene.blind->for_view(directions[d]);
    view.blind = blind.empty() ? nullptr : std::make_unique<TriangleGrid>(*scene.test, blind, tolerance);
    if (lines_on_gpu) {
      view.packed.resize(6 * groups[d].size());
      for (std::size_t i = 0; i < groups[d].size(); ++i) {
        const Vec3 &x = samples.positions[groups[d][i]], &n = samples.normals[groups[d][i]];
        std::copy_n(std::array<double, 6>{x.x(), x.y(), x.z(), n.x(), n.y(), n.z()}.data(), 6, &view.packed[6 * i]);
      }
    }
    if (!options.cull_views) return;
    const ViewFootprint footprint(view.camera, resolution, samples, groups[d],
                                  options.normal_line ? max_error : 0.0);
    view.rect = footprint.rect();
    view.wanted = footprint.read_squares();
    view.corners = footprint.corners_reaching(*scene.clusters);
  };
  const auto draw = [&](View& view) {
    if (options.cull_views) {
      scene.renderer->render_view_part(view.camera, resolution, view.rect, view.wanted, view.corners,
                                       lines_on_gpu ? nullptr : &view.depth);
    } else {
      scene.renderer->render_view(view.camera, resolution, view.depth);
    }
    if (lines_on_gpu) scene.renderer->read_view_lines(line_setup(view), view.packed, view.answers);
  };
  // Whether sample k's normal line meets one of `blind`'s faces, by the rule, at or above `from`.
  const auto meets_blind = [&](const TriangleGrid& blind, std::uint32_t k, double from) {
    const Vec3 &x = samples.positions[k], &n = samples.normals[k];
    const NormalLine line(x, n, max_error, tolerance);
    const auto& p = scene.test->positions();
    bool met = false;
    blind.for_each_along(x + from * n, x + (max_error + tolerance) * n, [&](std::uint32_t face) {
      if (met) return;
      const Triangle& t = scene.test->triangles()[face];
      const auto crossing = line.crossing(p[t[0]], p[t[1]], p[t[2]]);
      met = crossing && crossing->high >= from;
    });
    return met;
  };
  // The samples of a drawn view: found(k, d) for each it accepts; returns how many.
  const auto read = [&](const View& view) {
    const std::vector<std::uint32_t>& group = groups[view.direction];
    const OrthoCamera& camera = view.camera;
    std::atomic<std::size_t> resolved{0};
    const auto accept = [&](std::uint32_t k, double d) {
      // The view's d is good to its tolerance at the sample's angle to the view; past 50 degrees
      // (coarse view grids) that bound grows without limit, and the whole line is searched.
      const double alpha = std::acos(std::clamp(-camera.forward.dot(samples.normals[k]), -1.0, 1.0));
      const double window = alpha < 50 * M_PI / 180 ? view_tolerance(report, alpha, d) : 2 * max_error;
      if (view.blind && meets_blind(*view.blind, k, d - window)) return;
      found(k, d, kFaceLeft);
      ++resolved;
      if (!colour) return;
      const SampleHit hit = hit_face(scene, samples, k, d, max_error, window);
      const std::lock_guard<std::mutex> lock(hits_mutex);
      hits.push_back(hit);
    };
    if (lines_on_gpu) {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, group.size(), 256),
                        [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i != range.end(); ++i) {
                            if (view.answers[i].accepted) accept(group[i], view.answers[i].d);
                          }
                        });
    } else if (options.normal_line) {
      const ViewLine line(line_setup(view), view.depth);
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, group.size(), 256),
                        [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i != range.end(); ++i) {
                            const std::uint32_t k = group[i];
                            const auto s =
                                line.first_crossing(samples.positions[k], samples.normals[k], max_error);
                            if (s) accept(k, *s);
                          }
                        });
    } else {
      // The paper's reading: the view at the sample's own pixel, within h of its depth.
      const Vec3& direction = directions[view.direction];
      for (std::uint32_t k : group) {
        const Vec3 q = camera.to_normalised(samples.positions[k]);
        const std::optional<double> seen = read_depth(view.depth, resolution, 0.5 * q.x() + 0.5,
                                                      0.5 * q.y() + 0.5, options.bilinear, smooth_span);
        if (!seen) continue;  // nothing drawn there
        // Along the view direction: positive where M_C is nearer the camera than the sample.
        const double along_view = (q.z() - *seen) * 2 * radius;
        // The occlusion test: another part of M_C in front shows as a difference beyond h.
        if (std::abs(along_view) > max_error) continue;
        // To the normal: a surface parallel to M_R's at distance d meets the view line at d / cos.
        accept(k, options.cosine_correction ? along_view * direction.dot(samples.normals[k]) : along_view);
      }
    }
    return resolved.load();
  };

  // A pipeline of three views: while the GL thread (this one) draws view i, the other cores read
  // view i - 1 and prepare view i + 1 (footprint and culling), so that the CPU work hides behind
  // the driver's. The order of views, and what each reads, are those of drawing one at a time.
  std::array<View, 3> ring;  // view i in ring[i % 3]
  const auto worth_drawing = [&](std::size_t i) {
    return i < views && (!budget || budget->worth_a_view(groups[order[i]].size()));
  };
  std::size_t drawn = 0;
  if (worth_drawing(0)) prepare(ring[0], order[0]);
  for (; worth_drawing(drawn); ++drawn) {
    const std::size_t i = drawn;
    if (progress) progress("views", report.views_rendered, views);
    ++report.views_rendered;
    const Stopwatch watch;
    std::size_t previous_resolved = 0;
    double cpu_seconds = 0, draw_seconds = 0;
    run_beside(
        [&] {
          const Stopwatch cpu;
          if (i > 0) previous_resolved = read(ring[(i - 1) % 3]);
          if (i + 1 < views) prepare(ring[(i + 1) % 3], order[i + 1]);
          cpu_seconds = cpu.seconds();
        },
        [&] {
          const Stopwatch gl;
          draw(ring[i % 3]);
          draw_seconds = gl.seconds();
        });
    report.view_cpu_seconds += cpu_seconds;
    report.view_draw_seconds += draw_seconds;
    if (budget) {
      budget->record_step(watch.seconds());
      if (i > 0) budget->record_read(groups[order[i - 1]].size(), previous_resolved);
    }
  }
  if (drawn > 0) {
    const Stopwatch cpu;
    const std::size_t resolved = read(ring[(drawn - 1) % 3]);
    report.view_cpu_seconds += cpu.seconds();
    if (budget) budget->record_read(groups[order[drawn - 1]].size(), resolved);
  }
  if (colour) shade_hits(scene, hits, coloured);
}

namespace {

class ViewpointSampling final : public GlMethod {
 public:
  using GlMethod::GlMethod;
  std::string name() const override { return "viewpoint"; }

  void resolve(const SampleSet& samples, double max_error, GlReport& report, const Record& record,
               const Coloured& coloured) override {
    std::vector<std::uint32_t> all(samples.size());
    std::iota(all.begin(), all.end(), 0u);
    view_sample(
        scene_, samples, all, max_error, options_, report, progress_,
        [&](std::uint32_t k, double d, std::uint32_t face) { record(k, d, Resolution::View, face); }, coloured);
  }
};

}  // namespace

std::unique_ptr<DistanceMethod> make_viewpoint_sampling(const GlMethodOptions& options) {
  if (options.auto_views) {
    throw Error(
        "--views auto: only the cooperative method has per-sample cameras to choose instead of a view; found "
        "--method viewpoint (give HxV)");
  }
  return std::make_unique<ViewpointSampling>(options);
}

}  // namespace roving
