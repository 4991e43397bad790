// Thinning a cloud as scikit-learn's radius query and a loop do it in DTUeval-python: visiting the
// points in the order `rank` gives, each is kept unless a point kept before it is within `radius`
// (squared distance <= radius^2, as scikit-learn tests it).
#pragma once

#include <cstdint>
#include <vector>

#include "roving/core/triangle_mesh.h"

namespace roving {

// 1 per kept point, in the points' own indexing; rank[i] is point i's place in the visiting order
// (a permutation of 0 .. n - 1). Throws roving::Error for points whose extent is not finite.
std::vector<std::uint8_t> greedy_thinning(const std::vector<Vec3>& points, std::vector<std::uint32_t> rank,
                                          double radius);

}  // namespace roving
