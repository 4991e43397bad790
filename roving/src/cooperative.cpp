// The cooperative method (paper Section 4.3): viewpoint sampling, then surface roving for the
// samples no view accepted (occluded, or beyond the threshold).
#include "gl_passes.h"
#include "roving/gl_methods.h"
#include "roving/stopwatch.h"

namespace roving {
namespace {

class Cooperative final : public GlMethod {
 public:
  using GlMethod::GlMethod;
  std::string name() const override { return "cooperative"; }

  DistanceResult measure(const SampleSet& samples, const DistanceOptions& options) override {
    GlReport report = start(samples, options);
    const Stopwatch watch;
    DistanceResult result;
    result.signed_distance.assign(samples.size(), 0.0);
    result.hit.assign(samples.size(), 0);
    const auto viewed = view_sample(scene_, samples, options.max_error, options_, report);
    std::vector<std::uint32_t> rejected;
    for (std::uint32_t k = 0; k < samples.size(); ++k) {
      if (viewed[k]) {
        result.hit[k] = 1;
        result.signed_distance[k] = *viewed[k];
        report.resolved_by[k] = Resolution::View;
      } else {
        rejected.push_back(k);
      }
    }
    const auto roved = rove(scene_, samples, rejected, options.max_error, report);
    for (std::size_t i = 0; i < rejected.size(); ++i) {
      if (!roved[i]) continue;
      const std::uint32_t k = rejected[i];
      result.hit[k] = 1;
      result.signed_distance[k] = *roved[i];
      report.resolved_by[k] = Resolution::Camera;
    }
    result.query_seconds = watch.seconds();
    result.gl = std::move(report);
    return result;
  }
};

}  // namespace

std::unique_ptr<DistanceMethod> make_cooperative(const GlMethodOptions& options) {
  return std::make_unique<Cooperative>(options);
}

}  // namespace roving
