// Sampling error of the surface means: confidence intervals for SiAD, USiAD and RMS when the
// samples are drawn at random, uniformly by area (--samples area:N).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "roving/core/running_moments.h"

namespace roving {

struct MeanInterval {
  double estimate = 0;        // the sample mean (for RMS: the root of the mean square)
  double standard_error = 0;  // of the mean (for RMS: of the mean square)
  double lower = 0, upper = 0;
};

struct SamplingIntervals {
  double level = 0.95;
  MeanInterval siad, usiad, rms;
};

// With N samples drawn independently and uniformly by area, the sample mean of d (of |d|, of d^2)
// is an unbiased estimator of its surface mean, the paper's eq. 1, with standard error s / sqrt(N)
// (s the sample standard deviation, N - 1 in its denominator). The 95% intervals are the normal
// approximation, mean +- 1.96 standard errors; RMS's is the root of its mean square's interval
// (clamped at 0). A no-hit counts as d = +max_error, as in the statistics. Throws roving::Error on
// fewer than 2 samples or a size mismatch.
SamplingIntervals sampling_intervals(const std::vector<double>& signed_distance, const std::vector<std::uint8_t>& hit,
                                     double max_error);

// The same figures gathered a sample at a time, for callers that fold samples in rather than hold
// them (a merge reading shards' parts in order): bit for bit sampling_intervals' in the same order.
class IntervalsAccumulator {
 public:
  explicit IntervalsAccumulator(double max_error) : max_error_(max_error) {}
  void add(double signed_distance, bool hit);
  std::size_t count() const { return static_cast<std::size_t>(d_.count); }
  // Throws roving::Error on fewer than 2 samples.
  SamplingIntervals finish() const;

 private:
  double max_error_;
  RunningMoments d_, magnitude_, square_;
};

// The z of a two-sided 95% normal interval.
constexpr double kZ95 = 1.959963984540054;

}  // namespace roving
