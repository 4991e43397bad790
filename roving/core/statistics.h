// Statistics of per-sample distances (the paper's SiAD, USiAD, STD, and what Metro users expect).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "roving/core/running_moments.h"

namespace roving {

struct Histogram {
  double low = 0, high = 0;          // range of signed d covered by the bins
  std::vector<std::size_t> counts;   // equal-width bins over [low, high]
  std::size_t below = 0, above = 0;  // hits outside the range
};

struct Statistics {
  std::size_t sample_count = 0;
  std::size_t hit_count = 0;
  std::size_t no_hit_count = 0;
  double no_hit_fraction = 0;
  // Plain means over all samples (eq. 2); a no-hit counts as d = +h (the paper's MAX_ERROR).
  double siad = 0;          // mean signed d
  double usiad = 0;         // mean |d|
  double std_signed = 0;    // standard deviation of signed d (the paper's STD)
  double std_unsigned = 0;  // standard deviation of |d|
  double rms = 0;
  // Extremes over the hits alone: a no-hit is counted in no_hit_count, never folded in as h.
  double max_abs = 0;     // max |d| (0 when nothing was hit)
  double min_signed = 0;  // most negative signed d
  double max_signed = 0;  // most positive signed d
  // Area-weighted means (eq. 1) with the same no-hit rule.
  double siad_area = 0;
  double usiad_area = 0;
  double rms_area = 0;
  // Over the hits alone (no MAX_ERROR substitution): what a no-hit would otherwise hide.
  double siad_hits = 0;
  double usiad_hits = 0;
  // Percentiles of |d| over all samples, a no-hit as h (nearest-rank).
  double p50 = 0, p90 = 0, p95 = 0, p99 = 0;
  Histogram histogram;  // of signed d over the hits, [-h, h]
};

// compute_statistics fed one sample at a time, in sample order: the same sums in the same order, so
// a run measured a chunk at a time gets the figures of the whole run bit for bit. It keeps |d|
// per sample (8 bytes, for the exact percentiles) and nothing else per sample.
class StatisticsAccumulator {
 public:
  // `max_error` = h (> 0 and finite; throws roving::Error otherwise). `expected` reserves |d|'s room.
  explicit StatisticsAccumulator(double max_error, std::size_t histogram_bins = 64, std::size_t expected = 0);
  // A sample's signed d (read only where `hit`) and the area it stands for.
  void add(double signed_distance, bool hit, double weight);
  std::size_t count() const { return magnitudes_.size(); }
  // The statistics of every sample added; throws roving::Error when there is none.
  Statistics finish();
  // The k-th smallest |d| (from 0) among the hits, read from the |d| kept for the percentiles (where
  // each no-hit stands as h), so that a caller needs no array of the hits' own; throws roving::Error
  // where k is not below the hit count. Reorders what is kept: call it after finish().
  double hit_magnitude(std::size_t k);

 private:
  double max_error_, bin_width_;
  Statistics s_;
  std::vector<double> magnitudes_;
  // Kahan-free but in double with per-term magnitudes ~h: relative error ~ n * 1e-16, negligible.
  double sum_ = 0, sum_abs_ = 0, sum_sq_ = 0;
  // Variances by Welford's update: no cancellation (E[d^2] - E[d]^2 lost all digits when the
  // spread is small against the mean), and exactly 0 for equal values.
  RunningMoments signed_spread_, unsigned_spread_;
  double w_sum_ = 0, w_d_ = 0, w_abs_ = 0, w_sq_ = 0;
  double hit_sum_ = 0, hit_abs_ = 0;
};

// `signed_distance` and `hit` per sample, `weights` per sample (area, may be empty for uniform),
// `max_error` = h (> 0). Throws roving::Error on size mismatch or an empty input.
Statistics compute_statistics(const std::vector<double>& signed_distance,
                              const std::vector<std::uint8_t>& hit, const std::vector<double>& weights,
                              double max_error, std::size_t histogram_bins = 64);

}  // namespace roving
