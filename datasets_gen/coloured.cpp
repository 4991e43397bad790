// Procedural colour fields and textures for coloured versions of the real models.
#include "coloured.h"

#include <algorithm>
#include <cmath>

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

}  // namespace roving
