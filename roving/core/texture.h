// Surface colour from textures: an 8-bit image, the sampler rules glTF 2.0 defines (and OBJ's
// subset of them), and a mesh's per-corner texture coordinates and per-face materials.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace roving {

using Colour = Eigen::Vector3f;  // sRGB code values on [0, 255] (see triangle_mesh.h)
using TexCoord = Eigen::Vector2d;

// An RGB image of 8-bit sRGB code values, row 0 at the top (as PNG and JPEG store it).
struct Texture {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // width * height * 3
  std::string source;             // the file, for messages

  Colour texel(int column, int row) const {
    const std::uint8_t* p = &rgb[(static_cast<std::size_t>(row) * width + column) * 3];
    return {float(p[0]), float(p[1]), float(p[2])};
  }
};

// glTF's sampler: wrap modes per axis and the magnification filter. The minification filter does not
// apply: a sample is one point, not a pixel's footprint, so no mipmap level is chosen.
enum class Wrap { Repeat, ClampToEdge, MirroredRepeat };
enum class Filter { Linear, Nearest };
struct Sampler {
  Wrap wrap_s = Wrap::Repeat, wrap_t = Wrap::Repeat;
  Filter filter = Filter::Linear;
};

// The texture's colour at `uv`, in glTF's convention: u to the right, v down from the image's top
// row, texel centres at ((i + 0.5) / width, (j + 0.5) / height). Linear filtering interpolates the
// four nearest texels' code values bilinearly (as GL does for a non-sRGB texture); the wrap mode
// chooses the texels beyond the edges.
Colour sample_texture(const Texture& texture, const Sampler& sampler, const TexCoord& uv);

// What a face's colour is made of: a constant factor (white when none), times its texture if any,
// in code values: colour = factor * texture / 255.
struct Material {
  std::string name;
  Colour factor = Colour::Constant(255);
  std::shared_ptr<const Texture> texture;
  Sampler sampler;
};

// Per-corner texture coordinates (three per triangle, in glTF's v-down convention) and one material
// per triangle.
struct TextureMapping {
  std::vector<Material> materials;
  std::vector<int> face_material;
  std::vector<TexCoord> corner_uv;
};

}  // namespace roving
