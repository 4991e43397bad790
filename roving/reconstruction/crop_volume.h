// Open3D's SelectionPolygonVolume, the crop files of Tanks and Temples (<scene>.json): a polygon
// drawn across two axes, extruded between two values of the third (the orthogonal axis). A point is
// inside as Open3D's CropInPolygon decides it, boundaries included: within [axis_min, axis_max],
// and an odd number of the polygon's edge crossings (on the point's line along the first axis)
// below the point's own coordinate, ties going as its sort and lower_bound send them.
#pragma once

#include <string>
#include <vector>

#include "roving/core/triangle_mesh.h"

namespace roving {

class CropVolume {
 public:
  // `axis`: 0, 1 or 2 for x, y or z; `polygon`: its vertices in order, closed from the last back to
  // the first (their coordinate along `axis` unused). Throws roving::Error, naming `source`, for a
  // polygon of fewer than 3 vertices, non-finite numbers, or axis_min > axis_max.
  CropVolume(int axis, double axis_min, double axis_max, std::vector<Vec3> polygon, const std::string& source);

  bool contains(const Vec3& p) const;
  int axis() const { return w_; }
  double axis_min() const { return axis_min_; }
  double axis_max() const { return axis_max_; }
  const std::vector<Vec3>& polygon() const { return polygon_; }

 private:
  int u_, v_, w_;  // the polygon's axes (crossings along u, on the line of the point's v) and the orthogonal one
  double axis_min_, axis_max_;
  std::vector<Vec3> polygon_;
};

// Reads Open3D's JSON for it (class_name "SelectionPolygonVolume", version 1.0, orthogonal_axis
// "X"/"Y"/"Z" in either case, axis_min, axis_max, bounding_polygon as [x, y, z] rows). Throws
// roving::Error naming `path` and what was expected where the file is not that.
CropVolume read_crop_volume(const std::string& path);

}  // namespace roving
