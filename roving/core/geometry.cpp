// Morton codes of points in a box (the closest-point kernels are inline in geometry.h).
#include "roving/core/geometry.h"

#include <algorithm>

namespace roving {

namespace {

// The low 10 bits of v spread to every third position (one axis of a Morton code).
std::uint64_t spread_bits(std::uint32_t v) {
  std::uint64_t x = v & 0x3ff;
  x = (x | (x << 16)) & 0x30000ff;
  x = (x | (x << 8)) & 0x300f00f;
  x = (x | (x << 4)) & 0x30c30c3;
  x = (x | (x << 2)) & 0x9249249;
  return x;
}

}  // namespace

std::uint64_t morton_code(const Vec3& p, const BoundingBox& box) {
  const Vec3 scale = (1023.0 / box.size().array().max(1e-300)).matrix();
  const Vec3 cell = (p - box.min).cwiseProduct(scale);
  std::uint64_t code = 0;
  for (int axis = 0; axis < 3; ++axis)
    code |= spread_bits(static_cast<std::uint32_t>(std::clamp(cell[axis], 0.0, 1023.0))) << axis;
  return code;
}

}  // namespace roving
