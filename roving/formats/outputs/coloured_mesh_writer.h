// Coloured meshes written so that their colour survives: OBJ with its MTL (Kd, map_Kd) and glTF
// 2.0 (.gltf, its buffer in a .bin beside it), each naming texture files the caller writes
// (write_texture). Together with the readers, the round trip keeps every colour the colour rule
// sees (tests/gltf_colour_test.cpp).
#pragma once

#include <string>
#include <vector>

#include "roving/core/triangle_mesh.h"

namespace roving {

// `texture_files[m]`: material m's texture file, relative to the model's folder (empty where it
// has none; one per material). Vertex colours go into `v x y z r g b` (fractions of 255);
// texture coordinates into `vt` (OBJ's v up); each material into the MTL `mtl_path` (beside the
// OBJ), Kd its factor, `-clamp on` for clamped textures. Throws roving::Error naming the file for
// what OBJ cannot say (mirrored repeat, nearest filtering, wrap modes that differ by axis) and on
// a write that fails; every file is whole or not written.
void write_coloured_obj(const TriangleMesh& mesh, const std::string& path, const std::string& mtl_path,
                        const std::vector<std::string>& texture_files);

// The same as glTF 2.0: one primitive per material, vertices split where a corner's texture
// coordinates differ; vertex colours as COLOR_0 and each factor as baseColorFactor, linear (the
// sRGB transfer function decodes the code values); textures by URI with their samplers. The
// buffer goes to the .gltf's name with .bin.
void write_coloured_gltf(const TriangleMesh& mesh, const std::string& path,
                         const std::vector<std::string>& texture_files);

}  // namespace roving
