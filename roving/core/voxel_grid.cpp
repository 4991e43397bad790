// Voxel grids (paper Section 4.3).
#include "roving/core/voxel_grid.h"

#include <algorithm>

namespace roving {

std::size_t VoxelGrid::occupied_count() const {
  return static_cast<std::size_t>(std::count(occupied.begin(), occupied.end(), std::uint8_t{1}));
}

}  // namespace roving
