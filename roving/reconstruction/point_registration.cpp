#include "roving/reconstruction/point_registration.h"

#include <fmt/format.h>

#include <Eigen/SVD>
#include <algorithm>
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
  result.pairs.reserve(static_cast<std::size_t>(
      std::count_if(squared.begin(), squared.end(), [&](double d) { return d < limit; })));
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
  // Eigen's umeyama step for step, its 3 x n matrices (and their centred copies, 4 x 24 bytes a
  // pair: 230 MB for the 2.4 M pairs of a 3 M-point cloud, each fresh allocation a page fault a
  // page) replaced by sums over the pairs in order. Its sums are blocked and vectorised, so the
  // last bits of the means and of sigma differ from these.
  const double one_over_n = 1.0 / static_cast<double>(pairs.size());
  Vec3 source_sum = Vec3::Zero(), target_sum = Vec3::Zero();
  for (const auto& [from, to] : pairs) {
    source_sum += source[from];
    target_sum += target[to];
  }
  const Vec3 source_mean = source_sum * one_over_n, target_mean = target_sum * one_over_n;
  Eigen::Matrix3d sigma = Eigen::Matrix3d::Zero();  // the covariance of target against source
  double source_variance = 0;
  for (const auto& [from, to] : pairs) {
    const Vec3 a = source[from] - source_mean, b = target[to] - target_mean;
    sigma += b * a.transpose();
    source_variance += a.squaredNorm();
  }
  sigma *= one_over_n;
  source_variance *= one_over_n;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(sigma, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Vec3 s = Vec3::Ones();  // a reflection turned into the nearest rotation
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0) s(2) = -1;
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = svd.matrixU() * s.asDiagonal() * svd.matrixV().transpose();
  const double scale = 1.0 / source_variance * svd.singularValues().dot(s);
  m.block<3, 1>(0, 3) = target_mean - scale * m.topLeftCorner<3, 3>() * source_mean;
  m.topLeftCorner<3, 3>() *= scale;
  return m;
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
