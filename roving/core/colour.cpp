// Colour at a point of a triangle, and each sample's pair of colours.
#include "roving/core/colour.h"

#include <tbb/parallel_for.h>

#include <limits>

#include "roving/core/error.h"
#include "roving/core/geometry.h"

namespace roving {

Colour colour_on_face(const TriangleMesh& mesh, std::size_t face, const Vec3& point) {
  const Triangle& t = mesh.triangles()[face];
  const auto& p = mesh.positions();
  const Vec3 w = closest_on_triangle(point, p[t[0]], p[t[1]], p[t[2]]).weights;
  const auto& c = mesh.vertex_colours();
  // In double, then rounded once: interpolating float colours in float drifted by 3e-5 of a step.
  const Eigen::Vector3d colour =
      w[0] * c[t[0]].cast<double>() + w[1] * c[t[1]].cast<double>() + w[2] * c[t[2]].cast<double>();
  return colour.cast<float>();
}

ColourPairs colour_pairs(const TriangleMesh& reference, const SampleSet& samples, const TriangleMesh& test,
                         const DistanceResult& result, Semantics semantics) {
  if (result.hit_face.size() != samples.size()) {
    throw Error("colour: the method gave no hit faces; colour needs the face each sample's line meets");
  }
  const bool vertex_samples = samples.kind == "vertices";
  ColourPairs pairs;
  pairs.reference.resize(samples.size());
  pairs.test.assign(samples.size(), Colour::Constant(std::numeric_limits<float>::quiet_NaN()));
  tbb::parallel_for(std::size_t(0), samples.size(), [&](std::size_t k) {
    const Vec3& x = samples.positions[k];
    pairs.reference[k] = vertex_samples ? reference.vertex_colours()[samples.elements[k]]
                                        : colour_on_face(reference, samples.elements[k], x);
    if (!result.hit[k]) return;
    const Vec3 at = correspondence_point(x, samples.normals[k], result.signed_distance[k], semantics);
    pairs.test[k] = colour_on_face(test, result.hit_face[k], at);
  });
  return pairs;
}

}  // namespace roving
