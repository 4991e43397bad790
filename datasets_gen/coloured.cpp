// Procedural colour fields and textures for coloured versions of the real models.
#include "coloured.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "roving/core/error.h"

namespace roving {

Colour procedural_colour(const Vec3& unit, double phase) {
  return Colour(static_cast<float>(127.5 + 110 * std::sin(12 * unit.x() + phase)),
                static_cast<float>(127.5 + 110 * std::cos(9 * unit.y())),
                static_cast<float>(20 + 215 * std::clamp(unit.z(), 0.0, 1.0)));
}

namespace {

const BoundingBox& box_or_own(const TriangleMesh& mesh, const BoundingBox& box) {
  return box.empty() ? mesh.bounding_box() : box;
}

Vec3 across(const BoundingBox& box, const Vec3& p) {
  return (p - box.min).cwiseQuotient(box.size().cwiseMax(Vec3::Constant(1e-300)));
}

}  // namespace

std::vector<Colour> procedural_colours(const TriangleMesh& mesh, const BoundingBox& box) {
  const BoundingBox& b = box_or_own(mesh, box);
  std::vector<Colour> colours;
  colours.reserve(mesh.vertex_count());
  for (const Vec3& p : mesh.positions()) colours.push_back(procedural_colour(across(b, p)));
  return colours;
}

Texture procedural_texture(int side, double phase, int stripes) {
  Texture t;
  t.width = t.height = side;
  t.source = "procedural texture";
  t.rgb.resize(static_cast<std::size_t>(3) * side * side);
  for (int row = 0; row < side; ++row) {
    for (int column = 0; column < side; ++column) {
      const double u = (column + 0.5) / side, v = (row + 0.5) / side;
      Colour c = procedural_colour(Vec3(u, 1 - v, 0.5), phase);
      if (stripes > 0) c.y() = float(c.y() * (0.75 + 0.25 * std::sin(2 * M_PI * stripes * u)));
      for (int k = 0; k < 3; ++k) {
        t.rgb[(static_cast<std::size_t>(row) * side + column) * 3 + k] =
            static_cast<std::uint8_t>(std::clamp(std::lround(c[k]), 0L, 255L));
      }
    }
  }
  return t;
}

TriangleMesh with_planar_texture(const TriangleMesh& mesh, std::shared_ptr<const Texture> texture,
                                 const Sampler& sampler, const BoundingBox& box) {
  const BoundingBox& b = box_or_own(mesh, box);
  TextureMapping mapping;
  Material material;
  material.name = "procedural";
  material.texture = std::move(texture);
  material.sampler = sampler;
  mapping.materials.push_back(material);
  mapping.face_material.assign(mesh.triangle_count(), 0);
  mapping.corner_uv.reserve(3 * mesh.triangle_count());
  for (const Triangle& t : mesh.triangles()) {
    for (const int v : t) {
      const Vec3 unit = across(b, mesh.positions()[v]);
      mapping.corner_uv.emplace_back(unit.x(), 1 - unit.y());
    }
  }
  TriangleMesh textured = mesh;
  textured.set_texture_mapping(std::move(mapping), "planar texture");
  return textured;
}

Colour detailed_colour(const Vec3& unit, int bands) {
  Colour c = procedural_colour(unit);
  if (bands > 0) c.y() = float(c.y() * (0.7 + 0.3 * std::sin(2 * M_PI * bands * unit.sum() / 3)));
  return c;
}

namespace {

std::uint8_t code(double value) {
  return static_cast<std::uint8_t>(std::clamp(std::lround(value), 0L, 255L));
}

}  // namespace

TriangleMesh with_baked_atlas(const TriangleMesh& mesh, int side,
                              const std::function<Colour(const Vec3&)>& field) {
  const std::size_t faces = mesh.triangle_count();
  const int cells = std::max(1, static_cast<int>(std::ceil(std::sqrt(double(faces)))));
  const int cell = side / cells;
  if (cell < 4) {
    throw Error(
        fmt::format("texture atlas: {} triangles need cells of at least 4 texels; {} texels a side give {}",
                    faces, side, cell));
  }
  auto atlas = std::make_shared<Texture>();
  atlas->width = atlas->height = side;
  atlas->source = "baked atlas";
  atlas->rgb.assign(static_cast<std::size_t>(3) * side * side, 0);
  TextureMapping mapping;
  mapping.materials.emplace_back().name = "atlas";
  mapping.materials[0].texture = atlas;
  mapping.face_material.assign(faces, 0);
  mapping.corner_uv.resize(3 * faces);
  tbb::parallel_for(std::size_t(0), faces, [&](std::size_t f) {
    const int x0 = static_cast<int>(f % cells) * cell, y0 = static_cast<int>(f / cells) * cell;
    // The corners in texel coordinates (x right, y down from the top row), and their points.
    const Eigen::Vector2d corner[3] = {
        {x0 + 1.0, y0 + 1.0}, {x0 + cell - 1.0, y0 + 1.0}, {x0 + 1.0, y0 + cell - 1.0}};
    const Triangle& t = mesh.triangles()[f];
    const Vec3 p[3] = {mesh.positions()[t[0]], mesh.positions()[t[1]], mesh.positions()[t[2]]};
    for (int c = 0; c < 3; ++c) mapping.corner_uv[3 * f + c] = corner[c] / side;
    // The cell's legs are along x and y: a texel centre (x, y) is the point
    // p0 + (x - x0 - 1) / (cell - 2) (p1 - p0) + (y - y0 - 1) / (cell - 2) (p2 - p0).
    for (int y = y0; y < y0 + cell; ++y) {
      for (int x = x0; x < x0 + cell; ++x) {
        const double a = (x + 0.5 - x0 - 1) / (cell - 2), b = (y + 0.5 - y0 - 1) / (cell - 2);
        const Colour colour = field(p[0] + a * (p[1] - p[0]) + b * (p[2] - p[0]));
        std::uint8_t* texel = &atlas->rgb[(static_cast<std::size_t>(y) * side + x) * 3];
        for (int k = 0; k < 3; ++k) texel[k] = code(colour[k]);
      }
    }
  });
  TriangleMesh textured = mesh;
  textured.set_texture_mapping(std::move(mapping), "baked atlas");
  return textured;
}

Texture downsampled(const Texture& texture, int times) {
  Texture t = texture;
  for (int i = 0; i < times; ++i) {
    Texture half;
    half.width = std::max(1, t.width / 2), half.height = std::max(1, t.height / 2);
    half.source = t.source;
    half.rgb.resize(static_cast<std::size_t>(3) * half.width * half.height);
    for (int y = 0; y < half.height; ++y) {
      for (int x = 0; x < half.width; ++x) {
        for (int k = 0; k < 3; ++k) {
          double sum = 0;
          for (int dy = 0; dy < 2; ++dy) {
            for (int dx = 0; dx < 2; ++dx) {
              const int sx = std::min(2 * x + dx, t.width - 1), sy = std::min(2 * y + dy, t.height - 1);
              sum += t.rgb[(static_cast<std::size_t>(sy) * t.width + sx) * 3 + k];
            }
          }
          half.rgb[(static_cast<std::size_t>(y) * half.width + x) * 3 + k] = code(sum / 4);
        }
      }
    }
    t = std::move(half);
  }
  return t;
}

Texture quantised(const Texture& texture, int bits) {
  Texture t = texture;
  const double step = 255.0 / ((1 << bits) - 1);
  for (std::uint8_t& value : t.rgb) value = code(std::round(value / step) * step);
  return t;
}

std::vector<Colour> quantised(const std::vector<Colour>& colours, int bits) {
  const double step = 255.0 / ((1 << bits) - 1);
  std::vector<Colour> out;
  out.reserve(colours.size());
  for (const Colour& c : colours) {
    out.emplace_back(Colour(float(code(std::round(c.x() / step) * step)),
                            float(code(std::round(c.y() / step) * step)),
                            float(code(std::round(c.z() / step) * step))));
  }
  return out;
}

}  // namespace roving
