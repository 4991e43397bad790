// CGAL's own AABB tree queries, without the shared rule (roving/core/raw_queries.h).
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>
#include <limits>

#include "roving/core/raw_queries.h"
#include "roving/reference_cgal/cgal_reference.h"

namespace roving {
namespace {

// The AABB tree of Epick triangles, as the reference builds it.

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using TriangleList = std::vector<Kernel::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleList::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Point to_point(const Vec3& v) {
  return Point(v.x(), v.y(), v.z());
}

double first_intersection(const Tree& tree, const Vec3& from, const Vec3& direction, double length) {
  const Kernel::Ray_3 ray(to_point(from), Kernel::Vector_3(direction.x(), direction.y(), direction.z()));
  const auto hit = tree.first_intersection(ray);
  if (!hit) return std::numeric_limits<double>::infinity();
  Point p;
  if (const Point* point = boost::get<Point>(&hit->first)) {
    p = *point;
  } else {
    const auto& segment = boost::get<Kernel::Segment_3>(hit->first);
    p = CGAL::has_smaller_distance_to_point(ray.source(), segment.source(), segment.target())
            ? segment.source()
            : segment.target();
  }
  const double t = std::sqrt(CGAL::to_double(CGAL::squared_distance(ray.source(), p)));
  return t <= length ? t : std::numeric_limits<double>::infinity();
}

}  // namespace

RawRun raw_cgal_queries(const TriangleMesh& test, const SampleSet& samples, Semantics semantics, double h) {
  RawRun run;
  const Stopwatch build;
  TriangleList triangles;
  triangles.reserve(test.triangle_count());
  const auto& p = test.positions();
  for (const Triangle& t : test.triangles())
    triangles.emplace_back(to_point(p[t[0]]), to_point(p[t[1]]), to_point(p[t[2]]));
  Tree tree(triangles.begin(), triangles.end());
  tree.build();
  // No accelerate_distance_queries(): CGAL makes its search tree at the first closest-point query
  // by default, inside the query time, as the exact reference does.
  run.build_seconds = build.seconds();
  const auto& x = samples.positions;
  const auto& n = samples.normals;
  switch (semantics) {
    case Semantics::FirstHit:
      time_raw_queries(run, samples.size(), [&](std::size_t k) {
        return raw_first_hit(first_intersection(tree, x[k] + h * n[k], -n[k], 2 * h), h);
      });
      break;
    case Semantics::Nearest:
      time_raw_queries(run, samples.size(), [&](std::size_t k) {
        return raw_nearest(first_intersection(tree, x[k], n[k], h), first_intersection(tree, x[k], -n[k], h));
      });
      break;
    case Semantics::Closest:
      time_raw_queries(run, samples.size(), [&](std::size_t k) {
        return std::sqrt(
            CGAL::to_double(CGAL::squared_distance(to_point(x[k]), tree.closest_point(to_point(x[k])))));
      });
      break;
  }
  return run;
}

}  // namespace roving
