// Agreement between methods and the GL methods' derived tolerances.
#include "roving/gl_methods/agreement.h"

#include <algorithm>
#include <cmath>

#include "roving/gl_methods/gl_methods.h"

namespace roving {

Agreement agreement(const DistanceResult& reference, const DistanceResult& result, double tolerance) {
  Agreement a;
  a.samples = reference.hit.size();
  for (std::size_t k = 0; k < a.samples; ++k) {
    a.same_flag += reference.hit[k] == result.hit[k];
    if (reference.hit[k] && result.hit[k]) {
      ++a.common_hits;
      a.close += std::abs(reference.signed_distance[k] - result.signed_distance[k]) <= tolerance;
    }
  }
  return a;
}

double roving_tolerance(const GlReport& gl) {
  return 8 * gl.camera_depth_step + 10 * gl.camera_half_width / 128;
}

double view_tolerance(const GlReport& gl, double alpha, double d) {
  const double tilt = 30 * M_PI / 180;
  return gl.view_pixel_size / std::sqrt(2.0) * std::tan(alpha + tilt) +
         std::abs(d) * std::tan(alpha) * std::tan(tilt) + 16 * gl.view_depth_step;
}

ViewAgreement view_agreement(const DistanceResult& reference, const DistanceResult& result,
                             const SampleSet& samples, const GlReport& gl) {
  const ViewGrid grid(gl.axis_views, gl.views_h, gl.views_v);
  ViewAgreement v;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    if (gl.resolved_by[k] != Resolution::View) continue;
    ++v.resolved;
    if (!reference.hit[k]) continue;
    const Vec3& n = samples.normals[k];
    const double best = grid.directions[grid.nearest(n)].dot(n);
    const double alpha = std::acos(std::clamp(best, -1.0, 1.0));
    v.within += std::abs(reference.signed_distance[k] - result.signed_distance[k]) <=
                view_tolerance(gl, alpha, reference.signed_distance[k]);
  }
  return v;
}

}  // namespace roving
