// Mesh files: our own strict readers (OBJ, PLY, OFF, STL) and OpenMesh's writers.
#include "roving/formats/meshes/mesh_io.h"

#include <fmt/format.h>

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iostream>
#include <mutex>
#include <optional>
#include <sstream>

#include "roving/formats/meshes/obj_reader.h"
#include "roving/formats/meshes/three_mf_reader.h"
#include "roving/formats/meshes/gltf_reader.h"
#include "roving/formats/meshes/off_reader.h"
#include "roving/formats/meshes/ply_reader.h"
#include "roving/core/error.h"
#include "roving/formats/files/atomic_file.h"
#include "roving/formats/files/file_bytes.h"
#include "roving/formats/meshes/stl_reader.h"

namespace roving {
namespace {

struct DoubleTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
};
using OpenMeshTriangles = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;

// Routes OpenMesh's error log into a string for the duration of a write, so that its diagnosis
// ends up in our message instead of on the library user's stderr. OpenMesh's log keeps every
// target it is given and never frees it, so one stream is connected once, for the process.
class CapturedOpenMeshLog {
 public:
  CapturedOpenMeshLog() : lock_(mutex()) {
    static const bool connected = [] {
      omerr().disconnect(std::cerr);
      omerr().connect(stream());
      return true;
    }();
    (void)connected;
    stream().str("");
    omlog().disable();
    omout().disable();
  }
  ~CapturedOpenMeshLog() {
    omerr().flush();
    omlog().enable();
    omout().enable();
  }
  std::string text() {
    omerr().flush();
    std::string s = stream().str();
    s.erase(std::remove(s.begin(), s.end(), '\n'), s.end());
    return s;
  }

 private:
  static std::ostringstream& stream() {
    static std::ostringstream text;
    return text;
  }
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  std::lock_guard<std::mutex> lock_;
};

std::string lower_extension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  const auto slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// `reading`: the formats read (also glTF and 3MF), else those written.
void require_known_format(const std::string& path, const std::string& ext, bool reading = false) {
  static const char* const known[] = {"obj", "ply", "off", "stl"};
  if (std::find(std::begin(known), std::end(known), ext) == std::end(known)) {
    throw Error(fmt::format("{}: unknown mesh format '{}'; expected .obj, .ply, .off{}", path,
                            ext.empty() ? "(no extension)" : "." + ext,
                            reading ? ", .stl, .gltf, .glb or .3mf" : " or .stl"));
  }
}

}  // namespace

LoadedMesh load_mesh(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext != "gltf" && ext != "glb" && ext != "3mf") require_known_format(path, ext, true);
  require_regular_file(path, "a ." + ext + " mesh");  // a FIFO or device would block the reader
  LoadedMesh loaded;
  if (ext == "obj") loaded = read_obj(path);
  if (ext == "ply") loaded = std::move(read_ply(path).mesh);
  if (ext == "off") loaded = read_off(path);
  if (ext == "stl") loaded = read_stl(path);
  if (ext == "gltf" || ext == "glb") loaded = read_gltf(path);
  if (ext == "3mf") loaded = read_3mf(path);
  const TriangleMesh& mesh = loaded.mesh;
  if (mesh.triangle_count() == 0) {
    throw Error(
        fmt::format("{}: no faces found ({} vertices); expected a triangle mesh", path, mesh.vertex_count()));
  }
  if (mesh.degenerate_triangle_count() == mesh.triangle_count()) {
    throw Error(
        fmt::format("{}: all {} triangles have zero area; expected a surface", path, mesh.triangle_count()));
  }
  return loaded;
}

namespace {

// Binary little-endian PLY, float coordinates: written directly, as OpenMesh would need a
// half-edge mesh (gigabytes at 10 million triangles) to write the same bytes.
void write_binary_ply(const TriangleMesh& mesh, const std::string& path) {
  AtomicFile out(path);
  std::FILE* file = out.stream();
  // Vertex colours as MeshLab writes them (uchar) where they are whole code values, else as
  // fractions of [0, 1] in float.
  const std::vector<Colour>& colours = mesh.vertex_colours();
  const bool whole = std::all_of(colours.begin(), colours.end(),
                                 [](const Colour& c) { return c == c.array().round().matrix(); });
  const char* colour_type = colours.empty() ? nullptr : whole ? "uchar" : "float";
  fmt::print(file,
             "ply\nformat binary_little_endian 1.0\nelement vertex {}\nproperty float x\nproperty float y\n"
             "property float z\n",
             mesh.vertex_count());
  if (colour_type) fmt::print(file, "property {0} red\nproperty {0} green\nproperty {0} blue\n", colour_type);
  fmt::print(file, "element face {}\nproperty list uchar int vertex_indices\nend_header\n",
             mesh.triangle_count());
  static_assert(sizeof(float) == 4 && sizeof(std::int32_t) == 4);
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const Vec3& p = mesh.positions()[v];
    const float xyz[3] = {float(p.x()), float(p.y()), float(p.z())};
    std::fwrite(xyz, sizeof xyz, 1, file);
    if (!colour_type) continue;
    if (whole) {
      const unsigned char rgb[3] = {static_cast<unsigned char>(colours[v].x()),
                                    static_cast<unsigned char>(colours[v].y()),
                                    static_cast<unsigned char>(colours[v].z())};
      std::fwrite(rgb, sizeof rgb, 1, file);
    } else {
      const float rgb[3] = {colours[v].x() / 255, colours[v].y() / 255, colours[v].z() / 255};
      std::fwrite(rgb, sizeof rgb, 1, file);
    }
  }
  for (const Triangle& t : mesh.triangles()) {
    unsigned char record[13] = {3};
    const std::int32_t corners[3] = {t[0], t[1], t[2]};
    std::memcpy(record + 1, corners, sizeof corners);  // x86 and ARM: little-endian already
    std::fwrite(record, sizeof record, 1, file);
  }
  out.commit();
}

}  // namespace

void save_mesh(const TriangleMesh& mesh, const std::string& path, bool binary) {
  const std::string ext = lower_extension(path);
  require_known_format(path, ext);
  if (binary && ext == "ply") {
    write_binary_ply(mesh, path);
    return;
  }
  OpenMeshTriangles om;
  for (const Vec3& p : mesh.positions()) om.add_vertex(OpenMesh::Vec3d(p.x(), p.y(), p.z()));
  // Built face by face without the manifold check: a soup writes out as it came in.
  for (const Triangle& t : mesh.triangles()) {
    om.add_face(OpenMesh::VertexHandle(t[0]), OpenMesh::VertexHandle(t[1]), OpenMesh::VertexHandle(t[2]));
  }
  if (om.n_faces() != mesh.triangle_count()) {
    throw Error(
        fmt::format("{}: cannot write a non-manifold mesh through OpenMesh ({} of {} "
                    "faces accepted)",
                    path, om.n_faces(), mesh.triangle_count()));
  }
  // OpenMesh writes by path: into the temporary file, which keeps the extension.
  AtomicFile out(path);
  out.close_stream();
  OpenMesh::IO::Options options;
  if (binary && (ext == "ply" || ext == "stl")) options += OpenMesh::IO::Options::Binary;
  std::string log;
  bool ok = false;
  {
    CapturedOpenMeshLog capture;
    ok = OpenMesh::IO::write_mesh(om, out.temporary_path(), options, 17);
    log = capture.text();
  }
  if (!ok) throw Error(fmt::format("{}: cannot write ({})", path, log.empty() ? "writer failed" : log));
  out.commit();
}

}  // namespace roving
