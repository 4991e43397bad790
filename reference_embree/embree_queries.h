// What the Embree-based code shares: a box in Embree's float rounded outwards, and a point query.
// Private to reference_embree (included by its .cpp files only).
#pragma once

#include <embree3/rtcore.h>

#include <cmath>

#include "roving/core/geometry.h"

namespace roving {

// [low, high] (double, in the scene's centred frame) as Embree's float box, rounded outwards so
// that it still holds every point of the double box.
inline void write_bounds(const Vec3& low, const Vec3& high, RTCBounds* out) {
  const auto down = [](double v) { return std::nextafter(static_cast<float>(v), -INFINITY); };
  const auto up = [](double v) { return std::nextafter(static_cast<float>(v), INFINITY); };
  out->lower_x = down(low.x()), out->lower_y = down(low.y()), out->lower_z = down(low.z());
  out->upper_x = up(high.x()), out->upper_y = up(high.y()), out->upper_z = up(high.z());
}

// A point query at `centred` (the query point less the scene's origin) within `radius`.
inline RTCPointQuery point_query(const Vec3& centred, float radius) {
  RTCPointQuery query;
  query.x = static_cast<float>(centred.x());
  query.y = static_cast<float>(centred.y());
  query.z = static_cast<float>(centred.z());
  query.time = 0.0f;
  query.radius = radius;
  return query;
}

}  // namespace roving
