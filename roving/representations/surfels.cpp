// Surfels: per-point radii from a CGAL kd-tree (k nearest neighbours, queried in parallel), then
// a triangle fan per point in its tangent plane.
#include "roving/representations/surfels.h"

#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/property_map.h>
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <boost/iterator/counting_iterator.hpp>
#include <cmath>
#include <limits>

#include "roving/core/error.h"

namespace roving {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using PointMap = CGAL::Pointer_property_map<Point>::type;
using Traits = CGAL::Search_traits_adapter<std::size_t, PointMap, CGAL::Search_traits_3<Kernel>>;
using Search = CGAL::Orthogonal_k_neighbor_search<Traits>;

std::string at(const Vec3& p) {
  return fmt::format("({}, {}, {})", p.x(), p.y(), p.z());
}

void validate(const PointCloud& cloud, const std::string& path, const SurfelRule& rule) {
  const std::size_t n = cloud.positions.size();
  if (n <= static_cast<std::size_t>(rule.neighbours)) {
    throw Error(
        fmt::format("{}: a point cloud drawn as surfels needs more than {} points (each disk reaches its "
                    "{}th nearest neighbour); found {}",
                    path, rule.neighbours, rule.neighbours, n));
  }
  if (cloud.normals.size() != n) {
    throw Error(fmt::format("{}: expected a normal per point for its surfels, found {} normals for {} points",
                            path, cloud.normals.size(), n));
  }
  for (std::size_t k = 0; k < n; ++k) {
    if (!cloud.positions[k].allFinite()) {
      throw Error(
          fmt::format("{}: point {} has a non-finite coordinate {}", path, k, at(cloud.positions[k])));
    }
    const double length = cloud.normals[k].norm();
    if (!std::isfinite(length) || length < 1e-12) {
      throw Error(
          fmt::format("{}: point {} has a zero or non-finite normal {}; a surfel needs its tangent plane",
                      path, k, at(cloud.normals[k])));
    }
  }
}

}  // namespace

SurfelSurface make_surfels(const PointCloud& cloud, const std::string& path, const SurfelRule& rule) {
  validate(cloud, path, rule);
  const std::size_t n = cloud.positions.size();
  std::vector<Point> points;
  points.reserve(n);
  for (const Vec3& p : cloud.positions) points.emplace_back(p.x(), p.y(), p.z());
  const PointMap point_map(points.data());
  Search::Tree tree(boost::counting_iterator<std::size_t>(0), boost::counting_iterator<std::size_t>(n),
                    Search::Tree::Splitter(), Traits(point_map));
  tree.build();  // before the parallel queries
  const Search::Distance distance(point_map);

  // Radius: the distance to the k-th neighbour (the point itself comes first, at 0). A second
  // point at distance 0 is a duplicate.
  std::vector<double> radius(n);
  std::vector<std::size_t> duplicate_of(n, n);
  tbb::parallel_for(std::size_t{0}, n, [&](std::size_t k) {
    const Search search(tree, points[k], static_cast<unsigned>(rule.neighbours + 1), 0, true, distance);
    double farthest = 0;
    for (auto it = search.begin(); it != search.end(); ++it) {
      if (it->first != k && it->second == 0) duplicate_of[k] = std::min(duplicate_of[k], it->first);
      farthest = std::max(farthest, it->second);
    }
    radius[k] = std::sqrt(farthest);
  });
  for (std::size_t k = 0; k < n; ++k) {
    if (duplicate_of[k] < n) {
      throw Error(fmt::format(
          "{}: points {} and {} are both at {}; surfels need distinct points (remove the "
          "duplicates)",
          path, std::min(k, duplicate_of[k]), std::max(k, duplicate_of[k]), at(cloud.positions[k])));
    }
  }

  if (n > static_cast<std::size_t>(std::numeric_limits<int>::max() / (rule.fan_sides + 1))) {
    throw Error(fmt::format("{}: {} points make more surfel vertices than a mesh can index", path, n));
  }
  // Each fan: the point, then the polygon's corners at r / cos(pi / sides), so that the polygon's
  // edges touch the disk of radius r from outside.
  const int sides = rule.fan_sides;
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  positions.reserve(n * (sides + 1));
  triangles.reserve(n * sides);
  const double stretch = 1 / std::cos(M_PI / sides);
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3 normal = cloud.normals[k].normalized();
    const Vec3 helper = std::abs(normal.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
    const Vec3 u = normal.cross(helper).normalized(), v = normal.cross(u);  // u x v = normal
    const int centre = static_cast<int>(positions.size());
    positions.push_back(cloud.positions[k]);
    for (int j = 0; j < sides; ++j) {
      const double angle = 2 * M_PI * j / sides;
      positions.push_back(cloud.positions[k] +
                          radius[k] * stretch * (std::cos(angle) * u + std::sin(angle) * v));
      triangles.push_back({centre, centre + 1 + j, centre + 1 + (j + 1) % sides});
    }
  }
  SurfelSurface surfels{TriangleMesh(std::move(positions), std::move(triangles)), rule, 0, 0, 0};
  if (!cloud.colours.empty()) {  // each disk in its point's colour
    std::vector<Colour> colours;
    colours.reserve(n * (sides + 1));
    for (const Colour& c : cloud.colours) colours.insert(colours.end(), sides + 1, c);
    surfels.mesh.set_vertex_colours(std::move(colours), path);
  }
  std::vector<double> sorted = radius;
  std::nth_element(sorted.begin(), sorted.begin() + n / 2, sorted.end());
  surfels.median_radius = sorted[n / 2];
  const auto [low, high] = std::minmax_element(radius.begin(), radius.end());
  surfels.min_radius = *low, surfels.max_radius = *high;
  return surfels;
}

}  // namespace roving
