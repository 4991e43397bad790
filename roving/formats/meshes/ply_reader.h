// Strict PLY reader (ASCII, binary little- and big-endian): meshes and point clouds.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "roving/core/point_cloud.h"
#include "roving/formats/meshes/mesh_io.h"

namespace roving {

struct PlyContents {
  // Vertices (x, y, z) and the faces' triangles; with the vertices' colours where they declare
  // red, green and blue (alpha is ignored), taken as sRGB code values: uchar as stored, float or
  // double (0-1) times 255.
  LoadedMesh mesh;
  std::vector<Vec3> normals;  // nx, ny, nz per vertex when the header declares them
  bool declares_faces = false;
  std::size_t non_finite_dropped = 0;  // vertices left out (read_ply's drop_non_finite_points)
};

// Reads a whole PLY file. Every count in the header is checked against the bytes the file
// holds before anything is allocated; the body must match the header exactly (no missing,
// stray or trailing values). Throws roving::Error naming the file, the header line or element
// and what was expected and found. With `drop_non_finite_points`, a file without faces (a point
// cloud) has its vertices with a NaN or infinite coordinate left out, and counted, instead.
PlyContents read_ply(const std::string& path, bool drop_non_finite_points = false);

// Reads only the header: true when it declares no face (or zero faces): a point cloud.
bool ply_declares_no_faces(const std::string& path);

// Whether the PLY `path` stores its vertices' colours as float or double (0-1, read scaled by 255),
// not as uchar: MPEG's pc_error reads colour only as uchar. Only the header is read.
bool ply_colours_are_floats(const std::string& path);

// Where a binary PLY of plain triangles keeps its vertices and faces, so that its faces can be
// read a block at a time (triangle_stream.h) rather than all at once.
struct PlyTriangleLayout {
  std::size_t vertex_count = 0, face_count = 0;
  std::uint64_t vertices_at = 0, faces_at = 0;  // byte offsets in the file
  std::size_t vertex_stride = 0;                // bytes per vertex
  std::size_t coordinate_offset[3] = {0, 0, 0};  // x, y, z within a vertex
  bool coordinates_double = false;               // else float
  bool indices_signed = false;                   // int32, else uint32
};

// The layout of `path` when it is a little-endian binary PLY whose elements are a vertex of
// fixed-size properties (x, y and z float or double; no colour) followed by a face of one list of
// a uchar count and 32-bit indices, and whose size is exactly that of its header with every face
// a triangle; nullopt for any other file (read it whole with read_ply). Only the header is read;
// its errors are read_ply's.
std::optional<PlyTriangleLayout> ply_triangle_layout(const std::string& path);

// The vertices of the PLY `bytes` (the file `path`) in place, when it is little-endian binary with
// one or more vertices of fixed-size properties (x, y, z float or double; nx, ny, nz all float or
// double or none; red, green, blue all uchar or none; any other scalar skipped), any other element
// empty, and its size exactly that of its header and vertices; nullopt for any other file
// (read_ply reads it, or names what is wrong). Only the header is parsed; its errors are read_ply's.
std::optional<PackedPointCloud> ply_packed_points(const std::string& path, std::string_view bytes);

}  // namespace roving
