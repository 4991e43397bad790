// Point clouds: positions with optional unit normals.
#pragma once

#include <vector>

#include "roving/core/triangle_mesh.h"

namespace roving {

struct PointCloud {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;  // unit; empty when the file had none
};

}  // namespace roving
