// Point clouds: positions with optional unit normals and colours.
#pragma once

#include <vector>

#include "roving/core/triangle_mesh.h"

namespace roving {

struct PointCloud {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;    // unit; empty when the file had none
  std::vector<Colour> colours;  // sRGB code values (triangle_mesh.h); empty when the file had none
};

}  // namespace roving
