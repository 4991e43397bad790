// Open3D's PointCloud::VoxelDownSample, as Tanks and Temples' evaluation thins both clouds: a grid
// of cubes of side `voxel_size` whose corner is half a side below the points' least corner; each
// occupied cube gives the mean of its points, summed in the points' order (Open3D's figure to the
// last bit). The cubes come out in Morton order (Open3D's hash-map order is unspecified; the
// figures computed from them are counts, which no order changes).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "roving/core/triangle_mesh.h"

namespace roving {

// `keep`, where given, marks the points to take (1) and those to leave out (0), as a crop leaves
// them; `move`, where given, moves each point first (as transformed_point moves it), so that a
// moved cloud need not be copied whole. Throws roving::Error, naming `name`, for a voxel_size that is not finite and > 0, or one so
// small that a cube's index along an axis would not fit an int (Open3D's "voxel_size is too small").
std::vector<Vec3> voxel_down_sample(const std::vector<Vec3>& points, double voxel_size,
                                    const std::string& name = "points", const std::vector<std::uint8_t>* keep = nullptr,
                                    const Eigen::Matrix4d* move = nullptr);

}  // namespace roving
