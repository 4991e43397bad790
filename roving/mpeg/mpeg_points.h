// A point cloud as MPEG's pc_error (mpeg-pcc-dmetric 0.14) holds it before it measures: single-
// precision coordinates and normals, 8-bit colours, sorted, and points at the same position merged
// into one (their colours averaged, truncated; the first one's normal kept), pc_error's default
// `--dropdups=2` (or the first kept, or all). Every figure it prints is over these points, so ours are too.
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
  std::vector<std::uint32_t> merged;             // how many points each merged, where asked for
  std::size_t points_read = 0;                   // before merging
  std::size_t nan_normals = 0;                   // normals used that are NaN (where kept)
  std::size_t first_nan_normal = 0;              // the first of them, in file order
  std::size_t size() const { return positions.size(); }
};

// How mpeg_points holds a cloud.
struct MpegReading {
  bool normals = true;           // the file's normals kept (pc_error's D2 uses A's alone)
  bool average_normals = false;  // merged points (dropdups 2) take their normals' mean (mmetric's merging), not the first's
  int dropdups = 2;              // pc_error's --dropdups: points at one position 0 all kept, 1 the first, 2 merged
  bool merged_counts = false;    // MpegPoints::merged filled (pc_error's --neighborsProc 2 weighs by it)
  bool nan_normals = false;      // NaN normals kept (pc_error computes on with them), else refused
};

// `cloud` as pc_error holds it, read as `reading` says. Colours are rounded to 8 bits (pc_error
// reads only 8-bit ones); merged points' colours are averaged (truncated), the first one's normal
// kept. Throws roving::Error naming `name` for a cloud with no points, a coordinate or normal that
// is not finite (or beyond float's range; a NaN normal is kept where `reading.nan_normals`), or
// normals or colours not one per point.
MpegPoints mpeg_points(const PointCloud& cloud, const std::string& name, const MpegReading& reading);

// The same of a cloud whose records are read where a binary file holds them, without a copy in
// double precision (A binary PLY's: ply_packed_points). The figures are those of the file read into
// a PointCloud; a point that is not finite is named as above.
MpegPoints mpeg_points(const PackedPointCloud& packed, const std::string& name, const MpegReading& reading);

// pc_error's --inputNorm: A's normals taken from another file's cloud (`normals`, made by
// mpeg_points with its normals), which pc_error pairs with A's points by their sorted order. Throws
// roving::Error naming `name` where it has no normals or its points, merged, are not A's (pc_error
// checks neither).
void use_normals_of(MpegPoints& a, MpegPoints& normals, const std::string& name);

}  // namespace roving
