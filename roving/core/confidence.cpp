// Normal-approximation confidence intervals of the surface means from area-uniform samples.
#include "roving/core/confidence.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "roving/core/error.h"
#include "roving/core/running_moments.h"

namespace roving {
namespace {

MeanInterval interval(const RunningMoments& m) {
  const double se = m.standard_error();
  return {m.mean, se, m.mean - kZ95 * se, m.mean + kZ95 * se};
}

}  // namespace

SamplingIntervals sampling_intervals(const std::vector<double>& signed_distance, const std::vector<std::uint8_t>& hit,
                                     double max_error) {
  if (hit.size() != signed_distance.size()) {
    throw Error(fmt::format("confidence intervals: expected a hit flag per sample, found {} for {} samples",
                            hit.size(), signed_distance.size()));
  }
  IntervalsAccumulator accumulator(max_error);
  for (std::size_t k = 0; k < signed_distance.size(); ++k) accumulator.add(signed_distance[k], hit[k]);
  return accumulator.finish();
}

void IntervalsAccumulator::add(double signed_distance, bool hit) {
  const double x = hit ? signed_distance : max_error_;
  d_.add(x);
  magnitude_.add(std::abs(x));
  square_.add(x * x);
}

SamplingIntervals IntervalsAccumulator::finish() const {
  if (count() < 2) {
    throw Error(fmt::format("confidence intervals: expected at least 2 samples, found {}", count()));
  }
  SamplingIntervals out;
  out.siad = interval(d_);
  out.usiad = interval(magnitude_);
  const MeanInterval q = interval(square_);
  out.rms = {std::sqrt(q.estimate), q.standard_error, std::sqrt(std::max(0.0, q.lower)), std::sqrt(q.upper)};
  return out;
}

}  // namespace roving
