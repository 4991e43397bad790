#include "roving/reconstruction/point_registration.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

#include "roving/core/error.h"
#include "roving/reconstruction/tanks_and_temples_protocol.h"

namespace roving {

namespace {

// Pairs up to this many (6 MB of matrices) are solved in Open3D's own arithmetic.
constexpr std::size_t kPairsInOpen3dsMatrices = std::size_t(1) << 16;

// The registration of source points whose nearest target points are `nearest`, `squared` away.
// In blocks on every core: each block's pairs counted, then listed in order, and its squared
// distances summed; the blocks' sums added in order (the same bits on any number of cores).
PointRegistration registration_of(const std::vector<std::uint32_t>& nearest, const std::vector<double>& squared,
                                  double max_distance, const Eigen::Matrix4d& transformation) {
  PointRegistration result;
  result.transformation = transformation;
  const double limit = max_distance * max_distance;
  constexpr std::size_t kBlock = 1 << 15;
  const std::size_t n = squared.size(), blocks = (n + kBlock - 1) / kBlock;
  std::vector<std::size_t> before(blocks + 1, 0);  // pairs in the blocks before each
  std::vector<double> error2(blocks, 0);
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
    std::size_t count = 0;
    for (std::size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) {
      if (squared[i] < limit) {
        error2[b] += squared[i];
        ++count;
      }
    }
    before[b + 1] = count;
  });
  for (std::size_t b = 0; b < blocks; ++b) before[b + 1] += before[b];
  result.pairs.resize(before[blocks]);
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
    std::size_t k = before[b];
    for (std::size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) {
      if (squared[i] < limit) result.pairs[k++] = {static_cast<std::uint32_t>(i), nearest[i]};
    }
  });
  if (!result.pairs.empty()) {
    double sum = 0;
    for (const double e : error2) sum += e;
    const double count = static_cast<double>(result.pairs.size());
    result.fitness = count / static_cast<double>(n);
    result.inlier_rmse = std::sqrt(sum / count);
  }
  return result;
}

// Each source point's nearest target point, carried from one ICP step to the next. A point whose
// second nearest target point is d2 away is at least d2 - m from every target point but its
// nearest after it has moved m in all (the triangle inequality), so while its nearest, measured
// again, is nearer than that, it is still its nearest; ICP's later steps move the points by
// little: most points then need no search, only their distance computed again, as the k-d tree
// computes it. The same pairs as a search from scratch (a tie aside, where any of the equally
// near points is as right, and duplicates add the same to every sum).
class NearestTargets {
 public:
  NearestTargets(const PointTree& tree, const std::vector<Vec3>& source)
      : tree_(tree), index_(source.size()), squared_(source.size()), reach_(source.size()) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, source.size(), 4096), [&](const auto& range) {
      for (std::size_t i = range.begin(); i < range.end(); ++i) search(i, source[i]);
    });
  }

  // Moves each source point as transform_points does, and finds its nearest target point again.
  void move(const Eigen::Matrix4d& update, std::vector<Vec3>& source) {
    const std::vector<Vec3>& target = tree_.points();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, source.size(), 4096), [&](const auto& range) {
      for (std::size_t i = range.begin(); i < range.end(); ++i) {
        const Vec3 moved = transformed_point(update, source[i]);
        reach_[i] -= (moved - source[i]).norm();
        source[i] = moved;
        const Vec3& t = target[index_[i]];
        const double dx = moved[0] - t[0], dy = moved[1] - t[1], dz = moved[2] - t[2];
        const double squared = dx * dx + dy * dy + dz * dz;  // the tree's sum, in its order
        if (reach_[i] > 0 && squared < reach_[i] * reach_[i]) {
          squared_[i] = squared;
        } else {
          search(i, moved);
        }
      }
    });
  }

  PointRegistration registration(double max_distance, const Eigen::Matrix4d& transformation) const {
    return registration_of(index_, squared_, max_distance, transformation);
  }

 private:
  void search(std::size_t i, const Vec3& p) {
    double second = 0;
    tree_.nearest_two(p, index_[i], squared_[i], second);
    // The second nearest's distance, less a margin far above the rounding of the distances (so
    // that a point kept is one the search would also find first); infinite where there is none.
    const double d2 = std::sqrt(second);
    reach_[i] = std::isinf(d2) ? d2 : d2 - 1e-9 * (p.cwiseAbs().maxCoeff() + d2);
  }

  const PointTree& tree_;
  std::vector<std::uint32_t> index_;
  std::vector<double> squared_;
  std::vector<double> reach_;  // every target point but the nearest is at least this far
};

}  // namespace

PointRegistration evaluate_registration(const std::vector<Vec3>& source, const PointTree& target, double max_distance,
                                        const Eigen::Matrix4d& transformation) {
  std::vector<std::uint32_t> nearest;
  std::vector<double> squared;
  target.nearest(source, nearest, squared);
  return registration_of(nearest, squared, max_distance, transformation);
}

