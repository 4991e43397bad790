// MPEG's D1 and D2 of the surfaces themselves, beside the sampled figures mmetric reports: every
// point of one surface against the other surface (not the other's samples), from a closest-point
// measurement. D1: the area-weighted mean squared closest distance; D2: the same of its component
// along the normal of the other surface at the closest point (mmetric's D2 takes B's own normals).
// Each with its 95% interval where the samples are area-uniform (area:N), and the certified
// Hausdorff interval, squared, where bounded (it bounds D2's largest value too: |e| <= d). The
// PSNRs use the sampled figure's peak, so the two read side by side.
#pragma once

#include <cstddef>
#include <optional>

#include "roving/core/confidence.h"
#include "roving/core/correspondence.h"
#include "roving/core/distance_method.h"
#include "roving/core/sample_set.h"
#include "roving/core/statistics.h"

namespace roving {

struct Interval {
  double lower = 0, upper = 0;
};

struct SurfaceFigures {
  std::size_t samples = 0, no_hits = 0;     // a no-hit counts at h (a lower bound there)
  double d1_mse = 0;                        // area-weighted mean of d^2, model units squared
  std::optional<Interval> d1_mse_interval;  // 95%, area-uniform samples only
  double d2_mse = 0;                        // area-weighted mean of ((x - c) . n_c)^2; NaN: no faces
  std::optional<Interval> d2_mse_interval;  // 95%, area-uniform samples only
  std::optional<Interval> hausdorff;        // certified, squared
};

// One direction's D1 from its closest-semantics statistics, intervals (area:N) and certified
// Hausdorff interval (unsquared; null where not bounded), and its D2 from each sample's closest
// point on `to` and the face it lies on (result.hit_face); `max_error` is h, a no-hit's value.
SurfaceFigures surface_figures(const SampleSet& samples, const DistanceResult& result,
                               const Correspondences& correspondences, const TriangleMesh& to,
                               const Statistics& statistics, const SamplingIntervals* intervals,
                               std::optional<Interval> hausdorff, double max_error);

// The worse of two directions, as MPEG's symmetric figures take it (the larger MSE, interval ends
// and Hausdorff bounds taken end by end).
SurfaceFigures worse(const SurfaceFigures& a, const SurfaceFigures& b);

}  // namespace roving
