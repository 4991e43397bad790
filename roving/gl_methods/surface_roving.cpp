// Exact surface roving (paper Section 4.1): one orthographic one-pixel camera per sample.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "gl_passes.h"
#include "hit_colour.h"
#include "roving/core/geometry.h"
#include "roving/core/normal_line.h"
#include "roving/core/stopwatch.h"
#include "roving/gl_methods/agreement.h"
#include "roving/gl_methods/gl_methods.h"

namespace roving {
namespace {

// If the segment p-q (normalised camera frame) passes within the pixel, a strip of half-width 1
// around its part near the pixel (two triangles, depth varying along it), and an octagon of
// radius 1 around p if p is near (six triangles at p's depth): the points within one
// half-width of the edge, as the shared rule widens it. The GPU builds the same in
// gl_depth_renderer.cpp's kTileFaceVertexShader, operation for operation: change both.
template <class Emit>
void widen_edge(const Vec3& p, const Vec3& q, const Emit& emit) {
  constexpr double kWindow = 2;  // clip to this square first: small, exact coordinates
  if (std::abs(p.x()) <= kWindow && std::abs(p.y()) <= kWindow) {
    constexpr int kSides = 8;
    Vec3 ring[kSides];
    for (int i = 0; i < kSides; ++i) {
      const double angle = 2 * M_PI * i / kSides;
      ring[i] = Vec3(p.x() + std::cos(angle), p.y() + std::sin(angle), p.z());
    }
    for (int i = 1; i + 1 < kSides; ++i) {
      emit(ring[0]);
      emit(ring[i]);
      emit(ring[i + 1]);
    }
  }
  // Liang-Barsky: the part of p-q inside the window.
  const Vec3 delta = q - p;
  double enter = 0, leave = 1;
  for (int axis = 0; axis < 2; ++axis) {
    for (const double bound : {-kWindow, kWindow}) {
      const double distance = bound - p[axis];
      if (delta[axis] == 0) {
        if ((bound < 0 && distance > 0) || (bound > 0 && distance < 0)) return;
        continue;
      }
      const double t = distance / delta[axis];
      if ((bound < 0) == (delta[axis] > 0)) {
        enter = std::max(enter, t);
      } else {
        leave = std::min(leave, t);
      }
    }
  }
  if (enter >= leave) return;
  const Vec3 start = p + enter * delta, end = p + leave * delta;
  const double dx = end.x() - start.x(), dy = end.y() - start.y();
  const double length = std::sqrt(dx * dx + dy * dy);  // not hypot: GLSL has only sqrt
  if (!(length > 1e-9)) return;                        // seen end-on: the octagons at its ends cover it
  const Vec3 across((start.y() - end.y()) / length, (end.x() - start.x()) / length, 0);
  const Vec3 corners[4] = {start + across, end + across, end - across, start - across};
  for (const int i : {0, 1, 2, 0, 2, 3}) emit(corners[i]);
}

// Tiles per draw: 64 x 64, small enough that the next batch is built while one is drawn, large
// enough that the per-draw cost (clear, flush, read back) is spread over many cameras.
constexpr std::size_t kTilesPerBatch = 64 * 64;
constexpr std::size_t kSamplesPerChunk = 512;
// Cameras per batch in the compute pass: one dispatch of 1,024 work groups, while the next
// batch's samples are packed.
constexpr std::size_t kComputedPerBatch = 1 << 16;

// A face less than one camera half-width wide across the camera (edge-on to the line, degenerate
// to a segment or a point, or nearly so) covers no pixel centre by itself, and the strips along
// its edges give their own depths, not the face's: the rasteriser cannot follow the rule there.
// Such a face is not drawn; the rule decides it (normal_line.h), on the same doubles as Embree
// and CGAL, and the tile's d is the higher of the two (first-hit: the highest crossing).
bool thin_across(const Vec3 (&offset)[3], const OrthoCamera& camera) {
  double x[3], y[3], longest_squared = 0;
  for (int c = 0; c < 3; ++c) x[c] = offset[c].dot(camera.right), y[c] = offset[c].dot(camera.up);
  for (int e = 0; e < 3; ++e) {
    const int f = (e + 1) % 3;
    longest_squared = std::max(longest_squared, (x[f] - x[e]) * (x[f] - x[e]) + (y[f] - y[e]) * (y[f] - y[e]));
  }
  const double twice_area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
  return !(twice_area * twice_area > camera.half_width * camera.half_width * longest_squared);
}

// The tile's top crossing among its thin faces, by the rule.
class ThinFaces {
 public:
  ThinFaces(const SampleSet& samples, std::uint32_t k, double max_error, double tolerance)
      : samples_(samples), k_(k), max_error_(max_error), tolerance_(tolerance) {}
  void consider(const TriangleMesh& test, std::uint32_t face) {
    if (!line_) line_.emplace(samples_.positions[k_], samples_.normals[k_], max_error_, tolerance_);
    const Triangle& t = test.triangles()[face];
    const auto crossing = line_->crossing(test.positions()[t[0]], test.positions()[t[1]], test.positions()[t[2]]);
    if (crossing && (!top_ || crossing->high > *top_)) top_ = crossing->high;
  }
  const std::optional<double>& top() const { return top_; }

