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
  if (signed_distance.size() < 2 || hit.size() != signed_distance.size()) {
    throw Error(fmt::format("confidence intervals: expected at least 2 samples with a hit flag each, found {} and {}",
                            signed_distance.size(), hit.size()));
  }
  RunningMoments d, magnitude, square;
  for (std::size_t k = 0; k < signed_distance.size(); ++k) {
    const double x = hit[k] ? signed_distance[k] : max_error;
    d.add(x);
    magnitude.add(std::abs(x));
    square.add(x * x);
  }
  SamplingIntervals out;
  out.siad = interval(d);
  out.usiad = interval(magnitude);
  const MeanInterval q = interval(square);
  out.rms = {std::sqrt(q.estimate), q.standard_error, std::sqrt(std::max(0.0, q.lower)), std::sqrt(q.upper)};
  return out;
}

}  // namespace roving
