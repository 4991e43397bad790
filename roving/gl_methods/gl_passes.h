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
#include "triangle_clusters.h"
#include "triangle_grid.h"

namespace roving {

// A renderer with M_C uploaded and the grid for per-camera culling, made by build(); the
// clusters for per-view culling, made by the first view.
struct GlScene {
  std::unique_ptr<DepthRenderer> renderer;
  std::unique_ptr<TriangleGrid> grid;
  std::unique_ptr<TriangleClusters> clusters;
  const TriangleMesh* test = nullptr;

  void build(GlBackend backend, const TriangleMesh& test_model);
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

// Where a pass hands each sample it resolves, k, and its d (first hit). Passed on at once
// rather than gathered, so that no pass holds a value for every sample.
using Found = std::function<void(std::uint32_t k, double d)>;

// Surface roving for samples[indices[i]]: found(k, d) for each k of `indices` whose camera sees
// M_C. Fills the report's camera fields; tells `progress` of each batch of cameras.
void rove(GlScene& scene, const SampleSet& samples, const std::vector<std::uint32_t>& indices,
          double max_error, GlReport& report, const ProgressFn& progress, const Found& found);

// `--views auto`: a view is drawn while its expected cost stays below that of the per-sample
// cameras it would save. A camera's cost is measured by a first batch of cameras; a view's, and
// the fraction of its samples a view resolves, by the views read so far (a view is read while
// the next is drawn, so the first two are always drawn).
class ViewBudget {
 public:
  explicit ViewBudget(double seconds_per_camera) : seconds_per_camera_(seconds_per_camera) {}
  bool worth_a_view(std::size_t samples) const {
    if (views_ == 0) return true;
    const double resolved_fraction = double(resolved_) / double(attempted_);
    return view_seconds_ / views_ < resolved_fraction * double(samples) * seconds_per_camera_;
  }
  void record_view(double seconds, std::size_t samples, std::size_t resolved) {
    ++views_, view_seconds_ += seconds, attempted_ += samples, resolved_ += resolved;
  }

 private:
  double seconds_per_camera_, view_seconds_ = 0;
  std::size_t views_ = 0, attempted_ = 0, resolved_ = 0;
};

// Viewpoint sampling of samples[candidates]: found(k, d) where a view accepted sample k, from
// several threads at once (for different k). Views go in decreasing number of samples; with a
// `budget`, the first view not worth drawing ends them (the rest have fewer samples still).
// Fills the report's view fields; tells `progress` of each view.
void view_sample(GlScene& scene, const SampleSet& samples, const std::vector<std::uint32_t>& candidates,
                 double max_error, const GlMethodOptions& options, GlReport& report,
                 const ProgressFn& progress, const Found& found, ViewBudget* budget = nullptr);

// What the three GL methods share: checks, timing, and filling in the result and report; each
// method only says how it resolves samples.
class GlMethod : public DistanceMethod {
 public:
  explicit GlMethod(GlMethodOptions options) : options_(options) {}
  std::vector<Semantics> supported_semantics() const override { return {Semantics::FirstHit}; }
  double build(const TriangleMesh& test) override;
  void release() override { scene_.release(); }
  DistanceResult measure(const SampleSet& samples, const DistanceOptions& options) final;

 protected:
  // Per-sample answers: record(k, d, how) marks sample k a hit with distance d.
  using Record = std::function<void(std::uint32_t k, double d, Resolution how)>;
  virtual void resolve(const SampleSet& samples, double max_error, GlReport& report,
                       const Record& record) = 0;

  GlMethodOptions options_;
  GlScene scene_;
};

}  // namespace roving
