// Voxel models (paper Section 4.3): binvox files, their exposed faces as a test surface, and
// reference samples on those faces with axis normals.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "roving/sample_set.h"
#include "roving/triangle_mesh.h"

namespace roving {

// A cubic grid of dimension^3 voxels; voxel (x, y, z) is the cube
// origin + voxel_size * [x, x+1] x [y, y+1] x [z, z+1].
struct VoxelGrid {
  int dimension = 0;
  Vec3 origin = Vec3::Zero();
  double voxel_size = 1;
  std::vector<std::uint8_t> occupied;  // index(x, y, z)

  std::size_t index(int x, int y, int z) const {
    return (static_cast<std::size_t>(x) * dimension + z) * dimension + y;  // binvox order: y fastest, then z, then x
  }
  bool at(int x, int y, int z) const {
    return x >= 0 && y >= 0 && z >= 0 && x < dimension && y < dimension && z < dimension && occupied[index(x, y, z)];
  }
  std::size_t occupied_count() const;
};

// Reads a binvox file (header "#binvox 1", "dim D D D", "translate", "scale", "data", then
// run-length pairs). Throws roving::Error naming the file for a bad header, unequal or absurd
// dimensions (1..2048), runs that overflow or fall short of D^3, or an empty grid.
VoxelGrid read_binvox(const std::string& path);
void write_binvox(const VoxelGrid& grid, const std::string& path);

// The faces between an occupied and an empty voxel (or the grid's outside), two triangles each,
// facing out of the occupied voxel, on shared lattice vertices (watertight).
TriangleMesh exposed_faces(const VoxelGrid& grid);

// One sample per exposed face: its centre, its axis normal, its area as weight.
SampleSet exposed_face_samples(const VoxelGrid& grid);

}  // namespace roving
