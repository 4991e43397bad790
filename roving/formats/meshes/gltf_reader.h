// glTF 2.0 (.gltf with data-URI or external buffers, and binary .glb): the triangles of every
// mesh a scene's nodes place, each node's transform applied. A strict reader of our own:
// Debian's assimp crashes and over-allocates on malformed glTF under fuzzing, and everything a
// file declares (chunk lengths, buffer sizes, accessor ranges, indices, the node graph) is
// checked here against what the file actually holds before it is used.
#pragma once

#include <string>

#include "roving/formats/meshes/mesh_io.h"

namespace roving {

// Throws roving::Error naming `path` and what was expected and found: malformed JSON or GLB
// framing, a buffer, view or accessor reaching past its data, an index out of range, a node
// cycle, a required extension (Draco, quantisation) or sparse accessor we do not read, NaN or
// infinite positions, or no triangles (points and lines are not surfaces).
LoadedMesh read_gltf(const std::string& path);

}  // namespace roving
