// Binary STL and OBJ written straight from a TriangleMesh (plain_mesh_writers.h).
#include "plain_mesh_writers.h"

#include <fmt/format.h>

#include <cstdint>
#include <cstring>

#include "roving/core/error.h"
#include "roving/formats/files/atomic_file.h"

namespace roving {

void write_binary_stl(const TriangleMesh& mesh, const std::string& path) {
  if (mesh.triangle_count() > UINT32_MAX) {
    throw Error(fmt::format("{}: {} triangles do not fit binary STL's 32-bit count", path, mesh.triangle_count()));
  }
  AtomicFile out(path);
  std::FILE* file = out.stream();
  char header[80] = "binary STL written by roving-datasets";
  std::fwrite(header, sizeof header, 1, file);
  const auto count = static_cast<std::uint32_t>(mesh.triangle_count());
  std::fwrite(&count, sizeof count, 1, file);  // x86 and ARM: little-endian already
  const auto& positions = mesh.positions();
  const auto& triangles = mesh.triangles();
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const Vec3 n = mesh.face_normal(f);
    const Vec3 &a = positions[triangles[f][0]], &b = positions[triangles[f][1]], &c = positions[triangles[f][2]];
    const float values[12] = {float(n.x()), float(n.y()), float(n.z()), float(a.x()), float(a.y()), float(a.z()),
                              float(b.x()), float(b.y()), float(b.z()), float(c.x()), float(c.y()), float(c.z())};
    char record[50] = {};
    std::memcpy(record, values, sizeof values);
    std::fwrite(record, sizeof record, 1, file);
  }
  out.commit();
}

void write_plain_obj(const TriangleMesh& mesh, const std::string& path) {
  AtomicFile out(path);
  std::FILE* file = out.stream();
  fmt::print(file, "# written by roving-datasets: {} vertices, {} triangles\n", mesh.vertex_count(),
             mesh.triangle_count());
  fmt::memory_buffer lines;  // printed a few thousand lines at a time
  const auto flush = [&](bool always) {
    if (!always && lines.size() < (std::size_t{1} << 20)) return;
    std::fwrite(lines.data(), 1, lines.size(), file);
    lines.clear();
  };
  for (const Vec3& p : mesh.positions()) {
    fmt::format_to(std::back_inserter(lines), "v {} {} {}\n", float(p.x()), float(p.y()), float(p.z()));
    flush(false);
  }
  for (const Triangle& t : mesh.triangles()) {
    fmt::format_to(std::back_inserter(lines), "f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
    flush(false);
  }
  flush(true);
  out.commit();
}

}  // namespace roving
