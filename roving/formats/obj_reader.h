// Internal: a strict, fast Wavefront OBJ reader (positions and faces only).
#pragma once

#include <string>

#include "roving/formats/mesh_io.h"

namespace roving {

// Reads `v` and `f` records (f with v, v/vt, v/vt/vn or v//vn corners, negative indices
// relative to the vertices read so far, polygons fan-triangulated); other records are skipped.
// Throws roving::Error "path:line: expected ..., found ..." on a malformed record.
LoadedMesh read_obj(const std::string& path);

}  // namespace roving
