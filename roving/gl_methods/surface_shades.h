// Internal: a test model's colour as the GL passes draw it: each triangle corner's shade (its
// vertex colour times its material's factor, as fractions of 255, and its texture coordinates)
// and each triangle's material, whose texture the fragment multiplies in.
#pragma once

#include <cstdint>
#include <vector>

#include "roving/core/triangle_mesh.h"
#include "roving/gl/depth_renderer.h"

namespace roving {

struct SurfaceShades {
  std::vector<Material> materials;            // the mesh's, or one white untextured material
  std::vector<TileShade> corners;             // three a triangle
  std::vector<std::uint32_t> face_materials;  // empty: every triangle material 0

  std::uint32_t material_of(std::uint32_t face) const {
    return face_materials.empty() ? 0 : face_materials[face];
  }
  // The shade at the point of triangle `face` of `mesh` nearest p, interpolated as the
  // rasteriser interpolates it.
  TileShade at(const TriangleMesh& mesh, std::uint32_t face, const Vec3& p) const;
};

// How a model's colour is drawn: as its files declare it (each material's factor times its vertex
// colours and texture, sampled by its own sampler), or as MPEG's mmetric draws it (a textured face
// shows its texture alone, bilinear and clamped to the edge; any other face its vertex colours).
enum class ShadeRule { AsDeclared, AsMmetric };

// Requires mesh.has_colour().
SurfaceShades surface_shades(const TriangleMesh& mesh, ShadeRule rule = ShadeRule::AsDeclared);

}  // namespace roving
