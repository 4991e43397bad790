// Internal: the two passes the GL methods are made of, shared by roving, viewpoint and
// cooperative.
#pragma once

#include <tbb/task_group.h>

#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "roving/core/distance_method.h"
#include "roving/gl/depth_renderer.h"
#include "roving/gl_methods/gl_methods.h"
#include "blind_faces.h"
#include "surface_shades.h"
#include "triangle_clusters.h"
#include "triangle_grid.h"

namespace roving {

// A renderer with M_C uploaded and the grid for per-camera culling, made by build(); the
// clusters for per-view culling, made by the first view.
struct GlScene {
  std::unique_ptr<DepthRenderer> renderer;
  std::unique_ptr<TriangleGrid> grid;
  std::unique_ptr<TriangleClusters> clusters;
  std::unique_ptr<BlindFaces> blind;  // the views' (viewpoint_sampling.cpp), made by the first
  const TriangleMesh* test = nullptr;
  CameraGeometry cameras = CameraGeometry::Cpu;  // GlMethodOptions::camera_geometry
  SurfaceShades shades;      // colour (prepare_colour()); empty corners: none drawn
  bool faces_asked = false;  // this run asks each hit's face (DistanceOptions::faces)
  void build(GlBackend backend, const TriangleMesh& test_model, CameraGeometry camera_geometry);
  // Uploads M_C's materials and makes its shades, once: then the passes can draw colour.
  // Requires test->has_colour().
  void prepare_colour();
  // Frees the culling structures (the renderer and its context stay, to be reused).
  void release();
  std::string renderer_name() const;
};

// Runs `background` on TBB's other threads while this thread (the one holding the GL context)
// runs `foreground`; returns once both are done, rethrowing a failure of either.
template <class Background, class Foreground>
void run_beside(const Background& background, const Foreground& foreground) {
  tbb::task_group others;
  others.run(background);
  try {
    foreground();
  } catch (...) {
    others.wait();
    throw;
  }
  others.wait();
}

// Where a pass hands each sample it resolves, k, its d (first hit), and the face of M_C the hit
// lies on where the pass chose it by the exact rule (hit_colour.h; the compute pass's cameras
// do), kFaceLeft where it did not. Passed on at once rather than gathered, so that no pass holds
// a value for every sample.
using Found = std::function<void(std::uint32_t k, double d, std::uint32_t face)>;
// Where a pass hands TEST's colour at a sample it resolved, as the frame buffer gives it (code
// values). An empty one: the pass draws depth alone.
using Coloured = std::function<void(std::uint32_t k, const Colour& colour)>;

// What rove's cameras cost, measured as it goes: the first batch's draw (which compiles the
// tile shader) and the steps of the pipeline after it (a batch drawn while the next is built).
struct CameraCost {
  double first_draw_seconds = 0;
  double step_seconds = 0;
  std::size_t stepped_cameras = 0;  // the cameras of those steps
  double seconds_per_camera() const { return step_seconds / double(stepped_cameras); }
};

// Asked before each batch of cameras after the first, with how many of the indices will be done
// once it is drawn and the cost so far: true makes it the last batch.
using LastBatch = std::function<bool(std::size_t done, const CameraCost& cost)>;

// Surface roving for samples[indices[i]]: found(k, d) for each k of `indices` whose camera sees
// M_C, and with `coloured` its colour there (hit_colour.h), batch by batch. Fills the report's camera fields;
// tells `progress` of each batch of cameras. Returns how many of `indices` it did: all, unless `last_batch`
// stopped it early (at a batch boundary).
std::size_t rove(GlScene& scene, const SampleSet& samples, const std::vector<std::uint32_t>& indices,
                 double max_error, GlReport& report, const ProgressFn& progress, const Found& found,
                 const Coloured& coloured = {}, const LastBatch& last_batch = {});

// `--views auto`: a view is drawn while its expected cost stays below that of the per-sample
// cameras it would save. A camera's cost is measured by the first batches of cameras; a view's
// by the steps of the views' pipeline so far (a view drawn while the previous is read and the
// next prepared), and the fraction of its samples a view resolves by the views read so far:
// until the first is read (it is read while the next is drawn), all, the most a view can save.
class ViewBudget {
 public:
  explicit ViewBudget(double seconds_per_camera) : seconds_per_camera_(seconds_per_camera) {}
  bool worth_a_view(std::size_t samples) const {
    if (steps_ == 0) return true;
    const double resolved_fraction = attempted_ ? double(resolved_) / double(attempted_) : 1.0;
    return step_seconds_ / double(steps_) < resolved_fraction * double(samples) * seconds_per_camera_;
  }
  void record_step(double seconds) { ++steps_, step_seconds_ += seconds; }
  void record_read(std::size_t samples, std::size_t resolved) {
    attempted_ += samples, resolved_ += resolved;
  }

 private:
  double seconds_per_camera_, step_seconds_ = 0;
  std::size_t steps_ = 0, attempted_ = 0, resolved_ = 0;
};

// Viewpoint sampling of samples[candidates]: found(k, d) where a view accepted sample k, from
// several threads at once (for different k). Views go in decreasing number of samples; with a
// `budget`, the first view not worth drawing ends them (the rest have fewer samples still).
// With `coloured`, each accepted sample's colour, once the views are done (hit_colour.h).
// Fills the report's view fields; tells `progress` of each view.
void view_sample(GlScene& scene, const SampleSet& samples, const std::vector<std::uint32_t>& candidates,
                 double max_error, const GlMethodOptions& options, GlReport& report,
                 const ProgressFn& progress, const Found& found, const Coloured& coloured = {},
                 ViewBudget* budget = nullptr);

// What the three GL methods share: checks, timing, and filling in the result and report; each
// method only says how it resolves samples.
class GlMethod : public DistanceMethod {
 public:
  explicit GlMethod(GlMethodOptions options) : options_(options) {}
  std::vector<Semantics> supported_semantics() const override { return {Semantics::FirstHit}; }
  double build(const TriangleMesh& test) override;
  void release() override { scene_.release(); }
  DistanceResult measure(const SampleSet& samples, const DistanceOptions& options) final;
  // Views are drawn for every sample given at once (and cooperative's budget of views weighs
  // them all); exact roving's cameras answer a batch of tiles at a time.
  std::size_t independent_run() const override { return 0; }

 protected:
  // Per-sample answers: record(k, d, how, face) marks sample k a hit with distance d, and its
  // face where the pass chose it (Found); `coloured`, when not empty, takes TEST's colour there
  // (DistanceOptions::colour).
  using Record = std::function<void(std::uint32_t k, double d, Resolution how, std::uint32_t face)>;
  virtual void resolve(const SampleSet& samples, double max_error, GlReport& report, const Record& record,
                       const Coloured& coloured) = 0;

  GlMethodOptions options_;
  GlScene scene_;
};

}  // namespace roving
