// 3MF meshes through assimp (Debian's libassimp): every object of the build with its item's
// transform applied, as one triangle mesh.
#pragma once

#include <string>

#include "roving/formats/meshes/mesh_io.h"

namespace roving {

// Throws roving::Error naming `path` when assimp refuses the file (with its reason), or when it
// holds no triangles; coordinates and indices are then checked as for every mesh.
LoadedMesh read_3mf(const std::string& path);

}  // namespace roving
