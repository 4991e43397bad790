// Strict STL reader (binary and ASCII); corners with bit-identical coordinates become one vertex.
#pragma once

#include <string>

#include "roving/formats/meshes/mesh_io.h"

namespace roving {

// Throws roving::Error naming the file (and line, for ASCII) for a size that does not match
// the triangle count, a truncated or malformed record, or trailing data.
LoadedMesh read_stl(const std::string& path);

}  // namespace roving
