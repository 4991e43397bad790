// The cooperative method (paper Section 4.3): viewpoint sampling, then surface roving for the
// samples no view accepted (occluded, or beyond the threshold).
#include <tbb/task_arena.h>

#include <algorithm>
#include <numeric>
#include <optional>

#include "gl_passes.h"
#include "roving/core/stopwatch.h"
#include "roving/gl_methods/gl_methods.h"

namespace roving {
namespace {

class Cooperative final : public GlMethod {
 public:
  using GlMethod::GlMethod;
  std::string name() const override { return "cooperative"; }

  void resolve(const SampleSet& samples, double max_error, GlReport& report, const Record& record,
               const Coloured& coloured) override {
    const Found by_camera = [&](std::uint32_t k, double d, std::uint32_t face) {
      record(k, d, Resolution::Camera, face);
    };
    std::vector<std::uint32_t> candidates;
    std::optional<ViewBudget> budget;
    if (options_.auto_views) {
      budget = start_cameras(samples, max_error, report, by_camera, coloured, candidates);
      if (!budget) return;  // the cameras did every sample
    } else {
      candidates.resize(samples.size());
      std::iota(candidates.begin(), candidates.end(), 0u);
    }
    std::vector<std::uint8_t> viewed(samples.size(), 0);
    view_sample(
        scene_, samples, candidates, max_error, options_, report, progress_,
        [&](std::uint32_t k, double d, std::uint32_t face) {
          viewed[k] = 1;
          record(k, d, Resolution::View, face);
        },
        coloured, budget ? &*budget : nullptr);
    scene_.clusters.reset();  // the views' culling structure; the cameras use the grid
    // What no view accepted goes to the cameras (candidates is reused for it).
    candidates.erase(
        std::remove_if(candidates.begin(), candidates.end(), [&](std::uint32_t k) { return viewed[k]; }),
        candidates.end());
    rove(scene_, samples, candidates, max_error, report, progress_, by_camera, coloured);
  }

 private:
  // --views auto: the cameras start, timed as they go. First 1/16 of the samples (4,096 to
  // 65,536) in 16 runs of consecutive samples spread over the model (neighbours, whose cameras
  // find the grid cells and triangles in cache as the others' do: single samples spread evenly
  // measured a camera at 1.8 times its cost at 4.4 M samples), then the rest in order. Once the
  // runs are done and a batch after the first is timed, views are explored only if the fullest
  // direction's samples would cost their cameras more than exploring costs at least: grouping
  // every sample by direction, and a view drawn with its shaders' first compile, taken to cost
  // what the first batch's draw did with the tile shader's. Below that not even the fullest view
  // can repay it. Then the cameras stop there and this returns the views' budget, leaving in
  // `candidates` the samples they did not do; otherwise they go on to the end in the same
  // pipeline, and no view is drawn.
  std::optional<ViewBudget> start_cameras(const SampleSet& samples, double max_error, GlReport& report,
                                          const Found& by_camera, const Coloured& coloured,
                                          std::vector<std::uint32_t>& candidates) {
    const std::size_t runs_total =
        std::min(samples.size(), std::clamp<std::size_t>(samples.size() / 16, 4096, 65536));
    std::vector<std::uint32_t> order;
    order.reserve(samples.size());
    std::vector<std::uint8_t> in_runs(samples.size(), 0);
    constexpr std::size_t kRuns = 16;
    for (std::size_t run = 0; run < kRuns; ++run) {
      const std::size_t begin = run * samples.size() / kRuns;
      const std::size_t length = (run + 1) * runs_total / kRuns - run * runs_total / kRuns;
      for (std::size_t k = begin; k < begin + length; ++k) {
        order.push_back(static_cast<std::uint32_t>(k));
        in_runs[k] = 1;
      }
    }
    for (std::uint32_t k = 0; k < samples.size(); ++k) {
      if (!in_runs[k]) order.push_back(k);
    }
    report.axis_views = axis_normals(samples);  // what the views would be, drawn or not
    const Grouping grouping =
        estimate_grouping(samples, ViewGrid(report.axis_views, options_.views_h, options_.views_v));
    bool decided = false;
    double seconds_per_camera = 0;
    const std::size_t done =
        rove(scene_, samples, order, max_error, report, progress_, by_camera, coloured,
             [&](std::size_t done, const CameraCost& cost) {
               if (decided || done < runs_total || cost.stepped_cameras == 0) return false;
               decided = true;
               seconds_per_camera = cost.seconds_per_camera();
               return grouping.fullest * seconds_per_camera > grouping.seconds + cost.first_draw_seconds;
             });
    if (done == order.size()) return std::nullopt;
    candidates.assign(order.begin() + done, order.end());
    return ViewBudget(seconds_per_camera);
  }

  // How many samples the fullest view direction holds, and how long grouping all the samples
  // by direction takes, both estimated from about 4,096 spread evenly.
  struct Grouping {
    double fullest = 0, seconds = 0;
  };
  static Grouping estimate_grouping(const SampleSet& samples, const ViewGrid& grid) {
    std::vector<std::size_t> counts(grid.directions.size(), 0);
    const Stopwatch watch;
    const std::size_t stride = std::max<std::size_t>(1, samples.size() / 4096);
    for (std::size_t k = 0; k < samples.size(); k += stride) ++counts[grid.nearest(samples.normals[k])];
    const double threads = tbb::this_task_arena::max_concurrency();  // grouping runs on all of them
    return {double(*std::max_element(counts.begin(), counts.end())) * double(stride),
            watch.seconds() * double(stride) / threads};
  }
};

}  // namespace

std::unique_ptr<DistanceMethod> make_cooperative(const GlMethodOptions& options) {
  return std::make_unique<Cooperative>(options);
}

}  // namespace roving
