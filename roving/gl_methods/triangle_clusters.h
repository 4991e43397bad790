// Internal: M_C's triangles in small spatially coherent clusters (Morton order of their
// centroids), each with a bounding box, so that a view can reject a whole cluster whose
// projected box touches no pixel it reads before looking at its triangles; each triangle's
// corners and box are stored in cluster order, so that the triangles are then decided, and the
// kept ones' corners copied, reading memory in sequence.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "roving/core/triangle_mesh.h"

namespace roving {

class TriangleClusters {
 public:
  static constexpr std::size_t kSize = 16;  // triangles per cluster (the last may hold fewer)

  // An axis-aligned box, relative to origin(), rounded outwards to float: the mesh's own
  // coordinates may be far from 0, where float would lose the box's size.
  struct Box {
    float centre[3], half_size[3];
  };

  // Keeps a reference to the mesh's positions: the mesh must outlive the clusters.
  explicit TriangleClusters(const TriangleMesh& mesh);

  // The mesh's box centre.
  const Vec3& origin() const { return origin_; }
  const SharedArray<Vec3>& positions() const { return *positions_; }
  std::size_t count() const { return cluster_boxes_.size(); }
  // How many triangles cluster c holds.
  std::size_t size(std::size_t c) const { return std::min(kSize, boxes_.size() - c * kSize); }
  // The corners (vertex indices, three a triangle) of cluster c's triangles.
  const std::uint32_t* corners(std::size_t c) const { return corners_.data() + 3 * c * kSize; }
  // The boxes of cluster c's triangles, in the same order.
  const Box* boxes(std::size_t c) const { return boxes_.data() + c * kSize; }
  // A box holding every vertex of cluster c's triangles.
  const Box& cluster_box(std::size_t c) const { return cluster_boxes_[c]; }

 private:
  Vec3 origin_;
  const SharedArray<Vec3>* positions_;
  std::vector<std::uint32_t> corners_;  // cluster by cluster
  std::vector<Box> boxes_;              // one per triangle of corners_
  std::vector<Box> cluster_boxes_;
};

}  // namespace roving
