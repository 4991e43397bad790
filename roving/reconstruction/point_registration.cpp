#include "roving/reconstruction/point_registration.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <cmath>

#include "roving/core/error.h"
#include "roving/reconstruction/tanks_and_temples_protocol.h"

namespace roving {

PointRegistration evaluate_registration(const std::vector<Vec3>& source, const PointTree& target, double max_distance,
                                        const Eigen::Matrix4d& transformation) {
  PointRegistration result;
  result.transformation = transformation;
  std::vector<std::uint32_t> nearest;
  std::vector<double> squared;
  target.nearest(source, nearest, squared);
  const double limit = max_distance * max_distance;
  double error2 = 0;
  for (std::size_t i = 0; i < source.size(); ++i) {
    if (squared[i] < limit) {
      error2 += squared[i];
      result.pairs.emplace_back(static_cast<std::uint32_t>(i), nearest[i]);
    }
  }
  if (!result.pairs.empty()) {
    const double count = static_cast<double>(result.pairs.size());
    result.fitness = count / static_cast<double>(source.size());
    result.inlier_rmse = std::sqrt(error2 / count);
  }
  return result;
}

Eigen::Matrix4d similarity_of_pairs(const std::vector<Vec3>& source, const std::vector<Vec3>& target,
                                    const PointPairs& pairs) {
  if (pairs.empty()) return Eigen::Matrix4d::Identity();
  Eigen::MatrixXd from(3, pairs.size()), to(3, pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    from.col(static_cast<Eigen::Index>(k)) = source[pairs[k].first];
    to.col(static_cast<Eigen::Index>(k)) = target[pairs[k].second];
  }
  return Eigen::umeyama(from, to, true);
}

PointRegistration icp_point_to_point(std::vector<Vec3> source, const std::vector<Vec3>& target, double max_distance,
                                     const IcpCriteria& criteria) {
  if (!(std::isfinite(max_distance) && max_distance > 0)) {
    throw Error(fmt::format("ICP: the largest distance of a pair is {}; expected a length > 0", max_distance));
  }
  if (target.empty()) throw Error("ICP: the target has no point");
  const PointTree tree(target);
  Eigen::Matrix4d transformation = Eigen::Matrix4d::Identity();
  PointRegistration result = evaluate_registration(source, tree, max_distance, transformation);
  for (int i = 0; i < criteria.max_iterations; ++i) {
    const Eigen::Matrix4d update = similarity_of_pairs(source, target, result.pairs);
    transformation = update * transformation;
    transform_points(update, source);
    const PointRegistration last = std::move(result);
    result = evaluate_registration(source, tree, max_distance, transformation);
    result.iterations = i + 1;
    if (std::abs(last.fitness - result.fitness) < criteria.relative_fitness &&
        std::abs(last.inlier_rmse - result.inlier_rmse) < criteria.relative_rmse) {
      break;
    }
  }
  return result;
}

}  // namespace roving
