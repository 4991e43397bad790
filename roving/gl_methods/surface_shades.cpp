// A test model's colour as the GL passes draw it.
#include "surface_shades.h"

#include <tbb/parallel_for.h>

#include <cmath>

#include "roving/core/geometry.h"

namespace roving {

SurfaceShades surface_shades(const TriangleMesh& mesh, ShadeRule rule) {
  SurfaceShades shades;
  const TextureMapping* mapping = mesh.texture_mapping();
  shades.materials = mapping ? mapping->materials : std::vector<Material>(1);
  if (rule == ShadeRule::AsMmetric) {
    for (Material& material : shades.materials) {
      material.sampler = Sampler{Wrap::ClampToEdge, Wrap::ClampToEdge, Filter::Linear};
      material.factor = Material{}.factor;
    }
  }
  if (shades.materials.size() > 1) {
    shades.face_materials.assign(mapping->face_material.begin(), mapping->face_material.end());
  }
  const std::vector<Colour>& vertex_colours = mesh.vertex_colours();
  shades.corners.resize(3 * mesh.triangle_count());
  tbb::parallel_for(std::size_t(0), mesh.triangle_count(), [&](std::size_t face) {
    const Material& material = shades.materials[mapping ? mapping->face_material[face] : 0];
    const bool textured = mapping && material.texture;
    const bool vertex_coloured = !vertex_colours.empty() && !(textured && rule == ShadeRule::AsMmetric);
    // A whole number of repeats (two of mirrored ones) off the coordinates changes no colour,
    // and keeps them small enough for float.
    TexCoord shift = TexCoord::Zero();
    if (textured) {
      const TexCoord* uv = &mapping->corner_uv[3 * face];
      const TexCoord lowest = uv[0].cwiseMin(uv[1]).cwiseMin(uv[2]);
      const Wrap wraps[2] = {material.sampler.wrap_s, material.sampler.wrap_t};
      for (int axis = 0; axis < 2; ++axis) {
        if (wraps[axis] == Wrap::Repeat) shift[axis] = std::floor(lowest[axis]);
        if (wraps[axis] == Wrap::MirroredRepeat) shift[axis] = 2 * std::floor(lowest[axis] / 2);
      }
    }
    for (int c = 0; c < 3; ++c) {
      const int v = mesh.triangles()[face][c];
      const Eigen::Vector3d factor =
          (vertex_coloured ? Eigen::Vector3d(vertex_colours[v].cast<double>() / 255)
                           : Eigen::Vector3d::Ones())
              .cwiseProduct(material.factor.cast<double>() / 255);
      const TexCoord uv = textured ? TexCoord(mapping->corner_uv[3 * face + c] - shift) : TexCoord::Zero();
      shades.corners[3 * face + c] = {float(factor.x()), float(factor.y()), float(factor.z()), float(uv.x()),
                                      float(uv.y())};
    }
  });
  return shades;
}

TileShade SurfaceShades::at(const TriangleMesh& mesh, std::uint32_t face, const Vec3& p) const {
  const Triangle& t = mesh.triangles()[face];
  const auto& positions = mesh.positions();
  const Vec3 w = closest_on_triangle(p, positions[t[0]], positions[t[1]], positions[t[2]]).weights;
  const TileShade* corner = &corners[3 * face];
  const auto mix = [&](float TileShade::*channel) {
    return float(w[0] * corner[0].*channel + w[1] * corner[1].*channel + w[2] * corner[2].*channel);
  };
  return {mix(&TileShade::r), mix(&TileShade::g), mix(&TileShade::b), mix(&TileShade::u), mix(&TileShade::v)};
}

}  // namespace roving
