// Point-cloud normal estimation with CGAL's Point_set_processing_3.
#include "roving/representations/point_normals.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/mst_orient_normals.h>
#include <CGAL/pca_estimate_normals.h>
#include <CGAL/property_map.h>
#include <fmt/format.h>

#include "roving/core/error.h"

namespace roving {

std::vector<Vec3> estimate_normals(const std::vector<Vec3>& points, int k) {
  if (points.size() <= static_cast<std::size_t>(k)) {
    throw Error(fmt::format("normal estimation: expected more than {} points, found {}", k, points.size()));
  }
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  // Each point carries its input index: mst_orient_normals reorders the range.
  using Entry = std::tuple<Kernel::Point_3, Kernel::Vector_3, std::size_t>;
  std::vector<Entry> cloud;
  cloud.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    cloud.emplace_back(Kernel::Point_3(points[i].x(), points[i].y(), points[i].z()),
                       Kernel::Vector_3(0, 0, 0), i);
  }
  const auto parameters = CGAL::parameters::point_map(CGAL::Nth_of_tuple_property_map<0, Entry>())
                              .normal_map(CGAL::Nth_of_tuple_property_map<1, Entry>());
  CGAL::pca_estimate_normals<CGAL::Parallel_if_available_tag>(cloud, k, parameters);
  // Points it cannot orient (other components) keep their PCA sign.
  CGAL::mst_orient_normals(cloud, k, parameters);
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& p : points) centroid += p;
  centroid /= double(points.size());
  std::vector<Vec3> normals(points.size());
  std::size_t outward = 0;
  for (const auto& [point, normal, index] : cloud) {
    normals[index] = Vec3(normal.x(), normal.y(), normal.z()).normalized();
    outward += normals[index].dot(points[index] - centroid) > 0;
  }
  if (2 * outward < points.size()) {
    for (Vec3& n : normals) n = -n;
  }
  return normals;
}

}  // namespace roving
