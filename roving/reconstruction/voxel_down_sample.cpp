#include "roving/reconstruction/voxel_down_sample.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

#include "roving/core/error.h"

namespace roving {

std::vector<Vec3> voxel_down_sample(const std::vector<Vec3>& points, double voxel_size, const std::string& name) {
  if (!(std::isfinite(voxel_size) && voxel_size > 0)) {
    throw Error(fmt::format("{}: voxel down-sampling: voxel size {}; expected a length > 0", name, voxel_size));
  }
  if (points.empty()) return {};
  Vec3 low = points[0], high = points[0];
  for (const Vec3& p : points) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  const Vec3 half = Vec3::Constant(voxel_size) * 0.5;
  const Vec3 grid_low = low - half, grid_high = high + half;
  if (voxel_size * std::numeric_limits<int>::max() < (grid_high - grid_low).maxCoeff()) {
    throw Error(fmt::format("{}: voxel down-sampling: voxel size {} is too small for points spanning {} (a cube's "
                            "index would not fit an int)",
                            name, voxel_size, (grid_high - grid_low).maxCoeff()));
  }
  struct Cube {
    Vec3 sum = Vec3::Zero();
    std::uint32_t count = 0;
  };
  std::vector<Cube> cubes;
  // A cube by its three indices (each may be any int, so they are hashed, not packed).
  struct Key {
    int x, y, z;
    bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      std::uint64_t h = static_cast<std::uint32_t>(k.x);
      h = h * 0x9E3779B97F4A7C15ull ^ static_cast<std::uint32_t>(k.y);
      h = h * 0x9E3779B97F4A7C15ull ^ static_cast<std::uint32_t>(k.z);
      return static_cast<std::size_t>(h ^ (h >> 29));
    }
  };
  std::unordered_map<Key, std::uint32_t, KeyHash> cube_of;
  cube_of.reserve(points.size() / 4 + 16);
  for (const Vec3& p : points) {
    const Vec3 r = (p - grid_low) / voxel_size;
    const Key key{static_cast<int>(std::floor(r[0])), static_cast<int>(std::floor(r[1])),
                  static_cast<int>(std::floor(r[2]))};
    const auto [it, added] = cube_of.try_emplace(key, static_cast<std::uint32_t>(cubes.size()));
    if (added) cubes.emplace_back();
    Cube& cube = cubes[it->second];
    cube.sum += p;
    ++cube.count;
  }
  std::vector<Vec3> means;
  means.reserve(cubes.size());
  for (const Cube& cube : cubes) means.push_back(cube.sum / double(cube.count));
  return means;
}

}  // namespace roving
