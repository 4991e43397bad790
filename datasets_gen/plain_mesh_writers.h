// Binary STL and OBJ written straight from a TriangleMesh, for the streaming benchmark's 10^8-
// triangle references in the formats a REF streams from: save_mesh writes these through OpenMesh,
// whose half-edge copy of such a mesh would not fit beside it.
#pragma once

#include <string>

#include "roving/core/triangle_mesh.h"

namespace roving {

// Each facet its normal (as the mesh computes it) and its three corners, in float; 0 attribute bytes.
void write_binary_stl(const TriangleMesh& mesh, const std::string& path);
// 'v' lines (each coordinate rounded to float, as the PLY and STL copies store it, printed in the
// fewest digits that read back as that float), then 'f' lines numbered from 1.
void write_plain_obj(const TriangleMesh& mesh, const std::string& path);

}  // namespace roving
