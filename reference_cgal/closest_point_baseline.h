// Internal: the shared measuring loop of the closest-point baselines (nearest vertex / nearest
// point of the triangles); each baseline supplies only its nearest-point search.
#pragma once

#include <string>

#include "roving/core/distance_method.h"
#include "roving/core/error.h"
#include "roving/core/geometry.h"
#include "roving/core/stopwatch.h"

namespace roving {

class ClosestPointBaseline : public DistanceMethod {
 public:
  std::vector<Semantics> supported_semantics() const override { return {Semantics::Closest}; }

  DistanceResult measure(const SampleSet& samples, const DistanceOptions& options) override {
    if (!built_) throw Error(name() + ": measure() called before build()");
    validate_options(*this, options);
    // A nearest point always exists: every sample is a hit.
    return measure_each(samples.size(), [&](std::size_t k) {
      const Vec3& x = samples.positions[k];
      return std::optional<double>(signed_offset(x, samples.normals[k], nearest(x)));
    }, progress_);
  }

 protected:
  virtual Vec3 nearest(const Vec3& x) const = 0;
  bool built_ = false;
};

// The AABB-tree closest-point method under the baseline's name (cgal_reference.cpp).
std::unique_ptr<DistanceMethod> make_accelerated_vertex_to_plane();

}  // namespace roving
