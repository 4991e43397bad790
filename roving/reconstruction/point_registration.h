// Open3D 0.16's registration of two point clouds (pipelines/registration), as Tanks and Temples'
// run.py refines a reconstruction's alignment with it: a transformation is judged by each source
// point's nearest target point closer than a distance (fitness: the share that has one;
// inlier RMSE: the root mean square of their distances), and point-to-point ICP with scale
// repeats Umeyama's similarity on those pairs until the fitness and the RMSE stop changing.
// Every pair is listed in the source points' order, as Open3D lists them on one thread, and summed
// in blocks added in order (the same bits on any number of cores); Open3D's OpenMP threads merge
// their pairs in any order, which moves a sum's last bits and nothing else.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <utility>
#include <vector>

#include "roving/core/triangle_mesh.h"
#include "roving/reconstruction/point_tree.h"

namespace roving {

// (source index, target index) pairs.
using PointPairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

struct PointRegistration {
  Eigen::Matrix4d transformation = Eigen::Matrix4d::Identity();
  double fitness = 0;      // the share of source points with a target point closer than the distance
  double inlier_rmse = 0;  // the root mean square of those distances (0 where none)
  int iterations = 0;      // ICP's updates
  PointPairs pairs;        // each such source point and its nearest target point
  // Open3D's IsBetterRANSACThan: a higher fitness, or the same with a lower RMSE.
  bool better_than(const PointRegistration& other) const {
    return fitness > other.fitness || (fitness == other.fitness && inlier_rmse < other.inlier_rmse);
  }
};

// `source` (already moved by `transformation`, which the result records) against the points of
// `target`: each source point's nearest target point, kept where its squared distance is below
// max_distance^2 (Open3D's SearchHybrid with one neighbour).
PointRegistration evaluate_registration(const std::vector<Vec3>& source, const PointTree& target, double max_distance,
                                        const Eigen::Matrix4d& transformation);

// The similarity (rotation, scale, shift) that takes the pairs' source points closest to their
// target points in the least-squares sense: Umeyama's, as Eigen's umeyama with scaling computes it
// for Open3D's TransformationEstimationPointToPoint(with_scaling=True). Up to 65,536 pairs by that
// very call on the same matrices (Open3D's bits); above, its sums taken in blocks on every core and
// added in order (its last bits). The identity for no pair.
Eigen::Matrix4d similarity_of_pairs(const std::vector<Vec3>& source, const std::vector<Vec3>& target,
                                    const PointPairs& pairs);

struct IcpCriteria {  // Open3D's ICPConvergenceCriteria and its defaults
  double relative_fitness = 1e-6;
  double relative_rmse = 1e-6;
  int max_iterations = 30;
};

// Open3D's registration_icp with TransformationEstimationPointToPoint(True), from the identity:
// evaluate, then up to max_iterations times move the source by the similarity of its pairs and
// evaluate again, stopping once both the fitness and the RMSE changed by less than their criteria.
// The result's transformation is the product of the updates. Throws roving::Error for a
// max_distance that is not finite and > 0, or a target with no point.
PointRegistration icp_point_to_point(std::vector<Vec3> source, const PointTree& target, double max_distance,
                                     const IcpCriteria& criteria = {});

}  // namespace roving
