// Exact surface roving (paper Section 4.1): one orthographic one-pixel camera per sample.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "gl_passes.h"
#include "roving/core/normal_line.h"
#include "roving/gl_methods/gl_methods.h"

namespace roving {
namespace {

// Tiles per draw: 512 x 512, well inside every GL's framebuffer and a few MB of vertices.
constexpr std::size_t kTilesPerBatch = 512 * 512;
constexpr std::size_t kSamplesPerChunk = 512;

// The 2D distance, in the camera's normalised frame (units of the camera half-width), from the
// central ray to the segment p-q.
double distance_to_ray(const Vec3& p, const Vec3& q) {
  const double du = q.x() - p.x(), dv = q.y() - p.y();
  const double length_squared = du * du + dv * dv;
  const double t =
      length_squared > 0 ? std::clamp(-(p.x() * du + p.y() * dv) / length_squared, 0.0, 1.0) : 0.0;
  return std::hypot(p.x() + t * du, p.y() + t * dv);
}

// Appends, for sample camera `camera` in tile `tile`, every triangle of the grid cells along its
// view volume that can reach the volume, in the camera's normalised frame; and, where an edge or
// a vertex passes within the camera's pixel, that edge as a line and that vertex as a point, so
// that the ray meets a closed triangle widened by the pixel's half-width (the shared rule of
// normal_line.h, whose tolerance the half-width is) whatever the fill rule decides on an edge.
// `stamp` marks triangles already seen for this camera (cells share triangles).
void emit_triangles(const TriangleMesh& test, const TriangleGrid& grid, const OrthoCamera& camera,
                    std::uint32_t tile, std::vector<std::uint32_t>& stamp, std::uint32_t mark,
                    TileBatch& out) {
  const Vec3 a = camera.centre - camera.half_depth * camera.forward;
  const Vec3 b = camera.centre + camera.half_depth * camera.forward;
  grid.for_each_along(a, b, [&](std::uint32_t face) {
    if (stamp[face] == mark) return;
    stamp[face] = mark;
    const Triangle& t = test.triangles()[face];
    Vec3 q[3];
    for (int c = 0; c < 3; ++c) q[c] = camera.to_normalised(test.positions()[t[c]]);
    // Cheap rejection: all corners beyond one face of the view volume.
    for (int axis = 0; axis < 3; ++axis) {
      const double low = axis == 2 ? 0.0 : -1.0;
      if ((q[0][axis] > 1 && q[1][axis] > 1 && q[2][axis] > 1) ||
          (q[0][axis] < low && q[1][axis] < low && q[2][axis] < low)) {
        return;
      }
    }
    const auto vertex = [&](const Vec3& p) {
      return TileVertex{float(p.x()), float(p.y()), float(p.z()), tile};
    };
    for (const Vec3& p : q) out.triangles.push_back(vertex(p));
    // Lines and points reach at most half a pixel (one normalised unit) across; 1.5 leaves room.
    for (int e = 0; e < 3; ++e) {
      const Vec3 &p = q[e], &r = q[(e + 1) % 3];
      if (distance_to_ray(p, r) <= 1.5) {
        out.lines.push_back(vertex(p));
        out.lines.push_back(vertex(r));
      }
      if (std::abs(p.x()) <= 1.5 && std::abs(p.y()) <= 1.5) out.points.push_back(vertex(p));
    }
  });
}

class SurfaceRoving final : public GlMethod {
 public:
  using GlMethod::GlMethod;
  std::string name() const override { return "roving"; }

  void resolve(const SampleSet& samples, double max_error, GlReport& report, const Record& record) override {
    std::vector<std::uint32_t> all(samples.size());
    for (std::uint32_t k = 0; k < all.size(); ++k) all[k] = k;
    const auto d = rove(scene_, samples, all, max_error, report);
    for (std::uint32_t k = 0; k < all.size(); ++k) {
      if (d[k]) record(k, *d[k], Resolution::Camera);
    }
  }
};

}  // namespace

std::vector<std::optional<double>> rove(GlScene& scene, const SampleSet& samples,
                                        const std::vector<std::uint32_t>& indices, double max_error,
                                        GlReport& report) {
  const TriangleMesh& test = *scene.test;
  // The camera's half-width: half a pixel across, and the shared rule's tolerance, which the
  // lines and points drawn for edges and vertices near the ray reach (normal_line.h). Tiny:
  // rasteriser subpixel snapping (1/256 pixel in llvmpipe) moves the ray by 1/128 of it.
  const double half_width = kNormalLineTolerance * test.bounding_box().diagonal();
  report.camera_half_width = half_width;
  report.camera_depth_step = 2 * max_error * std::ldexp(1.0, -24);
  report.sample_cameras += indices.size();

  std::vector<std::optional<double>> out(indices.size());
  std::vector<float> depth;
  for (std::size_t first = 0; first < indices.size(); first += kTilesPerBatch) {
    const std::size_t count = std::min(kTilesPerBatch, indices.size() - first);
    const std::size_t chunks = (count + kSamplesPerChunk - 1) / kSamplesPerChunk;
    std::vector<TileBatch> chunk_batches(chunks);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        thread_local std::vector<std::uint32_t> stamp;
                        thread_local std::uint32_t mark = 0;
                        if (stamp.size() < test.triangle_count())
                          stamp.assign(test.triangle_count(), mark = 0);
                        for (std::size_t chunk = range.begin(); chunk != range.end(); ++chunk) {
                          const std::size_t end = std::min(count, (chunk + 1) * kSamplesPerChunk);
                          for (std::size_t tile = chunk * kSamplesPerChunk; tile < end; ++tile) {
                            const std::uint32_t k = indices[first + tile];
                            if (++mark == 0)
                              std::fill(stamp.begin(), stamp.end(), mark++);  // wrapped: start afresh
                            // Camera at x + h n looking along -n; its box spans t in [0, 2h] (depth 0 at x +
                            // h n).
                            const OrthoCamera camera = OrthoCamera::looking_along(
                                -samples.normals[k], samples.positions[k], half_width, half_width, max_error);
                            emit_triangles(test, *scene.grid, camera, static_cast<std::uint32_t>(tile), stamp,
                                           mark, chunk_batches[chunk]);
                          }
                        }
                      });
    TileBatch batch;
    for (const TileBatch& part : chunk_batches) {
      batch.triangles.insert(batch.triangles.end(), part.triangles.begin(), part.triangles.end());
      batch.lines.insert(batch.lines.end(), part.lines.begin(), part.lines.end());
      batch.points.insert(batch.points.end(), part.points.begin(), part.points.end());
    }
    scene.renderer->render_tiles(batch, count, depth);
    for (std::size_t tile = 0; tile < count; ++tile) {
      // Depth z is t / 2h along the ray from x + h n; d = h - t. 1 is the cleared, empty tile.
      if (depth[tile] < 1.0f) out[first + tile] = max_error - double(depth[tile]) * 2 * max_error;
    }
  }
  return out;
}

std::unique_ptr<DistanceMethod> make_surface_roving(const GlMethodOptions& options) {
  return std::make_unique<SurfaceRoving>(options);
}

}  // namespace roving
