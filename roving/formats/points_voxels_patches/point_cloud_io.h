// Point clouds with normals and colours: PLY (vertices, optional nx ny nz and red green blue, no
// faces) and XYZ: "x y z" or "x y z nx ny nz" per line, or the columns a first comment line names
// ("# x y z r g b nx ny nz" or CloudCompare's "//X,Y,Z,R,G,B"), r g b being code values 0-255.
#pragma once

#include <string>

#include "roving/core/point_cloud.h"

namespace roving {

// Throws roving::Error naming the file (and line, for XYZ) on a malformed record, a coordinate
// NaN/inf, a colour outside [0, 255], an unknown or repeated column name, or no points. With
// `unit_normals`, normals are made unit and one of zero length or not finite is an error; without,
// they are kept as the file has them (MPEG's figures use them so) and left to the caller to check.
PointCloud read_point_cloud(const std::string& path, bool unit_normals = true);
// The same, except that points with a NaN or infinite coordinate are left out (with their normals
// and colours), as the Tanks and Temples toolbox's Open3D reads or crops them away; `dropped`
// counts them. A file none of whose points is finite has no points (an error).
PointCloud read_point_cloud_finite(const std::string& path, std::size_t& dropped);
// True when read_point_cloud reads `path` as a PLY (by its extension), else as XYZ.
bool read_as_ply(const std::string& path);

void write_point_cloud_ply(const PointCloud& cloud, const std::string& path);

// True when `path` is a PLY whose header declares no faces (a point cloud, not a mesh).
bool is_ply_point_cloud(const std::string& path);

}  // namespace roving
