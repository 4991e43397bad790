// The nearest of a set of points to each of another's: a k-d tree (nanoflann, Debian's
// libnanoflann-dev) over points that outlive it, searched exactly, in parallel. The protocols that
// compare point clouds point to point (DTU's, Tanks and Temples') measure with it.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "roving/core/triangle_mesh.h"

namespace roving {

class PointTree {
 public:
  // Where the tree keeps its points: `points` itself (the protocols' registrations, whose ties must
  // break as Open3D's tree over the same points breaks them), or a copy in spatial order
  // (spatial_order.h), whose searches run from cache where `points` come in a file's random order
  // (DTU's ground truth: the nearest distances are the same, a tie's index may differ).
  enum class Layout { AsGiven, InSpace };

  explicit PointTree(const std::vector<Vec3>& points, Layout layout = Layout::AsGiven);  // none built over no points
  ~PointTree();
  PointTree(const PointTree&) = delete;
  PointTree& operator=(const PointTree&) = delete;

  const std::vector<Vec3>& points() const { return points_; }
  // The distance from each of `from` to its nearest point here, as sqrt of the squared distance
  // summed over x, y, z in that order (Open3D's and scikit-learn's figure to the last bit); NaN
  // for every point when the tree holds none. Searched in `from`'s spatial order, each answer
  // put at its point's place.
  std::vector<double> nearest_distances(const std::vector<Vec3>& from) const;
  // The index of each of `from`'s nearest point here and the squared distance to it (summed as
  // above); the tree must hold points.
  void nearest(const std::vector<Vec3>& from, std::vector<std::uint32_t>& index, std::vector<double>& squared) const;
  // The nearest point to `p` (its index and squared distance, as above) and the squared distance
  // to the second nearest (infinity where the tree holds one point); the tree must hold points.
  void nearest_two(const Vec3& p, std::uint32_t& index, double& squared, double& second_squared) const;

 private:
  struct Index;
  const std::vector<Vec3>& points_;
  std::vector<Vec3> ordered_;          // Layout::InSpace: the points in spatial order
  std::vector<std::uint32_t> original_;  // and the index in `points_` of each
  std::unique_ptr<Index> index_;
};

}  // namespace roving
