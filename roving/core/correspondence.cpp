// Each sample's point on TEST and its barycentric coordinates.
#include "roving/core/correspondence.h"

#include <tbb/parallel_for.h>

#include <limits>

#include "roving/core/colour.h"
#include "roving/core/geometry.h"

namespace roving {

Correspondences correspondences(const SampleSet& samples, const TriangleMesh& test, const DistanceResult& result,
                                Semantics semantics) {
  const Vec3 none = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  Correspondences out;
  out.points.assign(samples.size(), none);
  out.barycentric.assign(samples.size(), none);
  const bool faces = result.hit_face.size() == samples.size();
  const auto& p = test.positions();
  tbb::parallel_for(std::size_t(0), samples.size(), [&](std::size_t k) {
    if (!result.hit[k]) return;
    const Vec3 at =
        correspondence_point(samples.positions[k], samples.normals[k], result.signed_distance[k], semantics);
    if (!faces) {
      // Without the face only the normal line's crossing is known; a closest point is not.
      if (semantics != Semantics::Closest) out.points[k] = at;
      return;
    }
    const Triangle& t = test.triangles()[result.hit_face[k]];
    const TrianglePoint on_face = closest_on_triangle(at, p[t[0]], p[t[1]], p[t[2]]);
    out.points[k] = on_face.point;
    out.barycentric[k] = on_face.weights;
  });
  return out;
}

}  // namespace roving
