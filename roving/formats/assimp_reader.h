// glTF 2.0 (.gltf, .glb) and 3MF meshes through assimp (Debian's libassimp): every mesh of the
// scene with its node's transform applied, as one triangle mesh.
#pragma once

#include <string>

#include "roving/formats/mesh_io.h"

namespace roving {

// Throws roving::Error naming `path` when assimp refuses the file (with its reason), or when it
// holds no triangles; coordinates and indices are then checked as for every mesh.
LoadedMesh read_with_assimp(const std::string& path);

}  // namespace roving
