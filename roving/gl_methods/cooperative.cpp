// The cooperative method (paper Section 4.3): viewpoint sampling, then surface roving for the
// samples no view accepted (occluded, or beyond the threshold).
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

  void resolve(const SampleSet& samples, double max_error, GlReport& report, const Record& record) override {
    std::vector<std::uint32_t> candidates(samples.size());
    std::iota(candidates.begin(), candidates.end(), 0u);
    std::optional<ViewBudget> budget;
    if (options_.auto_views) budget = calibrate(samples, max_error, report, record, candidates);
    std::vector<std::uint8_t> viewed(samples.size(), 0);
    view_sample(
        scene_, samples, candidates, max_error, options_, report, progress_,
        [&](std::uint32_t k, double d) {
          viewed[k] = 1;
          record(k, d, Resolution::View);
        },
        budget ? &*budget : nullptr);
    scene_.clusters.reset();  // the views' culling structure; the cameras use the grid
    // What no view accepted goes to the cameras (candidates is reused for it).
    candidates.erase(
        std::remove_if(candidates.begin(), candidates.end(), [&](std::uint32_t k) { return viewed[k]; }),
        candidates.end());
    rove(scene_, samples, candidates, max_error, report, progress_,
         [&](std::uint32_t k, double d) { record(k, d, Resolution::Camera); });
  }

 private:
  // --views auto: what a camera costs, timed on 1/16 of the samples (4,096 to 65,536), which are
  // then resolved (and leave `candidates`). They are 16 runs of consecutive samples spread over
  // the model: consecutive samples are neighbours, so their cameras find the grid cells and
  // triangles in cache as the cameras' own pass does (single samples spread evenly measured a
  // camera at 1.8 times its cost at 4.4 M samples). Roved in two halves of 8 runs, the first to
  // warm up (per-thread buffers sized to M_C, the driver's first batch), the second timed.
  ViewBudget calibrate(const SampleSet& samples, double max_error, GlReport& report, const Record& record,
                       std::vector<std::uint32_t>& candidates) {
    const std::size_t count =
        std::min(samples.size(), std::clamp<std::size_t>(samples.size() / 16, 4096, 65536));
    std::vector<std::uint32_t> spread[2];
    std::vector<std::uint8_t> taken(samples.size(), 0);
    constexpr std::size_t kRuns = 16;
    for (std::size_t run = 0; run < kRuns; ++run) {
      const std::size_t begin = run * samples.size() / kRuns;
      const std::size_t length = (run + 1) * count / kRuns - run * count / kRuns;  // count in all
      for (std::size_t k = begin; k < begin + length; ++k) {
        spread[run % 2].push_back(static_cast<std::uint32_t>(k));
        taken[k] = 1;
      }
    }
    double seconds_per_camera = 0;
    for (const auto& half : spread) {
      const Stopwatch watch;
      rove(scene_, samples, half, max_error, report, progress_,
           [&](std::uint32_t k, double d) { record(k, d, Resolution::Camera); });
      seconds_per_camera = watch.seconds() / double(std::max<std::size_t>(half.size(), 1));
    }
    candidates.erase(
        std::remove_if(candidates.begin(), candidates.end(), [&](std::uint32_t k) { return taken[k]; }),
        candidates.end());
    return ViewBudget(seconds_per_camera);  // the second, warm half's
  }
};

}  // namespace

std::unique_ptr<DistanceMethod> make_cooperative(const GlMethodOptions& options) {
  return std::make_unique<Cooperative>(options);
}

}  // namespace roving