 private:
  const SampleSet& samples_;
  std::uint32_t k_;
  double max_error_, tolerance_;
  std::optional<NormalLine> line_;
  std::optional<double> top_;
};

// Calls visit(face) for each triangle of the grid cells along the camera's view volume that is
// not wholly to one side of it across (right or up). The view volume is a pixel across, so most
// triangles of a cell are: they are passed over on the corners' offsets, before any division.
// `stamp` marks triangles already seen for this camera (cells share triangles).
// Faces thin across the camera go to `thin` instead.
template <class Visit>
void for_each_candidate(const TriangleMesh& test, const TriangleGrid& grid, const OrthoCamera& camera,
                        std::vector<std::uint32_t>& stamp, std::uint32_t mark, ThinFaces& thin, const Visit& visit) {
  const Vec3 a = camera.centre - camera.half_depth * camera.forward;
  const Vec3 b = camera.centre + camera.half_depth * camera.forward;
  grid.for_each_along(a, b, [&](std::uint32_t face) {
    if (stamp[face] == mark) return;
    stamp[face] = mark;
    const Triangle& t = test.triangles()[face];
    const Vec3 offset[3] = {test.positions()[t[0]] - camera.centre, test.positions()[t[1]] - camera.centre,
                            test.positions()[t[2]] - camera.centre};
    const auto misses = [&](const Vec3& axis, double half) {
      const double a0 = offset[0].dot(axis), a1 = offset[1].dot(axis), a2 = offset[2].dot(axis);
      const double bound = half * (1 + 1e-9);  // beyond it, a / half > 1 whatever the rounding
      return (a0 > bound && a1 > bound && a2 > bound) || (a0 < -bound && a1 < -bound && a2 < -bound);
    };
    if (misses(camera.right, camera.half_width) || misses(camera.up, camera.half_height)) return;
    if (thin_across(offset, camera)) {
      thin.consider(test, face);
    } else {
      visit(face);
    }
  });
}

// One batch of cameras, as the renderer takes it: built on the CPU, the tiles' vertices; built
// on the GPU, each tile's camera and its candidate triangles; for the compute pass, the samples
// themselves (position, normal), in Morton order: `order` gives each tile's sample. Beside them,
// the tiles whose lines meet a face too thin across the camera to be drawn, with the highest d
// the rule gives there.
struct TileBatch {
  std::vector<TileVertex> vertices;
  std::vector<OrthoCamera> cameras;
  std::vector<TileFace> faces;
  std::vector<std::uint32_t> order;
  std::vector<double> samples;
  std::vector<std::pair<std::uint32_t, double>> thin_tops;
};

// Appends, for sample camera `camera` in tile `tile`, every candidate triangle that reaches the
// view volume, in the camera's normalised frame (x, y in units of the camera half-width, which is
// the shared rule's tolerance: normal_line.h). Beside each triangle, its edges and vertices that
// pass within the pixel are widened into thin strips and small octagons one half-width across
// (built in double, here), so that the rasteriser covers the pixel centre wherever the central
// ray passes through the closed triangle or within the tolerance of it, whatever its fill rule
// decides on an edge.
void emit_triangles(const GlScene& scene, const OrthoCamera& camera, std::uint32_t tile,
                    std::vector<std::uint32_t>& stamp, std::uint32_t mark, ThinFaces& thin, TileBatch& out) {
  const TriangleMesh& test = *scene.test;
  for_each_candidate(test, *scene.grid, camera, stamp, mark, thin, [&](std::uint32_t face) {
    const Triangle& t = test.triangles()[face];
    Vec3 q[3];
    for (int c = 0; c < 3; ++c) q[c] = camera.to_normalised(test.positions()[t[c]]);
    for (int axis = 0; axis < 3; ++axis) {
      const double low = axis == 2 ? 0.0 : -1.0;
      if ((q[0][axis] > 1 && q[1][axis] > 1 && q[2][axis] > 1) ||
          (q[0][axis] < low && q[1][axis] < low && q[2][axis] < low)) {
        return;
      }
    }
    const auto emit = [&](const Vec3& p) {
      out.vertices.push_back({float(p.x()), float(p.y()), float(p.z()), tile});
    };
    for (int c = 0; c < 3; ++c) emit(q[c]);
    for (int e = 0; e < 3; ++e) widen_edge(q[e], q[(e + 1) % 3], emit);
  });
}

class SurfaceRoving final : public GlMethod {
 public:
  using GlMethod::GlMethod;
  std::string name() const override { return "roving"; }
  // A drawn camera's answer is its tile's depth: rasterised at the tile's place in its batch's
  // grid. A computed one's is its own.
  std::size_t independent_run() const override {
    return options_.camera_geometry == CameraGeometry::Compute ? 1 : kTilesPerBatch;
  }

