// Internal: the shared measuring loop of the closest-point baselines (nearest vertex / nearest
// point of the triangles); each baseline supplies only its nearest-point search.
#pragma once

#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "roving/distance_method.h"
#include "roving/error.h"
#include "roving/geometry.h"
#include "roving/stopwatch.h"

namespace roving {

class ClosestPointBaseline : public DistanceMethod {
 public:
  std::vector<Semantics> supported_semantics() const override { return {Semantics::Closest}; }

  DistanceResult measure(const SampleSet& samples, const DistanceOptions& options) override {
    if (!built_) throw Error(name() + ": measure() called before build()");
    validate_options(*this, options);
    const Stopwatch watch;
    DistanceResult result;
    result.signed_distance.assign(samples.size(), 0.0);
    result.hit.assign(samples.size(), 1);  // a nearest point always exists
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.size(), 16),
                      [&](const tbb::blocked_range<std::size_t>& range) {
      for (std::size_t k = range.begin(); k != range.end(); ++k) {
        const Vec3& x = samples.positions[k];
        result.signed_distance[k] = signed_offset(x, samples.normals[k], nearest(x));
      }
    });
    result.query_seconds = watch.seconds();
    return result;
  }

 protected:
  virtual Vec3 nearest(const Vec3& x) const = 0;
  bool built_ = false;
};

// The AABB-tree closest-point method under the baseline's name (cgal_reference.cpp).
std::unique_ptr<DistanceMethod> make_accelerated_vertex_to_plane();

}  // namespace roving
