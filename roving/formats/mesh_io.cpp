// Mesh files through OpenMesh's readers and writers, with the checks OpenMesh leaves to its caller.
#include "roving/formats/mesh_io.h"

#include <fmt/format.h>

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/IO/importer/ImporterT.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <algorithm>
#include <cctype>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

#include "mesh_header_check.h"
#include "obj_reader.h"
#include "roving/core/error.h"

namespace roving {
namespace {

struct DoubleTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
};
using OpenMeshTriangles = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;

// OpenMesh's importer drops faces with an out-of-range or repeated vertex and only logs it; we
// count them so that a bad index becomes an error and a repeated vertex a reported drop.
class CheckingImporter : public OpenMesh::IO::ImporterT<OpenMeshTriangles> {
 public:
  using ImporterT::ImporterT;

  OpenMesh::FaceHandle add_face(const VHandles& indices) override {
    const int vertex_count = static_cast<int>(n_vertices());
    for (const auto& vh : indices) {
      if (vh.idx() < 0 || vh.idx() >= vertex_count) {
        if (!bad_index) bad_index = BadIndex{face_count, vh.idx(), vertex_count};
        ++face_count;
        return OpenMesh::FaceHandle();
      }
    }
    for (std::size_t i = 0; i < indices.size(); ++i) {
      for (std::size_t j = i + 1; j < indices.size(); ++j) {
        if (indices[i] == indices[j]) {
          ++repeated_vertex_faces;
          ++face_count;
          return OpenMesh::FaceHandle();
        }
      }
    }
    if (indices.size() > 3) ++polygons;
    ++face_count;
    return ImporterT::add_face(indices);
  }

  struct BadIndex {
    std::size_t face;
    int index;
    int vertex_count;
  };
  std::optional<BadIndex> bad_index;
  std::size_t face_count = 0;
  std::size_t repeated_vertex_faces = 0;
  std::size_t polygons = 0;
};

// Routes OpenMesh's error log into a string for the duration of a read, so that its diagnosis
// ends up in our message instead of on the library user's stderr.
class CapturedOpenMeshLog {
 public:
  CapturedOpenMeshLog() {
    omerr().disconnect(std::cerr);
    omerr().connect(text_);
    omlog().disable();
    omout().disable();
  }
  ~CapturedOpenMeshLog() {
    omerr().flush();
    omerr().disconnect(text_);
    omerr().connect(std::cerr);
    omlog().enable();
    omout().enable();
  }
  std::string text() {
    omerr().flush();
    std::string s = text_.str();
    s.erase(std::remove(s.begin(), s.end(), '\n'), s.end());
    return s;
  }

 private:
  std::ostringstream text_;
};

std::string lower_extension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  const auto slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

void require_known_format(const std::string& path, const std::string& ext) {
  static const char* const known[] = {"obj", "ply", "off", "stl"};
  if (std::find(std::begin(known), std::end(known), ext) == std::end(known)) {
    throw Error(fmt::format("{}: unknown mesh format '{}'; expected .obj, .ply, .off or .stl", path,
                            ext.empty() ? "(no extension)" : "." + ext));
  }
}

LoadedMesh read_with_openmesh(const std::string& path, const std::string& ext) {
  check_mesh_header(path, ext);
  OpenMeshTriangles om;
  CheckingImporter importer(om);
  OpenMesh::IO::Options options;
  bool ok = false;
  std::string log;
  {
    CapturedOpenMeshLog capture;
    ok = OpenMesh::IO::IOManager().read(path, importer, options);
    log = capture.text();
  }
  if (!ok) {
    throw Error(fmt::format("{}: not a readable .{} mesh (OpenMesh: {})", path, ext,
                            log.empty() ? "reader failed" : log));
  }
  if (importer.bad_index) {
    const auto& bad = *importer.bad_index;
    throw Error(fmt::format("{}: face {} refers to vertex {}; expected an index in [0, {})", path, bad.face,
                            bad.index, bad.vertex_count));
  }

  std::vector<Vec3> positions(om.n_vertices());
  for (const auto vh : om.vertices()) {
    const auto& p = om.point(vh);
    positions[vh.idx()] = Vec3(p[0], p[1], p[2]);
  }
  std::vector<Triangle> triangles;
  triangles.reserve(om.n_faces());
  for (const auto fh : om.faces()) {
    Triangle t{};
    int corner = 0;
    for (const auto vh : om.fv_range(fh)) t[corner++] = vh.idx();
    triangles.push_back(t);
  }

  LoadedMesh loaded;
  loaded.path = path;
  loaded.dropped_repeated_vertex_faces = importer.repeated_vertex_faces;
  loaded.triangulated_polygons = importer.polygons;
  loaded.mesh = TriangleMesh(std::move(positions), std::move(triangles), path);
  return loaded;
}

}  // namespace

LoadedMesh load_mesh(const std::string& path) {
  const std::string ext = lower_extension(path);
  require_known_format(path, ext);
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) throw Error(fmt::format("{}: cannot open for reading", path));
    if (probe.peek() == std::ifstream::traits_type::eof()) {
      throw Error(fmt::format("{}: file is empty; expected a .{} mesh", path, ext));
    }
  }

  LoadedMesh loaded = ext == "obj" ? read_obj(path) : read_with_openmesh(path, ext);
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

void save_mesh(const TriangleMesh& mesh, const std::string& path, bool binary) {
  const std::string ext = lower_extension(path);
  require_known_format(path, ext);
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
  OpenMesh::IO::Options options;
  if (binary && (ext == "ply" || ext == "stl")) options += OpenMesh::IO::Options::Binary;
  std::string log;
  bool ok = false;
  {
    CapturedOpenMeshLog capture;
    ok = OpenMesh::IO::write_mesh(om, path, options, 17);
    log = capture.text();
  }
  if (!ok) throw Error(fmt::format("{}: cannot write ({})", path, log.empty() ? "writer failed" : log));
}

}  // namespace roving
