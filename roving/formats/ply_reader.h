// Strict PLY reader (ASCII, binary little- and big-endian): meshes and point clouds.
#pragma once

#include <string>
#include <vector>

#include "roving/formats/mesh_io.h"

namespace roving {

struct PlyContents {
  // Vertices (x, y, z) and the faces' triangles; with the vertices' colours where they declare
  // red, green and blue (alpha is ignored), taken as sRGB code values: uchar as stored, float or
  // double (0-1) times 255.
  LoadedMesh mesh;
  std::vector<Vec3> normals;  // nx, ny, nz per vertex when the header declares them
  bool declares_faces = false;
};

// Reads a whole PLY file. Every count in the header is checked against the bytes the file
// holds before anything is allocated; the body must match the header exactly (no missing,
// stray or trailing values). Throws roving::Error naming the file, the header line or element
// and what was expected and found.
PlyContents read_ply(const std::string& path);

// Reads only the header: true when it declares no face (or zero faces): a point cloud.
bool ply_declares_no_faces(const std::string& path);

}  // namespace roving
