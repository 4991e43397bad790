// What the CGAL-based code shares: the AABB tree of Epick triangles and point conversions.
// Private to reference_cgal (included by its .cpp files only).
#pragma once

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <vector>

#include "roving/core/geometry.h"
#include "roving/core/triangle_mesh.h"

namespace roving::aabb {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;

inline Point to_point(const Vec3& v) {
  return Point(v.x(), v.y(), v.z());
}
inline Vec3 to_vec(const Point& p) {
  return Vec3(p.x(), p.y(), p.z());
}

// CGAL's kernel with one routine replaced: the closest point on a triangle. CGAL 5.5's own is
// wrong on triangles with two equal or three collinear corners (a sample 0.163 from (0,0,0),
// (0,0,0), (-1,-1,-1) was given a point 0.768 away) and on thin caps (3.5e-5 where the exact
// distance is 4.6e-11), and off by up to ~250 units in the last place on ordinary ones
// (tests/exact_oracle_test.cpp, against an exact rational oracle). So the tree keeps CGAL's search
// (its boxes, traversal and distance comparisons) and takes the point from the project's
// exact-deciding kernel (roving/core/geometry.h), within its stated bound on every triangle.
struct ClosestPointKernel : Kernel {
  struct Construct_projected_point_3 {
    template <class Object>
    Point operator()(const Object& object, const Point& p) const {
      return Kernel().construct_projected_point_3_object()(object, p);
    }
    Point operator()(const Kernel::Triangle_3& t, const Point& p) const {
      return to_point(closest_point_on_triangle(to_vec(p), to_vec(t[0]), to_vec(t[1]), to_vec(t[2])));
    }
  };
  Construct_projected_point_3 construct_projected_point_3_object() const { return {}; }
};

using TriangleList = std::vector<Kernel::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleList::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<ClosestPointKernel, Primitive>>;

// Every triangle of `mesh`, degenerate ones too, in its order: a primitive's offset is its face.
inline TriangleList triangles_of(const TriangleMesh& mesh) {
  TriangleList triangles;
  triangles.reserve(mesh.triangle_count());
  const auto& p = mesh.positions();
  for (const Triangle& t : mesh.triangles())
    triangles.emplace_back(to_point(p[t[0]]), to_point(p[t[1]]), to_point(p[t[2]]));
  return triangles;
}

}  // namespace roving::aabb
