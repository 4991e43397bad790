// Strict Wavefront OBJ reader. OpenMesh's reader parses through iostreams (87% of a bunny load:
// 0.15 s of a 0.25 s budget) and skips malformed records without a word; this one parses with
// std::from_chars and names the line of the first bad record.
#include "obj_reader.h"

#include <fmt/format.h>

#include <string_view>

#include "file_bytes.h"
#include "roving/core/error.h"

namespace roving {
LoadedMesh read_obj(const std::string& path) {
  const FileBytes file(path, "a .obj mesh");
  const std::string_view text = file.bytes();

  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  LoadedMesh loaded;
  std::vector<int> corners;
  std::size_t line_number = 0;
  std::size_t position = 0;
  while (position < text.size()) {
    std::size_t end = text.find('\n', position);
    if (end == std::string::npos) end = text.size();
    std::string_view rest(text.data() + position, end - position);
    position = end + 1;
    ++line_number;
    const auto fail = [&](const std::string& what) {
      return Error(fmt::format("{}:{}: {}", path, line_number, what));
    };

    const std::string_view keyword = next_token(rest);
    if (keyword == "v") {
      double xyz[3];
      for (double& coordinate : xyz) {
        const std::string_view token = next_token(rest);
        if (!parse_number(token, coordinate)) {
          throw fail(fmt::format("expected 3 numbers after 'v', found {}", quoted(token)));
        }
      }
      positions.emplace_back(xyz[0], xyz[1], xyz[2]);
    } else if (keyword == "f") {
      corners.clear();
      for (std::string_view token = next_token(rest); !token.empty(); token = next_token(rest)) {
        // The vertex index is what precedes the first '/', if any.
        const std::string_view index_text = token.substr(0, token.find('/'));
        long long index = 0;
        if (!parse_number(index_text, index)) {
          throw fail(fmt::format("expected a vertex index in 'f', found '{}'", token));
        }
        const long long count = static_cast<long long>(positions.size());
        const long long resolved = index > 0 ? index - 1 : count + index;  // 1-based; negative: relative
        if (index == 0 || resolved < 0 || resolved >= count) {
          throw fail(
              fmt::format("face refers to vertex {}; expected 1..{} or -1..-{} (vertices "
                          "defined so far)",
                          index, count, count));
        }
        corners.push_back(static_cast<int>(resolved));
      }
      if (corners.size() < 3) {
        throw fail(fmt::format("expected at least 3 corners in 'f', found {}", corners.size()));
      }
      bool repeated = false;
      for (std::size_t i = 0; i < corners.size() && !repeated; ++i) {
        for (std::size_t j = i + 1; j < corners.size(); ++j) repeated |= corners[i] == corners[j];
      }
      if (repeated) {
        ++loaded.dropped_repeated_vertex_faces;
        continue;
      }
      if (corners.size() > 3) ++loaded.triangulated_polygons;
      for (std::size_t i = 1; i + 1 < corners.size(); ++i) {
        triangles.push_back({corners[0], corners[i], corners[i + 1]});
      }
    }
    // Everything else (vn, vt, g, o, s, usemtl, mtllib, l, #...) carries no geometry we use.
  }
  loaded.path = path;
  loaded.mesh = TriangleMesh(std::move(positions), std::move(triangles), path);
  return loaded;
}

}  // namespace roving
