// MPEG's D1 of the surfaces themselves, beside the sampled figure mmetric reports: every point of
// one surface against the other surface (not the other's samples), from a closest-point
// measurement: the area-weighted mean squared closest distance, with its 95% interval where the
// samples are area-uniform (area:N), and the certified Hausdorff interval, squared, where bounded.
// The PSNRs use the sampled figure's peak, so the two read side by side.
#pragma once

#include <cstddef>
#include <optional>

#include "roving/core/confidence.h"
#include "roving/core/statistics.h"

namespace roving {

struct Interval {
  double lower = 0, upper = 0;
};

struct SurfaceD1 {
  std::size_t samples = 0, no_hits = 0;  // a no-hit counts at h (a lower bound there)
  double mse = 0;                        // area-weighted mean of d^2, model units squared
  std::optional<Interval> mse_interval;  // 95%, area-uniform samples only
  std::optional<Interval> hausdorff;     // certified, squared
};

// One direction's figure from its closest-semantics statistics, intervals (area:N) and certified
// Hausdorff interval (unsquared; null where not bounded).
SurfaceD1 surface_d1(const Statistics& statistics, const SamplingIntervals* intervals,
                     std::optional<Interval> hausdorff);

// The worse of two directions, as MPEG's symmetric figures take it (the larger MSE, interval ends
// and Hausdorff bounds taken end by end).
SurfaceD1 worse(const SurfaceD1& a, const SurfaceD1& b);

}  // namespace roving
