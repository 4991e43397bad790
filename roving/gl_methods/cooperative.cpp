// The cooperative method (paper Section 4.3): viewpoint sampling, then surface roving for the
// samples no view accepted (occluded, or beyond the threshold).
#include "gl_passes.h"
#include "roving/gl_methods/gl_methods.h"

namespace roving {
namespace {

class Cooperative final : public GlMethod {
 public:
  using GlMethod::GlMethod;
  std::string name() const override { return "cooperative"; }

  void resolve(const SampleSet& samples, double max_error, GlReport& report, const Record& record) override {
    const auto viewed = view_sample(scene_, samples, max_error, options_, report, progress_);
    std::vector<std::uint32_t> rejected;
    for (std::uint32_t k = 0; k < samples.size(); ++k) {
      if (viewed[k]) {
        record(k, *viewed[k], Resolution::View);
      } else {
        rejected.push_back(k);
      }
    }
    const auto roved = rove(scene_, samples, rejected, max_error, report, progress_);
    for (std::size_t i = 0; i < rejected.size(); ++i) {
      if (roved[i]) record(rejected[i], *roved[i], Resolution::Camera);
    }
  }
};

}  // namespace

std::unique_ptr<DistanceMethod> make_cooperative(const GlMethodOptions& options) {
  return std::make_unique<Cooperative>(options);
}

}  // namespace roving
