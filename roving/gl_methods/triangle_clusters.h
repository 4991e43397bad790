// Internal: M_C's triangles in small spatially coherent clusters (Morton order of their
// centroids), each with a bounding sphere, so that a view can reject a whole cluster whose
// projected sphere touches no pixel it reads before looking at its triangles; each triangle's
// box is stored beside it, in cluster order, so that the triangles are then decided reading
// memory in sequence rather than gathering their vertices.
#pragma once

#include <cstdint>
#include <vector>

#include "roving/core/triangle_mesh.h"

namespace roving {

class TriangleClusters {
 public:
  static constexpr std::size_t kSize = 16;  // triangles per cluster (the last may hold fewer)

  // An axis-aligned box holding a triangle, rounded outwards to float.
  struct Box {
    float centre[3], half_size[3];
  };

  explicit TriangleClusters(const TriangleMesh& mesh);

  std::size_t count() const { return centres_.size(); }
  // The triangles of cluster c.
  const std::uint32_t* begin(std::size_t c) const { return order_.data() + c * kSize; }
  const std::uint32_t* end(std::size_t c) const {
    return order_.data() + std::min(order_.size(), (c + 1) * kSize);
  }
  // A sphere holding every vertex of cluster c's triangles.
  const Vec3& centre(std::size_t c) const { return centres_[c]; }
  double radius(std::size_t c) const { return radii_[c]; }
  // The boxes of cluster c's triangles, in the same order as begin(c).
  const Box* boxes(std::size_t c) const { return boxes_.data() + c * kSize; }

 private:
  std::vector<std::uint32_t> order_;  // triangle ids, cluster by cluster
  std::vector<Vec3> centres_;
  std::vector<double> radii_;
  std::vector<Box> boxes_;  // one per entry of order_
};

}  // namespace roving
