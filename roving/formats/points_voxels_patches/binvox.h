// binvox voxel files.
#pragma once

#include <string>

#include "roving/core/voxel_grid.h"

namespace roving {

// Reads a binvox file (header "#binvox 1", "dim D D D", "translate", "scale", "data", then
// run-length pairs). Throws roving::Error naming the file for a bad header, unequal or absurd
// dimensions (1..2048), runs that overflow or fall short of D^3, or an empty grid.
VoxelGrid read_binvox(const std::string& path);
void write_binvox(const VoxelGrid& grid, const std::string& path);

}  // namespace roving
