// An OBJ's records, parsed alike by both readers (obj_records.h).
#include "roving/formats/meshes/obj_records.h"

#include <fmt/format.h>

#include <cmath>


namespace roving::obj {
namespace {

// A 1-based or negative (relative) OBJ index resolved against `count` records so far; -1 when out of range.
long long resolve_index(long long index, long long count) {
  const long long resolved = index > 0 ? index - 1 : count + index;
  return index == 0 || resolved < 0 || resolved >= count ? -1 : resolved;
}

}  // namespace

Fail line_error(const std::string& path, const LineCursor& lines, std::size_t lines_before) {
  return [&path, &lines, lines_before](const std::string& what) {
    return Error(fmt::format("{}:{}: {}", path, lines_before + lines.line_number(), what));
  };
}

bool parse_vertex(std::string_view rest, Vec3& position, double rgb[3], const Fail& fail) {
  double xyz[3];
  for (double& coordinate : xyz) {
    const std::string_view token = next_token(rest);
    if (!parse_number(token, coordinate)) {
      throw fail(fmt::format("expected 3 numbers after 'v', found {}", quoted(token)));
    }
  }
  position = Vec3(xyz[0], xyz[1], xyz[2]);
  int given = 0;
  for (std::string_view token = next_token(rest); !token.empty() && given < 4; token = next_token(rest)) {
    if (given < 3 && !parse_number(token, rgb[given])) break;
    ++given;
  }
  return given == 3;
}

void parse_texture_coordinate(std::string_view rest, double uv[2], const Fail& fail) {
  for (int i = 0; i < 2; ++i) {
    const std::string_view token = next_token(rest);
    if (!parse_number(token, uv[i]) || !std::isfinite(uv[i])) {
      throw fail(fmt::format("expected 2 finite numbers after 'vt', found {}", quoted(token)));
    }
  }
}

void parse_face(std::string_view rest, long long vertices, long long texture_coordinates, std::vector<int>& corners,
                std::vector<int>& corner_uv, const Fail& fail) {
  corners.clear();
  corner_uv.clear();
  for (std::string_view token = next_token(rest); !token.empty(); token = next_token(rest)) {
    // v, v/vt, v/vt/vn or v//vn.
    const std::size_t slash = token.find('/');
    const std::string_view index_text = token.substr(0, slash);
    long long index = 0;
    if (!parse_number(index_text, index)) {
      throw fail(fmt::format("expected a vertex index in 'f', found '{}'", token));
    }
    const long long resolved = resolve_index(index, vertices);
    if (resolved < 0) {
      throw fail(fmt::format("face refers to vertex {}; expected 1..{} or -1..-{} (vertices defined so far)", index,
                             vertices, vertices));
    }
    corners.push_back(static_cast<int>(resolved));
    long long uv = -1;
    if (slash != std::string_view::npos) {
      const std::string_view after = token.substr(slash + 1);
      const std::string_view uv_text = after.substr(0, after.find('/'));
      if (!uv_text.empty() && (!parse_number(uv_text, index) || (uv = resolve_index(index, texture_coordinates)) < 0)) {
        throw fail(fmt::format("face refers to texture coordinate {}; expected 1..{} or -1..-{} ('vt' defined so far)",
                               quoted(uv_text), texture_coordinates, texture_coordinates));
      }
    }
    corner_uv.push_back(static_cast<int>(uv));
  }
  if (corners.size() < 3) throw fail(fmt::format("expected at least 3 corners in 'f', found {}", corners.size()));
}

bool repeats_a_vertex(const std::vector<int>& corners) {
  for (std::size_t i = 0; i < corners.size(); ++i) {
    for (std::size_t j = i + 1; j < corners.size(); ++j) {
      if (corners[i] == corners[j]) return true;
    }
  }
  return false;
}

}  // namespace roving::obj
