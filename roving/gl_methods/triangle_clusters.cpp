// Morton order of the triangles' centroids (10 bits per axis over the mesh's box), cut into
// runs of kSize, and the boxes of each run and each triangle.
#include "roving/gl_methods/triangle_clusters.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "roving/core/geometry.h"

namespace roving {
namespace {

// The box with its centre rounded to float and its half-size rounded up from the distance to
// that centre, so that the float box still holds every corner.
TriangleClusters::Box float_box(const BoundingBox& bounds, const Vec3& origin) {
  TriangleClusters::Box box;
  for (int axis = 0; axis < 3; ++axis) {
    const double low = bounds.min[axis] - origin[axis], high = bounds.max[axis] - origin[axis];
    box.centre[axis] = static_cast<float>(0.5 * (low + high));
    const double reach = std::max(high - box.centre[axis], box.centre[axis] - low);
    box.half_size[axis] = std::nextafter(static_cast<float>(reach), INFINITY);
  }
  return box;
}

}  // namespace

TriangleClusters::TriangleClusters(const TriangleMesh& mesh)
    : origin_(mesh.bounding_box().centre()), positions_(&mesh.positions()) {
  const auto& triangles = mesh.triangles();
  const auto& positions = mesh.positions();
  const BoundingBox& box = mesh.bounding_box();
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(triangles.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t t = range.begin(); t != range.end(); ++t) {
                        keyed[t] = {morton_code(mesh.centroid(t), box), static_cast<std::uint32_t>(t)};
                      }
                    });
  tbb::parallel_sort(keyed.begin(), keyed.end());
  corners_.resize(3 * keyed.size());
  boxes_.resize(keyed.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, keyed.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        const Triangle& corners = triangles[keyed[i].second];
                        BoundingBox bounds;
                        for (int k = 0; k < 3; ++k) {
                          corners_[3 * i + k] = static_cast<std::uint32_t>(corners[k]);
                          bounds.extend(positions[corners[k]]);
                        }
                        boxes_[i] = float_box(bounds, origin_);
                      }
                    });

  const std::size_t clusters = (boxes_.size() + kSize - 1) / kSize;
  cluster_boxes_.resize(clusters);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, clusters, 256),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t c = range.begin(); c != range.end(); ++c) {
                        BoundingBox bounds;
                        for (std::size_t k = 0; k < 3 * size(c); ++k) bounds.extend(positions[corners(c)[k]]);
                        cluster_boxes_[c] = float_box(bounds, origin_);
                      }
                    });
}

}  // namespace roving
