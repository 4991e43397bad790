// Turns the polygons a reader finds into triangles: indices checked, repeated-vertex faces
// dropped and counted, larger polygons fan-triangulated and counted (as the OBJ reader does).
#pragma once

#include <fmt/format.h>

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "roving/core/error.h"
#include "roving/core/memory_budget.h"
#include "roving/formats/meshes/mesh_io.h"

namespace roving {

// Checks, before a reader allocates, that a mesh of the declared size fits in memory: its
// positions, triangles and the per-face and per-vertex data TriangleMesh derives.
inline void require_mesh_memory(const std::string& path, unsigned long long vertices,
                                unsigned long long faces) {
  require_memory(fmt::format("{}: reading", path), 49.0 * vertices + 44.0 * faces,
                 fmt::format("{} vertices and {} faces", vertices, faces));
}

class PolygonSink {
 public:
  PolygonSink(const std::string& path, std::size_t vertex_count, LoadedMesh& loaded)
      : path_(path), vertex_count_(vertex_count), loaded_(loaded) {
    if (vertex_count > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
      throw Error(fmt::format("{}: {} vertices; at most {} are supported", path, vertex_count,
                              std::numeric_limits<int>::max()));
    }
  }

  // Face `face` (0-based, for messages) with `corners` vertex indices as the file gave them.
  void add(const std::vector<long long>& corners, std::size_t face, std::vector<Triangle>& triangles) {
    if (corners.size() < 3) {
      throw Error(
          fmt::format("{}: face {} has {} corners; expected at least 3", path_, face, corners.size()));
    }
    for (const long long index : corners) {
      if (index < 0 || static_cast<unsigned long long>(index) >= vertex_count_) {
        throw Error(fmt::format("{}: face {} refers to vertex {}; expected an index in [0, {})", path_, face,
                                index, vertex_count_));
      }
    }
    for (std::size_t i = 0; i < corners.size(); ++i) {
      for (std::size_t j = i + 1; j < corners.size(); ++j) {
        if (corners[i] == corners[j]) {
          ++loaded_.dropped_repeated_vertex_faces;
          return;
        }
      }
    }
    if (corners.size() > 3) ++loaded_.triangulated_polygons;
    for (std::size_t i = 1; i + 1 < corners.size(); ++i) {
      triangles.push_back(
          {static_cast<int>(corners[0]), static_cast<int>(corners[i]), static_cast<int>(corners[i + 1])});
    }
  }

 private:
  const std::string& path_;
  std::size_t vertex_count_;
  LoadedMesh& loaded_;
};

}  // namespace roving
