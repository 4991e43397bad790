// Which files are read a block of faces at a time (triangle_stream.h).
#include "roving/formats/meshes/triangle_stream.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "roving/formats/meshes/obj_triangle_stream.h"
#include "roving/formats/meshes/ply_triangle_stream.h"
#include "roving/formats/meshes/stl_triangle_stream.h"

namespace roving {

std::unique_ptr<TriangleStream> open_triangle_stream(const std::string& path, std::size_t more_faces_than) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".ply") {
    const std::optional<PlyTriangleLayout> layout = ply_triangle_layout(path);
    if (!layout || layout->face_count <= more_faces_than) return nullptr;
    return std::make_unique<PlyTriangleStream>(path, *layout);
  }
  if (extension == ".obj") return ObjTriangleStream::open(path, more_faces_than);
  if (extension == ".stl") {
    const std::optional<std::size_t> facets = binary_stl_facets(path);
    if (!facets || *facets <= more_faces_than) return nullptr;
    return std::make_unique<StlTriangleStream>(path, *facets);
  }
  return nullptr;
}

}  // namespace roving
