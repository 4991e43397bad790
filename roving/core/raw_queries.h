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

#include "roving/core/stopwatch.h"

namespace roving {

// One raw run: d for each sample (NaN for a no-hit; closest: unsigned) and its seconds.
struct RawRun {
  std::vector<double> distance;
  double build_seconds = 0, query_seconds = 0;
};

// d from a first-hit ray's t (from x + h n along -n), or from the nearer of the two rays from x
// (t along n and along -n); infinity for a ray that found nothing.
inline double raw_first_hit(double t, double h) {
  return std::isfinite(t) ? h - t : std::numeric_limits<double>::quiet_NaN();
}
inline double raw_nearest(double along, double against) {
  if (!std::isfinite(along) && !std::isfinite(against)) return std::numeric_limits<double>::quiet_NaN();
  return along <= against ? along : -against;
}

// Fills run.distance with answer(k) on all cores and times it.
template <class Answer>
void time_raw_queries(RawRun& run, std::size_t count, const Answer& answer) {
  run.distance.resize(count);
  const Stopwatch watch;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 256),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t k = r.begin(); k != r.end(); ++k) run.distance[k] = answer(k);
                    });
  run.query_seconds = watch.seconds();
}

}  // namespace roving
