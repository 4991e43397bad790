// Morton order of the triangles' centroids (10 bits per axis over the mesh's box), cut into
// runs of kSize, each run's bounding sphere (its vertices' box centre, padded radius) and each
// triangle's box.
#include "roving/gl_methods/triangle_clusters.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace roving {
namespace {

// The bits of v spread to every third position (Morton code of one axis).
std::uint64_t spread_bits(std::uint32_t v) {
  std::uint64_t x = v & 0x3ff;
  x = (x | (x << 16)) & 0x30000ff;
  x = (x | (x << 8)) & 0x300f00f;
  x = (x | (x << 4)) & 0x30c30c3;
  x = (x | (x << 2)) & 0x9249249;
  return x;
}

// The triangle's box with its centre rounded to float and its half-size rounded up from the
// distance to that centre, so that the float box still holds every corner.
TriangleClusters::Box box_of(const std::vector<Vec3>& positions, const Triangle& corners) {
  BoundingBox bounds;
  for (int corner : corners) bounds.extend(positions[corner]);
  TriangleClusters::Box box;
  for (int axis = 0; axis < 3; ++axis) {
    box.centre[axis] = static_cast<float>(bounds.centre()[axis]);
    const double reach = std::max(bounds.max[axis] - box.centre[axis], box.centre[axis] - bounds.min[axis]);
    box.half_size[axis] = std::nextafter(static_cast<float>(reach), INFINITY);
  }
  return box;
}

}  // namespace

TriangleClusters::TriangleClusters(const TriangleMesh& mesh) {
  const auto& triangles = mesh.triangles();
  const auto& positions = mesh.positions();
  const BoundingBox& box = mesh.bounding_box();
  const Vec3 scale = (1023.0 / box.size().array().max(1e-300)).matrix();
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(triangles.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t t = range.begin(); t != range.end(); ++t) {
                        const Vec3 cell = (mesh.centroid(t) - box.min).cwiseProduct(scale);
                        std::uint64_t code = 0;
                        for (int axis = 0; axis < 3; ++axis) {
                          code |= spread_bits(static_cast<std::uint32_t>(std::clamp(cell[axis], 0.0, 1023.0)))
                                  << axis;
                        }
                        keyed[t] = {code, static_cast<std::uint32_t>(t)};
                      }
                    });
  tbb::parallel_sort(keyed.begin(), keyed.end());
  order_.resize(keyed.size());
  boxes_.resize(keyed.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, keyed.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        order_[i] = keyed[i].second;
                        boxes_[i] = box_of(positions, triangles[order_[i]]);
                      }
                    });

  const std::size_t clusters = (order_.size() + kSize - 1) / kSize;
  centres_.resize(clusters);
  radii_.resize(clusters);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, clusters, 256),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t c = range.begin(); c != range.end(); ++c) {
                        BoundingBox bounds;
                        for (const std::uint32_t* t = begin(c); t != end(c); ++t) {
                          for (int corner : triangles[*t]) bounds.extend(positions[corner]);
                        }
                        double radius = 0;
                        for (const std::uint32_t* t = begin(c); t != end(c); ++t) {
                          for (int corner : triangles[*t])
                            radius = std::max(radius, (positions[corner] - bounds.centre()).norm());
                        }
                        centres_[c] = bounds.centre();
                        radii_[c] = radius * (1 + 1e-9);  // rounding can only widen it
                      }
                    });
}

}  // namespace roving
