// Voxel models (paper Section 4.3): a cubic grid of occupied and empty voxels.
#pragma once

#include <cstdint>
#include <vector>

#include "roving/core/triangle_mesh.h"

namespace roving {

// A cubic grid of dimension^3 voxels; voxel (x, y, z) is the cube
// origin + voxel_size * [x, x+1] x [y, y+1] x [z, z+1].
struct VoxelGrid {
  int dimension = 0;
  Vec3 origin = Vec3::Zero();
  double voxel_size = 1;
  std::vector<std::uint8_t> occupied;  // index(x, y, z)

  std::size_t index(int x, int y, int z) const {
    return (static_cast<std::size_t>(x) * dimension + z) * dimension +
           y;  // binvox order: y fastest, then z, then x
  }
  bool at(int x, int y, int z) const {
    return x >= 0 && y >= 0 && z >= 0 && x < dimension && y < dimension && z < dimension &&
           occupied[index(x, y, z)];
  }
  std::size_t occupied_count() const;
};

}  // namespace roving
