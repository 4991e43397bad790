// What the libraries under the exact references give on their own (Embree's triangle BVH and
// CGAL's AABB tree with their own queries, no shared rule): the limit the exact methods are
// measured against in roving-bench's throughput table. The queries themselves live beside each
// reference (raw_embree_queries, raw_cgal_queries).
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <vector>

#include "roving/core/distance_method.h"
#include "roving/core/sample_set.h"
#include "roving/core/stopwatch.h"

namespace roving {

// One raw run: d for each sample (NaN for a no-hit; closest: unsigned) and its seconds.
struct RawRun {
  std::vector<double> distance;
  double build_seconds = 0, query_seconds = 0;
};

// The raw run of `semantics` from a library's two queries, timed on all cores: cast(from,
// direction, length), the distance along a ray to the first triangle within `length` (infinity
// for none), and closest(x), the distance from x to the nearest point of the surface. First-hit
// casts one ray from x + h n along -n over 2h (d = h - t); nearest one each way from x over h
// and keeps the nearer.
template <class Cast, class Closest>
void time_raw_queries(RawRun& run, const SampleSet& samples, Semantics semantics, double h, const Cast& cast,
                      const Closest& closest) {
  constexpr double kNoHit = std::numeric_limits<double>::quiet_NaN();
  const auto& x = samples.positions;
  const auto& n = samples.normals;
  const auto answer = [&](std::size_t k) {
    if (semantics == Semantics::Closest) return closest(x[k]);
    if (semantics == Semantics::FirstHit) {
      const double t = cast(Vec3(x[k] + h * n[k]), Vec3(-n[k]), 2 * h);
      return std::isfinite(t) ? h - t : kNoHit;
    }
    const double along = cast(x[k], n[k], h), against = cast(x[k], Vec3(-n[k]), h);
    if (!std::isfinite(along) && !std::isfinite(against)) return kNoHit;
    return along <= against ? along : -against;
  };
  run.distance.resize(samples.size());
  const Stopwatch watch;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t k = r.begin(); k != r.end(); ++k) run.distance[k] = answer(k);
                    });
  run.query_seconds = watch.seconds();
}

}  // namespace roving
