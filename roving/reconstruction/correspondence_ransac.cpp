#include "roving/reconstruction/correspondence_ransac.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "roving/core/error.h"
#include "roving/reconstruction/tanks_and_temples_protocol.h"

namespace roving {
namespace {

// The share of the given pairs whose source point, moved, is closer than the distance to its target.
double inlier_share(const std::vector<Vec3>& moved, const std::vector<Vec3>& target, const PointPairs& pairs,
                    double max_distance) {
  std::size_t inliers = 0;
  for (const auto& [from, to] : pairs) {
    if ((moved[from] - target[to]).squaredNorm() < max_distance * max_distance) ++inliers;
  }
  return static_cast<double>(inliers) / static_cast<double>(pairs.size());
}

}  // namespace

PointRegistration ransac_on_pairs(const std::vector<Vec3>& source, const std::vector<Vec3>& target,
                                  const PointPairs& pairs, double max_distance, int sample_size,
                                  const RansacCriteria& criteria, std::uint32_t seed) {
  if (sample_size < 3 || pairs.size() < static_cast<std::size_t>(sample_size)) {
    throw Error(fmt::format("RANSAC: {} pairs to draw {} from; expected at least {} and a draw of at least 3",
                            pairs.size(), sample_size, std::max(sample_size, 3)));
  }
  if (!(std::isfinite(max_distance) && max_distance > 0)) {
    throw Error(fmt::format("RANSAC: the largest distance of a pair is {}; expected a length > 0", max_distance));
  }
  for (const auto& [from, to] : pairs) {
    if (from >= source.size() || to >= target.size()) {
      throw Error(fmt::format("RANSAC: the pair ({}, {}) names a point beyond the {} source and {} target points",
                              from, to, source.size(), target.size()));
    }
  }
  const PointTree tree(target);
  std::mt19937 engine(seed);
  std::uniform_int_distribution<int> draw(0, static_cast<int>(pairs.size()) - 1);
  PointRegistration best;
  PointPairs sample(static_cast<std::size_t>(sample_size));
  int enough = criteria.max_iterations;
  std::vector<Vec3> moved;
  for (int iteration = 0; iteration < criteria.max_iterations && iteration < enough; ++iteration) {
    for (auto& pair : sample) pair = pairs[static_cast<std::size_t>(draw(engine))];
    const Eigen::Matrix4d transformation = similarity_of_pairs(source, target, sample);
    moved = source;
    transform_points(transformation, moved);
    PointRegistration result = evaluate_registration(moved, tree, max_distance, transformation);
    if (!result.better_than(best)) continue;
    best = std::move(result);
    const double share = inlier_share(moved, target, pairs, max_distance);
    // Draws enough to have drawn only inliers once at `confidence`. With no inlier this is -inf,
    // which Open3D turns into the lowest int (x86's conversion), and stops: so does this.
    const double draws = std::log(1.0 - criteria.confidence) / std::log(1.0 - std::pow(share, sample_size));
    if (draws < enough) enough = std::isfinite(draws) ? static_cast<int>(std::ceil(draws)) : 0;
  }
  best.pairs.clear();
  return best;
}

}  // namespace roving
