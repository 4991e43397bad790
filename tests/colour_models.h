// Shared by the colour suites: coloured and textured planes whose colour is known in closed form,
// and textures made texel by texel.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "roving/core/texture.h"
#include "roving/core/triangle_mesh.h"

namespace roving::testing {

// width x height texels, each colour(column, row) (an Eigen::Vector3i of code values).
template <typename Pattern>
Texture make_texture(int width, int height, Pattern colour) {
  Texture t;
  t.width = width;
  t.height = height;
  t.source = "test texture";
  for (int row = 0; row < height; ++row) {
    for (int column = 0; column < width; ++column) {
      const Eigen::Vector3i c = colour(column, row);
      for (int k = 0; k < 3; ++k) t.rgb.push_back(static_cast<std::uint8_t>(c[k]));
    }
  }
  return t;
}

inline Texture checkerboard(int n) {
  return make_texture(n, n, [](int i, int j) {
    return (i + j) % 2 ? Eigen::Vector3i(255, 255, 255) : Eigen::Vector3i(i, j, 7);
  });
}

// A square grid of side 10 at height z, normal +z, coloured by the linear field
// (50 + 10 x', 20 + 10 y', 100) with x' = x - shift: TEST moved along x by `shift` in colour.
inline TriangleMesh gradient_plane(double z, double shift, int n = 21) {
  std::vector<Vec3> positions;
  std::vector<Colour> colours;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double x = 10.0 * i / (n - 1), y = 10.0 * j / (n - 1);
      positions.emplace_back(x, y, z);
      colours.emplace_back(static_cast<float>(50 + 10 * (x - shift)), static_cast<float>(20 + 10 * y),
                           100.0f);
    }
  }
  std::vector<Triangle> triangles;
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      triangles.push_back({a, b, d});
      triangles.push_back({a, d, c});
    }
  }
  TriangleMesh mesh(std::move(positions), std::move(triangles));
  mesh.set_vertex_colours(std::move(colours));
  return mesh;
}

// The square [0, 10]^2 at height z, normal +z, in two triangles, textured by `texture` across it
// from texel centre to texel centre (glTF's UVs: u with x, v down as y grows), so that bilinear
// filtering is linear across the whole square.
inline TriangleMesh textured_square(double z, std::shared_ptr<const Texture> texture,
                                    const Sampler& sampler = {}) {
  const double lo_u = 0.5 / texture->width, hi_u = 1 - lo_u, lo_v = 0.5 / texture->height, hi_v = 1 - lo_v;
  TriangleMesh mesh({Vec3(0, 0, z), Vec3(10, 0, z), Vec3(10, 10, z), Vec3(0, 10, z)}, {{0, 1, 2}, {0, 2, 3}});
  TextureMapping mapping;
  Material material;
  material.texture = std::move(texture);
  material.sampler = sampler;
  mapping.materials.push_back(material);
  mapping.face_material = {0, 0};
  const TexCoord corner[4] = {{lo_u, hi_v}, {hi_u, hi_v}, {hi_u, lo_v}, {lo_u, lo_v}};
  for (const Triangle& t : mesh.triangles()) {
    for (const int v : t) mapping.corner_uv.push_back(corner[v]);
  }
  mesh.set_texture_mapping(std::move(mapping));
  return mesh;
}

// A colour for face f, scattered by a hash so that neighbouring faces differ by many steps.
inline Eigen::Vector3i face_colour(std::size_t f) {
  std::uint64_t x = (f + 1) * 0x9E3779B97F4A7C15ull;
  x ^= x >> 29;
  x *= 0xBF58476D1CE4E5B9ull;
  x ^= x >> 32;
  return {int(x & 255), int((x >> 8) & 255), int((x >> 16) & 255)};
}

// `mesh` with a colour of its own on every face, by an atlas with one texel per face (its three
// corners at the texel's centre, nearest filtering): every vertex and edge a seam, as in a
// per-triangle atlas.
inline TriangleMesh with_a_texel_per_face(const TriangleMesh& mesh) {
  const auto faces = mesh.triangle_count();
  const int side = static_cast<int>(std::ceil(std::sqrt(double(faces))));
  TextureMapping mapping;
  Material material;
  material.texture = std::make_shared<Texture>(make_texture(
      side, side, [&](int column, int row) { return face_colour(std::size_t(row) * side + column); }));
  material.sampler.filter = Filter::Nearest;
  mapping.materials.push_back(material);
  mapping.face_material.assign(faces, 0);
  for (std::size_t f = 0; f < faces; ++f) {
    const TexCoord centre((double(f % side) + 0.5) / side, (double(f / side) + 0.5) / side);
    for (int c = 0; c < 3; ++c) mapping.corner_uv.push_back(centre);
  }
  TriangleMesh out = mesh;
  out.set_texture_mapping(std::move(mapping));
  return out;
}

// `mesh` as a triangle soup, each face with three vertices of its own (a glTF whose seam vertices
// are split) coloured with the face's colour: colours that differ per face at every vertex.
inline TriangleMesh soup_coloured_per_face(const TriangleMesh& mesh) {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  std::vector<Colour> colours;
  for (std::size_t f = 0; f < mesh.triangle_count(); ++f) {
    const Triangle& t = mesh.triangles()[f];
    const auto first = static_cast<int>(positions.size());
    for (int c = 0; c < 3; ++c) {
      positions.push_back(mesh.positions()[t[c]]);
      colours.push_back(face_colour(f).cast<float>());
    }
    triangles.push_back({first, first + 1, first + 2});
  }
  TriangleMesh out(std::move(positions), std::move(triangles));
  out.set_vertex_colours(std::move(colours));
  return out;
}

}  // namespace roving::testing
