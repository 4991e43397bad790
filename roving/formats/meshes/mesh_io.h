// Reading and writing triangle meshes (OBJ, PLY ASCII/binary, OFF, STL) through OpenMesh's readers.
#pragma once

#include <string>
#include <vector>

#include "roving/core/triangle_mesh.h"

namespace roving {

struct LoadedMesh {
  TriangleMesh mesh;
  std::string path;
  // Faces the file held that repeat a vertex (a, a, b): dropped, counted here.
  std::size_t dropped_repeated_vertex_faces = 0;
  // Polygons with more than three corners, fan-triangulated.
  std::size_t triangulated_polygons = 0;
  // What the reader measured without, each a line naming the file (an OBJ's missing .mtl).
  std::vector<std::string> warnings;
};

// Reads `path`, choosing the format by its extension (.obj .ply .off .stl, any case).
// Throws roving::Error, naming the file, when it is unreadable, of an unknown format, malformed or
// truncated (OpenMesh refuses it), refers to vertices that do not exist, holds NaN or infinite
// coordinates, or has no triangle of non-zero area.
LoadedMesh load_mesh(const std::string& path);

// Writes `mesh` by extension (.obj .ply .off .stl); binary PLY/STL when `binary`, a binary PLY with
// its vertex colours where it has them. Throws on failure.
void save_mesh(const TriangleMesh& mesh, const std::string& path, bool binary = true);

}  // namespace roving
