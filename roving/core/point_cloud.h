// Point clouds: positions with optional unit normals and colours.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "roving/core/triangle_mesh.h"

namespace roving {

struct PointCloud {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;    // unit; empty when the file had none
  std::vector<Colour> colours;  // sRGB code values (triangle_mesh.h); empty when the file had none
};

// A point cloud's records where a binary file holds them, read in place (ply_packed_points): a
// fixed-size record a point, its coordinates and normals float or double at these offsets, its
// colours uchar. The bytes belong to whoever made it and must outlive it.
struct PackedPointCloud {
  struct Field {
    std::size_t offset = 0;  // within a record
    bool is_double = false;  // else float
  };
  const char* records = nullptr;
  std::size_t count = 0, stride = 0;
  std::array<Field, 3> position{}, normal{};
  std::array<std::size_t, 3> colour{};  // red, green, blue
  bool normals = false, colours = false;
};

}  // namespace roving
