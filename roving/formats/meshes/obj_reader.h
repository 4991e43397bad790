// Internal: a strict, fast Wavefront OBJ reader: positions, faces, and what colours them.
#pragma once

#include <string>

#include "roving/formats/meshes/mesh_io.h"

namespace roving {

// Reads `v` and `f` records (f with v, v/vt, v/vt/vn or v//vn corners, negative indices
// relative to the records read so far, polygons fan-triangulated), and the colour: `v x y z r g b`
// vertex colours (fractions of [0, 1], as MeshLab writes them), `vt`, `mtllib` and `usemtl` with
// the MTL's Kd and map_Kd (mtl_reader.h). Other records are skipped.
// Throws roving::Error "path:line: expected ..., found ..." on a malformed record, and for colour
// that would be guessed: colours on only some vertices, faces without a material beside faces with
// one, a textured face without texture coordinates, an undefined material.
LoadedMesh read_obj(const std::string& path);

}  // namespace roving
