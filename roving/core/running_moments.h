// Running mean and sum of squared deviations (Welford 1962): no cancellation when the spread is
// small against the mean, and exactly 0 for equal values.
#pragma once

#include <cmath>

namespace roving {

struct RunningMoments {
  double count = 0, mean = 0, squared_deviations = 0;
  void add(double x) {
    count += 1;
    const double delta = x - mean;
    mean += delta / count;
    squared_deviations += delta * (x - mean);
  }
  // Of the values themselves (N in the denominator, as the paper's STD).
  double standard_deviation() const { return count > 0 ? std::sqrt(squared_deviations / count) : 0.0; }
  // Of their mean, as an estimate from independent samples (N - 1 in the variance).
  double standard_error() const { return count > 1 ? std::sqrt(squared_deviations / (count - 1) / count) : 0.0; }
};

}  // namespace roving
