// Strict OFF reader: ASCII ([ST][C][N]OFF, '#' comments) and OFF BINARY.
#pragma once

#include <string>

#include "roving/formats/meshes/mesh_io.h"

namespace roving {

// Throws roving::Error naming the file (and line) for a bad header, counts the file cannot
// hold, a truncated or malformed record, stray values, a bad index or trailing data.
LoadedMesh read_off(const std::string& path);

}  // namespace roving
