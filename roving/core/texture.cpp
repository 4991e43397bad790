// Texture sampling by glTF 2.0's sampler rules (its specification, section 3.8.4, defers to
// OpenGL's: wrap per axis, then nearest or bilinear among texel centres).
#include "roving/core/texture.h"

#include <algorithm>
#include <cmath>

namespace roving {
namespace {

// Texel index `i` (any integer) brought inside [0, size) by the wrap mode.
int wrap_index(long long i, int size, Wrap wrap) {
  switch (wrap) {
    case Wrap::ClampToEdge: return static_cast<int>(std::clamp<long long>(i, 0, size - 1));
    case Wrap::MirroredRepeat: {
      const long long period = 2LL * size;
      long long m = i % period;
      if (m < 0) m += period;
      return static_cast<int>(m < size ? m : period - 1 - m);
    }
    case Wrap::Repeat:
    default: {
      long long m = i % size;
      return static_cast<int>(m < 0 ? m + size : m);
    }
  }
}

// Texel coordinate from a texture coordinate, far out of range first brought near [0, 1] (where
// the wrap gives the same texel) so that the integer conversion cannot overflow.
double texel_coordinate(double t, int size, Wrap wrap) {
  if (std::abs(t) > 4 && wrap != Wrap::ClampToEdge) t -= 2 * std::floor(t / 2);  // period 2 suits both
  if (wrap == Wrap::ClampToEdge) t = std::clamp(t, -1.0, 2.0);
  return t * size;
}

}  // namespace

Colour sample_texture(const Texture& texture, const Sampler& sampler, const TexCoord& uv) {
  const double x = texel_coordinate(uv.x(), texture.width, sampler.wrap_s);
  const double y = texel_coordinate(uv.y(), texture.height, sampler.wrap_t);
  if (sampler.filter == Filter::Nearest) {
    const int column = wrap_index(static_cast<long long>(std::floor(x)), texture.width, sampler.wrap_s);
    const int row = wrap_index(static_cast<long long>(std::floor(y)), texture.height, sampler.wrap_t);
    return texture.texel(column, row);
  }
  const double fx = std::floor(x - 0.5), fy = std::floor(y - 0.5);
  const double a = x - 0.5 - fx, b = y - 0.5 - fy;  // weights of the right and lower texels
  const int c0 = wrap_index(static_cast<long long>(fx), texture.width, sampler.wrap_s);
  const int c1 = wrap_index(static_cast<long long>(fx) + 1, texture.width, sampler.wrap_s);
  const int r0 = wrap_index(static_cast<long long>(fy), texture.height, sampler.wrap_t);
  const int r1 = wrap_index(static_cast<long long>(fy) + 1, texture.height, sampler.wrap_t);
  const Eigen::Vector3d top =
      (1 - a) * texture.texel(c0, r0).cast<double>() + a * texture.texel(c1, r0).cast<double>();
  const Eigen::Vector3d bottom =
      (1 - a) * texture.texel(c0, r1).cast<double>() + a * texture.texel(c1, r1).cast<double>();
  return ((1 - b) * top + b * bottom).cast<float>();
}

}  // namespace roving
