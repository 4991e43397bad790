// CGAL's own AABB tree queries, without the shared rule (roving/core/raw_queries.h).
#include <cmath>
#include <limits>

#include "aabb_tree.h"
#include "roving/core/raw_queries.h"
#include "roving/reference_cgal/cgal_reference.h"

namespace roving {
namespace {

using namespace aabb;

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
  const TriangleList triangles = triangles_of(test);
  Tree tree(triangles.begin(), triangles.end());
  tree.build();
  // No accelerate_distance_queries(): CGAL makes its search tree at the first closest-point query
  // by default, inside the query time, as the exact reference does.
  run.build_seconds = build.seconds();
  time_raw_queries(
      run, samples, semantics, h,
      [&](const Vec3& from, const Vec3& direction, double length) {
        return first_intersection(tree, from, direction, length);
      },
      [&](const Vec3& x) {
        return std::sqrt(
            CGAL::to_double(CGAL::squared_distance(to_point(x), tree.closest_point(to_point(x)))));
      });
  return run;
}

}  // namespace roving
