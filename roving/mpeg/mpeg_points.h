// A point cloud as MPEG's pc_error (mpeg-pcc-dmetric 0.14) holds it before it measures: single-
// precision coordinates and normals, 8-bit colours, sorted, and points at the same position merged
// into one (their colours averaged, truncated; the first one's normal kept), pc_error's default
// `--dropdups=2`. Every figure it prints is over these points, so ours are too.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "roving/core/point_cloud.h"

namespace roving {

struct MpegPoints {
  std::vector<std::array<float, 3>> positions;
  std::vector<std::array<float, 3>> normals;     // empty: none (D2 needs them on A)
  std::vector<std::array<std::uint8_t, 3>> colours;  // empty: none
  std::size_t points_read = 0;                   // before merging
  std::size_t size() const { return positions.size(); }
};

// `cloud` as pc_error holds it, its normals kept where `with_normals` (pc_error uses A's alone).
// Colours are rounded to 8 bits (pc_error reads only 8-bit ones). With `average_normals` (mmetric's
// own merging), merged points get the mean of their normals (not normalised) instead of the first.
// Throws roving::Error naming `name` for a cloud with no points, a coordinate or normal that is not
// finite (or beyond float's range), or normals or colours not one per point.
MpegPoints mpeg_points(const PointCloud& cloud, const std::string& name, bool with_normals,
                       bool average_normals = false);

// The same of a cloud whose records are read where a binary file holds them, without a copy in
// double precision (A binary PLY's: ply_packed_points). The figures are those of the file read into
// a PointCloud; a point that is not finite is named as above.
MpegPoints mpeg_points(const PackedPointCloud& packed, const std::string& name, bool with_normals,
                       bool average_normals = false);

// pc_error's --inputNorm: A's normals taken from another file's cloud (`normals`, made by
// mpeg_points with its normals), which pc_error pairs with A's points by their sorted order. Throws
// roving::Error naming `name` where it has no normals or its points, merged, are not A's (pc_error
// checks neither).
void use_normals_of(MpegPoints& a, MpegPoints& normals, const std::string& name);

}  // namespace roving