  void resolve(const SampleSet& samples, double max_error, GlReport& report, const Record& record,
               const Coloured& coloured) override {
    std::vector<std::uint32_t> all(samples.size());
    for (std::uint32_t k = 0; k < all.size(); ++k) all[k] = k;
    report.views_h = report.views_v = report.resolution = 0;  // cameras only: no view grid applies
    rove(
        scene_, samples, all, max_error, report, progress_,
        [&](std::uint32_t k, double d, std::uint32_t face) { record(k, d, Resolution::Camera, face); }, coloured);
  }
};

}  // namespace

std::size_t rove(GlScene& scene, const SampleSet& samples, const std::vector<std::uint32_t>& indices,
                 double max_error, GlReport& report, const ProgressFn& progress, const Found& found,
                 const Coloured& coloured, const LastBatch& last_batch) {
  const TriangleMesh& test = *scene.test;
  // The camera's half-width: half a pixel across, and the shared rule's tolerance, which the
  // lines and points drawn for edges and vertices near the ray reach (normal_line.h). Tiny:
  // rasteriser subpixel snapping (1/256 pixel in llvmpipe) moves the ray by 1/128 of it.
  const double half_width = kNormalLineTolerance * test.bounding_box().diagonal();
  report.camera_half_width = half_width;
  // The view volume reaches the tolerance beyond h at both ends too (normal_line.h); d is then
  // clamped into [-h, h].
  const double half_depth = max_error + half_width;
  report.camera_depth_step = 2 * half_depth * std::ldexp(1.0, -24);
  const double window = roving_tolerance(report);  // the cameras' bound on their d

  // The batch `first` .. first + batch_size of `indices`, tile by tile: chunks of tiles in
  // parallel, then joined in order.
  const bool on_gpu = scene.cameras == CameraGeometry::Gpu;
  const bool computed = scene.cameras == CameraGeometry::Compute;
  report.camera_geometry = scene.cameras;
  const std::size_t batch_size = computed ? kComputedPerBatch : kTilesPerBatch;
  // The compute pass also chooses each hit's face where colour or the faces are asked: the rest
  // (and every drawn camera's) is chosen on the CPU threads by hit_face().
  const bool faces_in_pass = computed && (coloured || scene.faces_asked);
  const RovingSetup setup{half_width, half_depth, max_error, faces_in_pass ? window : 0.0};
  // Camera at x + h n looking along -n; its box spans t in [0, 2h] (depth 0 at x + h n).
  const auto camera_of = [&](std::uint32_t k) {
    return OrthoCamera::looking_along(-samples.normals[k], samples.positions[k], half_width, half_width,
                                      half_depth);
  };
  const auto pack_batch = [&](std::size_t first, TileBatch& batch) {
    const Stopwatch building;
    const std::size_t count = std::min(batch_size, indices.size() - first);
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(count);
    for (std::size_t i = 0; i < count; ++i) {
      const std::uint32_t k = indices[first + i];
      keyed[i] = {morton_code(samples.positions[k], test.bounding_box()), k};
    }
    std::sort(keyed.begin(), keyed.end());
    batch.order.resize(count);
    batch.samples.resize(6 * count);
    for (std::size_t i = 0; i < count; ++i) {
      const std::uint32_t k = batch.order[i] = keyed[i].second;
      const Vec3 &p = samples.positions[k], &n = samples.normals[k];
      std::copy_n(std::array<double, 6>{p.x(), p.y(), p.z(), n.x(), n.y(), n.z()}.data(), 6, &batch.samples[6 * i]);
    }
    report.camera_build_seconds += building.seconds();
  };
  const auto emit_batch = [&](std::size_t first, TileBatch& batch) {
    if (computed) return pack_batch(first, batch);
    const Stopwatch building;
    const std::size_t count = std::min(batch_size, indices.size() - first);
    const std::size_t chunks = (count + kSamplesPerChunk - 1) / kSamplesPerChunk;
    std::vector<TileBatch> chunk_batches(chunks);
    batch.cameras.resize(on_gpu ? count : 0);
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, chunks), [&](const tbb::blocked_range<std::size_t>& range) {
          thread_local std::vector<std::uint32_t> stamp;
          thread_local std::uint32_t mark = 0;
          if (stamp.size() < test.triangle_count()) stamp.assign(test.triangle_count(), mark = 0);
          for (std::size_t chunk = range.begin(); chunk != range.end(); ++chunk) {
            const std::size_t end = std::min(count, (chunk + 1) * kSamplesPerChunk);
            for (std::size_t tile = chunk * kSamplesPerChunk; tile < end; ++tile) {
              const std::uint32_t k = indices[first + tile];
              if (++mark == 0) std::fill(stamp.begin(), stamp.end(), mark++);  // wrapped: start afresh
              const OrthoCamera camera = camera_of(k);
              const auto t = static_cast<std::uint32_t>(tile);
              ThinFaces thin(samples, k, max_error, half_width);
              if (on_gpu) {
                batch.cameras[tile] = camera;
                for_each_candidate(test, *scene.grid, camera, stamp, mark, thin, [&](std::uint32_t face) {
                  chunk_batches[chunk].faces.push_back({t, face});
                });
              } else {
                emit_triangles(scene, camera, t, stamp, mark, thin, chunk_batches[chunk]);
              }
              if (thin.top()) chunk_batches[chunk].thin_tops.emplace_back(t, *thin.top());
            }
          }
        });
    const auto join = [&](auto member) {
      auto& all = batch.*member;
      std::size_t total = 0;
      for (const TileBatch& c : chunk_batches) total += (c.*member).size();
      all.clear();
      all.reserve(total);
      for (const TileBatch& c : chunk_batches) all.insert(all.end(), (c.*member).begin(), (c.*member).end());
    };
    join(&TileBatch::vertices);
    join(&TileBatch::faces);
    join(&TileBatch::thin_tops);
    report.camera_build_seconds += building.seconds();
  };

  // The compute pass leaves faces thin across a camera to the rule: the tiles it flagged, decided
  // here on the CPU threads, into the batch's thin_tops.
  const auto decide_thin = [&](TileBatch& batch, const std::vector<ComputedTile>& answers) {
    const Stopwatch deciding;
    std::vector<std::uint32_t> flagged;
    for (std::uint32_t tile = 0; tile < answers.size(); ++tile)
      if (answers[tile].thin) flagged.push_back(tile);
    std::vector<std::optional<double>> tops(flagged.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, flagged.size(), 16),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        thread_local std::vector<std::uint32_t> stamp;
                        thread_local std::uint32_t mark = 0;
                        if (stamp.size() < test.triangle_count()) stamp.assign(test.triangle_count(), mark = 0);
                        for (std::size_t i = range.begin(); i != range.end(); ++i) {
                          const std::uint32_t k = batch.order[flagged[i]];
                          if (++mark == 0) std::fill(stamp.begin(), stamp.end(), mark++);
                          ThinFaces thin(samples, k, max_error, half_width);
                          for_each_candidate(test, *scene.grid, camera_of(k), stamp, mark, thin, [](std::uint32_t) {});
                          tops[i] = thin.top();
                        }
                      });
    batch.thin_tops.clear();
    for (std::size_t i = 0; i < flagged.size(); ++i)
      if (tops[i]) batch.thin_tops.emplace_back(flagged[i], *tops[i]);
    report.thin_cameras += flagged.size();
    report.camera_build_seconds += deciding.seconds();
  };

  // A pipeline of two batches: while the GL thread (this one) draws a batch, the other cores
  // build the next one.
  TileBatch batch[2];
  std::vector<ComputedTile> answers;  // the compute pass's, per tile
  std::vector<float> depth;
  std::vector<std::optional<double>> tile_d;  // a batch's d per tile, drawn and thin faces
  // A batch's hits for colour: the tile and its sample's d.
  std::vector<std::pair<std::uint32_t, double>> resolved;
  std::vector<SampleHit> hits;
  CameraCost cost;
  std::size_t end = indices.size();  // where last_batch stops it
  if (!indices.empty()) emit_batch(0, batch[0]);
  for (std::size_t first = 0, b = 0; first < end; first += batch_size, ++b) {
    const std::size_t count = std::min(batch_size, end - first);
    if (b > 0 && last_batch && last_batch(first + count, cost)) end = first + count;
    const Stopwatch step;
    double draw_seconds = 0;
    run_beside(
        [&] {
          if (first + count < end) emit_batch(first + count, batch[(b + 1) % 2]);
        },
        [&] {
          const Stopwatch draw;
          const TileBatch& drawn = batch[b % 2];
          if (computed) {
            scene.renderer->rove_samples(drawn.samples, setup, answers);
            depth.resize(count);
            for (std::size_t tile = 0; tile < count; ++tile) depth[tile] = answers[tile].depth;
          } else if (on_gpu) {
            scene.renderer->render_tile_faces(drawn.cameras, drawn.faces, depth);
          } else {
            scene.renderer->render_tiles(drawn.vertices, count, depth);
          }
          draw_seconds = draw.seconds();
          report.camera_render_seconds += draw_seconds;
        });
    resolved.clear();
    // Depth z is t / 2h along the ray from x + h n; d = h - t. 1 is the cleared, empty tile.
    tile_d.assign(count, std::nullopt);
    for (std::size_t tile = 0; tile < count; ++tile) {
      if (depth[tile] < 1.0f)
        tile_d[tile] = std::clamp(half_depth - double(depth[tile]) * 2 * half_depth, -max_error, max_error);
    }
    if (computed) decide_thin(batch[b % 2], answers);
    const auto sample_of = [&](std::size_t tile) { return computed ? batch[b % 2].order[tile] : indices[first + tile]; };
    for (const auto& [tile, top] : batch[b % 2].thin_tops) {
      if (!tile_d[tile] || top > *tile_d[tile]) tile_d[tile] = top;
    }
    const auto face_of = [&](std::size_t tile) { return faces_in_pass ? answers[tile].face : kFaceLeft; };
    for (std::size_t tile = 0; tile < count; ++tile) {
      if (!tile_d[tile]) continue;
      found(sample_of(tile), *tile_d[tile], face_of(tile));
      if (coloured) resolved.emplace_back(static_cast<std::uint32_t>(tile), *tile_d[tile]);
      if (faces_in_pass) ++(face_of(tile) == kFaceLeft ? report.faces_left_to_cpu : report.faces_chosen_in_pass);
    }
    if (coloured) {
      // Which face each hit's colour comes from, by the exact rule near the cameras' d (the
      // compute pass's choice, or hit_colour.h's), then shaded there: a tile's own fragment may
      // be any face meeting at the point.
      const Stopwatch choosing;
      hits.resize(resolved.size());
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, resolved.size(), 256),
                        [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i != range.end(); ++i) {
                            const auto [tile, d] = resolved[i];
                            const std::uint32_t k = sample_of(tile);
                            if (face_of(tile) != kFaceLeft) {
                              const ComputedTile& answer = answers[tile];
                              hits[i] = {k, answer.face,
                                         samples.positions[k] + answer.distance * samples.normals[k]};
                            } else {
                              hits[i] = hit_face(scene, samples, k, d, max_error, window);
                            }
                          }
                        });
      report.camera_build_seconds += choosing.seconds();
      const Stopwatch shading;
      shade_hits(scene, hits, coloured);
      report.camera_render_seconds += shading.seconds();
    }
    report.sample_cameras += count;
    if (b == 0) {
      cost.first_draw_seconds = draw_seconds;
    } else {
      cost.step_seconds += step.seconds();
      cost.stepped_cameras += count;
    }
    if (progress) progress("cameras", first + count, indices.size());
  }
  return end;
}

std::unique_ptr<DistanceMethod> make_surface_roving(const GlMethodOptions& options) {
  return std::make_unique<SurfaceRoving>(options);
}

}  // namespace roving
