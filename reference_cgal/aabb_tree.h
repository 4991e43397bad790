// What the CGAL-based code shares: the AABB tree of Epick triangles and point conversions.
// Private to reference_cgal (included by its .cpp files only).
#pragma once

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <vector>

#include "roving/core/triangle_mesh.h"

namespace roving::aabb {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using TriangleList = std::vector<Kernel::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleList::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

inline Point to_point(const Vec3& v) {
  return Point(v.x(), v.y(), v.z());
}
inline Vec3 to_vec(const Point& p) {
  return Vec3(p.x(), p.y(), p.z());
}

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
