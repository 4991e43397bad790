// A point cloud coloured by each point's distance, as the Tanks and Temples toolbox writes it for
// viewing (evaluation.py's write_color_distances): matplotlib's "hot_r" colour map at
// min(d, max) / max, the colours written as Open3D writes a point cloud's PLY (binary, double
// coordinates, 8-bit colours). Points on the other cloud are white, far ones (max and beyond) black.
#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "roving/core/triangle_mesh.h"

namespace roving {

// matplotlib 3.6's hot_r (256 entries) at t in [0, 1], as 8-bit code values the way Open3D's PLY
// writer turns its [0, 1] colours into bytes (times 255, rounded).
std::array<std::uint8_t, 3> hot_r_colour(double t);

// `points` with the colour of min(distances[i], max_distance) / max_distance (one distance per
// point; max_distance > 0), binary little-endian PLY.
void write_distance_cloud_ply(std::FILE* out, const std::vector<Vec3>& points, const std::vector<double>& distances,
                              double max_distance);

}  // namespace roving