Eigen::Matrix4d similarity_of_pairs(const std::vector<Vec3>& source, const std::vector<Vec3>& target,
                                    const PointPairs& pairs) {
  if (pairs.empty()) return Eigen::Matrix4d::Identity();
  if (pairs.size() <= kPairsInOpen3dsMatrices) {
    // Open3D's TransformationEstimationPointToPoint exactly: the pairs' points copied into two 3 x n
    // matrices and Eigen's umeyama called on them, so its vectorised, blocked sums give the same
    // bits as Open3D's (Debian's build of it on the same Eigen 3.4 with the same SSE2 code; the
    // test compares with Open3D's own matrix). RANSAC's draws of 6 pairs decide the alignment's
    // last bits, and with them which side of a voxel's boundary a point falls in ICP's rounds.
    Eigen::MatrixXd source_matrix(3, static_cast<Eigen::Index>(pairs.size()));
    Eigen::MatrixXd target_matrix(3, static_cast<Eigen::Index>(pairs.size()));
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      source_matrix.col(static_cast<Eigen::Index>(k)) = source[pairs[k].first];
      target_matrix.col(static_cast<Eigen::Index>(k)) = target[pairs[k].second];
    }
    return Eigen::umeyama(source_matrix, target_matrix, true);
  }
  // Above that, Eigen's umeyama step for step, its 3 x n matrices (and their centred copies, 4 x
  // 24 bytes a pair: 230 MB for the 2.4 M pairs of a 3 M-point cloud, each fresh allocation a page
  // fault a page) replaced by sums over the pairs. Eigen's sums are blocked and vectorised, these
  // are blocks of pairs summed on every core and added in order (the same bits on any number of
  // cores): the last bits of the means and of sigma differ from Eigen's.
  const double one_over_n = 1.0 / static_cast<double>(pairs.size());
  const auto summed = [&](auto term, auto zero) {
    constexpr std::size_t kBlock = 1 << 15;
    std::vector<decltype(zero)> block_sums((pairs.size() + kBlock - 1) / kBlock, zero);
    tbb::parallel_for(std::size_t(0), block_sums.size(), [&](std::size_t b) {
      for (std::size_t k = b * kBlock; k < std::min(pairs.size(), (b + 1) * kBlock); ++k) {
        term(block_sums[b], source[pairs[k].first], target[pairs[k].second]);
      }
    });
    for (std::size_t b = 1; b < block_sums.size(); ++b) block_sums[0] += block_sums[b];
    return block_sums[0];
  };
  using Sums = Eigen::Matrix<double, 3, 2>;  // the source's, the target's
  const Sums means = summed(
                         [](Sums& sum, const Vec3& a, const Vec3& b) {
                           sum.col(0) += a;
                           sum.col(1) += b;
                         },
                         Sums::Zero().eval()) *
                     one_over_n;
  const Vec3 source_mean = means.col(0), target_mean = means.col(1);
  using Moments = Eigen::Matrix<double, 3, 4>;  // the covariance of target against source; the source's variance
  const Moments moments = summed(
      [&](Moments& sum, const Vec3& source_point, const Vec3& target_point) {
        const Vec3 a = source_point - source_mean, b = target_point - target_mean;
        sum.leftCols<3>() += b * a.transpose();
        sum(0, 3) += a.squaredNorm();
      },
      Moments::Zero().eval());
  const Eigen::Matrix3d sigma = moments.leftCols<3>() * one_over_n;
  const double source_variance = moments(0, 3) * one_over_n;
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

PointRegistration icp_point_to_point(std::vector<Vec3> source, const PointTree& tree, double max_distance,
                                     const IcpCriteria& criteria) {
  if (!(std::isfinite(max_distance) && max_distance > 0)) {
    throw Error(fmt::format("ICP: the largest distance of a pair is {}; expected a length > 0", max_distance));
  }
  const std::vector<Vec3>& target = tree.points();
  if (target.empty()) throw Error("ICP: the target has no point");
  NearestTargets nearest(tree, source);
  Eigen::Matrix4d transformation = Eigen::Matrix4d::Identity();
  PointRegistration result = nearest.registration(max_distance, transformation);
  for (int i = 0; i < criteria.max_iterations; ++i) {
    const Eigen::Matrix4d update = similarity_of_pairs(source, target, result.pairs);
    transformation = update * transformation;
    nearest.move(update, source);
    const double last_fitness = result.fitness, last_rmse = result.inlier_rmse;
    result.pairs = {};  // freed before the next are made
    result = nearest.registration(max_distance, transformation);
    result.iterations = i + 1;
    if (std::abs(last_fitness - result.fitness) < criteria.relative_fitness &&
        std::abs(last_rmse - result.inlier_rmse) < criteria.relative_rmse) {
      break;
    }
  }
  return result;
}

}  // namespace roving
