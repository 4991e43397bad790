// Small exact-arithmetic-free geometric kernels shared by the references and baselines.
#pragma once

#include "roving/core/triangle_mesh.h"

namespace roving {

// Closest point to `p` on the closed triangle (a, b, c): Ericson, "Real-Time Collision Detection",
// section 5.1.5. Works for degenerate triangles (returns a point of the segment or the vertex).
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

// The same point with its barycentric weights (of a, b, c; non-negative, summing to 1), for
// what is interpolated over the triangle there (colour).
struct TrianglePoint {
  Vec3 point;
  Vec3 weights;
};
TrianglePoint closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

// Signed distance for closest-point measures: |c - x| with the sign of (c - x) . n, so that it is
// positive where the test surface lies outside the reference along its normal, as with the
// paper's d = h - t, and defined even where c lies on an edge or a vertex.
inline double signed_offset(const Vec3& x, const Vec3& n, const Vec3& c) {
  const Vec3 v = c - x;
  const double length = v.norm();
  return v.dot(n) < 0 ? -length : length;
}

}  // namespace roving
