// Strict, bounded OFF reader (ASCII with comments, and OFF BINARY). OpenMesh's reader
// reserved 13.8 GB for an 11-byte file, never size-checked its binary variant (a 63-byte file
// ran 22-28 s; a header alone gave an uninitialised index), and refused '#' comments.
#include "roving/formats/meshes/off_reader.h"

#include <fmt/format.h>

#include <cstring>
#include <optional>

#include "roving/formats/files/file_bytes.h"
#include "roving/formats/meshes/polygon_sink.h"
#include "roving/core/error.h"

namespace roving {
namespace {

// The header keyword's optional prefixes: [ST][C][N][4][n]OFF.
struct OffVariant {
  bool texture = false, colour = false, normal = false;
};

std::optional<OffVariant> parse_magic(std::string_view magic, const std::string& path) {
  if (magic.size() < 3 || magic.substr(magic.size() - 3) != "OFF") return std::nullopt;
  std::string_view prefix = magic.substr(0, magic.size() - 3);
  OffVariant variant;
  const auto take = [&](std::string_view p) {
    if (prefix.substr(0, p.size()) != p) return false;
    prefix.remove_prefix(p.size());
    return true;
  };
  variant.texture = take("ST");
  variant.colour = take("C");
  variant.normal = take("N");
  if (take("4") || take("n")) {
    throw Error(fmt::format("{}: '{}' is a 4D or n-dimensional OFF; expected 3D vertices", path, magic));
  }
  if (!prefix.empty()) return std::nullopt;
  return variant;
}

// Significant lines: blank lines and '#' comments (whole lines or line ends) are skipped.
class OffLines {
 public:
  OffLines(const std::string& path, std::string_view text) : path_(path), cursor_(text) {}
  bool next(std::string_view& line) {
    while (cursor_.next_line(line)) {
      line = line.substr(0, line.find('#'));
      if (line.find_first_not_of(" \t\r\f\v") != std::string_view::npos) return true;
    }
    return false;
  }
  std::string where() const { return fmt::format("{}:{}", path_, cursor_.line_number()); }
  std::size_t offset() const { return cursor_.offset(); }

 private:
  const std::string& path_;
  LineCursor cursor_;
};

void check_counts(const std::string& path, long long vertices, long long faces, std::size_t bytes,
                  std::size_t vertex_bytes, std::size_t face_bytes) {
  if (vertices < 0 || faces < 0) {
    throw Error(
        fmt::format("{}: expected vertex and face counts >= 0, found {} and {}", path, vertices, faces));
  }
  const auto v = static_cast<unsigned long long>(vertices), f = static_cast<unsigned long long>(faces);
  if (v > bytes / vertex_bytes || f > (bytes - v * vertex_bytes) / face_bytes) {
    throw Error(fmt::format(
        "{}: truncated or wrong counts: {} vertices and {} faces need at least {} and {} bytes each; the "
        "file holds {} bytes after the counts",
        path, vertices, faces, vertex_bytes, face_bytes, bytes));
  }
  require_mesh_memory(path, v, f);
}

LoadedMesh read_ascii(const std::string& path, std::string_view text, OffLines& lines, std::string_view rest,
                      const OffVariant& variant) {
  // The counts follow the keyword on its line, or on the next significant one.
  std::string_view line = rest, probe = rest;
  if (next_token(probe).empty() && !lines.next(line)) {
    throw Error(fmt::format("{}: truncated: expected the vertex and face counts after the header", path));
  }
  long long vertices = -1, faces = -1, edges = 0;
  const std::string_view v_text = next_token(line), f_text = next_token(line), e_text = next_token(line);
  if (!parse_number(v_text, vertices) || !parse_number(f_text, faces) ||
      (!e_text.empty() && !parse_number(e_text, edges)) || !next_token(line).empty()) {
    throw Error(fmt::format("{}: expected whole-number vertex and face counts 'V F [E]', found '{} {}'",
                            lines.where(), v_text, f_text));
  }
  // A vertex line holds at least "0 0 0\n", a face line "3 0 1 2\n".
  check_counts(path, vertices, faces, text.size() - lines.offset(), 6, 8);

  const std::size_t extra_columns = (variant.normal ? 3 : 0) + (variant.texture ? 2 : 0);
  LoadedMesh loaded;
  std::vector<Vec3> positions;
  positions.reserve(static_cast<std::size_t>(vertices));
  for (long long v = 0; v < vertices; ++v) {
    if (!lines.next(line)) {
      throw Error(fmt::format("{}: truncated: expected {} vertices, found {}", path, vertices, v));
    }
    Vec3 p;
    for (int axis = 0; axis < 3; ++axis) {
      const std::string_view token = next_token(line);
      if (!parse_number(token, p[axis])) {
        throw Error(
            fmt::format("{}: vertex {}: expected 3 numbers, found {}", lines.where(), v, quoted(token)));
      }
    }
    std::size_t extra = 0;
    for (std::string_view token = next_token(line); !token.empty(); token = next_token(line)) ++extra;
    // Colours are RGB or RGBA.
    if (extra != extra_columns &&
        !(variant.colour && (extra == extra_columns + 3 || extra == extra_columns + 4))) {
      throw Error(fmt::format("{}: vertex {}: expected {} values after the coordinates, found {}",
                              lines.where(), v, extra_columns, extra));
    }
    positions.push_back(p);
  }
  PolygonSink sink(path, positions.size(), loaded);
  std::vector<Triangle> triangles;
  triangles.reserve(static_cast<std::size_t>(faces));
  std::vector<long long> corners;
  for (long long f = 0; f < faces; ++f) {
    if (!lines.next(line))
      throw Error(fmt::format("{}: truncated: expected {} faces, found {}", path, faces, f));
    long long count = 0;
    const std::string_view count_text = next_token(line);
    if (!parse_number(count_text, count) || count < 0 || static_cast<std::size_t>(count) > line.size()) {
      throw Error(fmt::format("{}: face {}: expected a corner count, found {}", lines.where(), f,
                              quoted(count_text)));
    }
    corners.clear();
    for (long long c = 0; c < count; ++c) {
      const std::string_view token = next_token(line);
      long long index = 0;
      if (!parse_number(token, index)) {
        throw Error(fmt::format("{}: face {}: expected {} vertex indices, found {}", lines.where(), f, count,
                                quoted(token)));
      }
      corners.push_back(index);
    }
    std::size_t colour = 0;  // none, a colour-map index, RGB or RGBA
    for (std::string_view token = next_token(line); !token.empty(); token = next_token(line)) ++colour;
    if (colour == 2 || colour > 4) {
      throw Error(fmt::format("{}: face {}: expected 0, 1, 3 or 4 colour values after the indices, found {}",
                              lines.where(), f, colour));
    }
    sink.add(corners, static_cast<std::size_t>(f), triangles);
  }
  std::string_view trailing;
  if (lines.next(trailing)) {
    throw Error(fmt::format("{}: expected the end of the file after {} faces, found {}", lines.where(), faces,
                            quoted(next_token(trailing))));
  }
  loaded.path = path;
  loaded.mesh = TriangleMesh(std::move(positions), std::move(triangles), path);
  return loaded;
}

// OFF BINARY (Geomview): big-endian int32 counts, float32 coordinates, per face int32 corner
// count, indices, a colour count and that many float32 values.
class BigEndian {
 public:
  BigEndian(const std::string& path, std::string_view bytes) : path_(path), bytes_(bytes) {}
  std::uint32_t word(const char* what) {
    if (bytes_.size() - position_ < 4) {
      throw Error(fmt::format("{}: truncated: expected {} at byte {}, found the end of the file", path_, what,
                              position_));
    }
    unsigned char b[4];
    std::memcpy(b, bytes_.data() + position_, 4);
    position_ += 4;
    return std::uint32_t(b[0]) << 24 | std::uint32_t(b[1]) << 16 | std::uint32_t(b[2]) << 8 | b[3];
  }
  std::int32_t integer(const char* what) { return static_cast<std::int32_t>(word(what)); }
  float real(const char* what) {
    const std::uint32_t w = word(what);
    float f;
    std::memcpy(&f, &w, 4);
    return f;
  }
  std::size_t remaining() const { return bytes_.size() - position_; }

 private:
  const std::string& path_;
  std::string_view bytes_;
  std::size_t position_ = 0;
};

LoadedMesh read_binary(const std::string& path, std::string_view body, const OffVariant& variant) {
  if (variant.colour || variant.normal || variant.texture) {
    throw Error(
        fmt::format("{}: binary OFF with colours, normals or texture coordinates is not supported; "
                    "expected plain 'OFF BINARY'",
                    path));
  }
  BigEndian in(path, body);
  const long long vertices = in.integer("the vertex count"), faces = in.integer("the face count");
  in.integer("the edge count");
  // A vertex is 12 bytes; a face at least 20 (count, 3 indices, colour count).
  check_counts(path, vertices, faces, in.remaining(), 12, 20);
  LoadedMesh loaded;
  std::vector<Vec3> positions(static_cast<std::size_t>(vertices));
  for (Vec3& p : positions) {
    for (int axis = 0; axis < 3; ++axis) p[axis] = in.real("a vertex coordinate");
  }
  PolygonSink sink(path, positions.size(), loaded);
  std::vector<Triangle> triangles;
  triangles.reserve(static_cast<std::size_t>(faces));
  std::vector<long long> corners;
  for (long long f = 0; f < faces; ++f) {
    const long long count = in.integer("a face's corner count");
    if (count < 0 || static_cast<unsigned long long>(count) > in.remaining() / 4) {
      throw Error(fmt::format("{}: face {} declares {} corners; the file holds at most {} more values", path,
                              f, count, in.remaining() / 4));
    }
    corners.resize(static_cast<std::size_t>(count));
    for (long long& c : corners) c = in.integer("a vertex index");
    const long long colours = in.integer("a face's colour count");
    if (colours < 0 || colours > 4) {
      throw Error(
          fmt::format("{}: face {}: expected 0 to 4 colour values, found a count of {}", path, f, colours));
    }
    for (long long c = 0; c < colours; ++c) in.real("a colour value");
    sink.add(corners, static_cast<std::size_t>(f), triangles);
  }
  if (in.remaining() != 0) {
    throw Error(
        fmt::format("{}: {} bytes follow the last face; expected the end of the file", path, in.remaining()));
  }
  loaded.path = path;
  loaded.mesh = TriangleMesh(std::move(positions), std::move(triangles), path);
  return loaded;
}

}  // namespace

LoadedMesh read_off(const std::string& path) {
  const FileBytes file(path, "a .off mesh");
  const std::string_view text = file.bytes();
  OffLines lines(path, text);
  std::string_view line;
  if (!lines.next(line)) throw Error(fmt::format("{}: expected an OFF header, found only comments", path));
  const std::string_view magic = next_token(line);
  const auto variant = parse_magic(magic, path);
  if (!variant) {
    throw Error(
        fmt::format("{}: expected an OFF header ('OFF', 'COFF', 'NOFF'...), found {}", path, quoted(magic)));
  }
  std::string_view rest = line;
  if (next_token(rest) == "BINARY") {
    if (!next_token(rest).empty())
      throw Error(fmt::format("{}: expected a line break after 'OFF BINARY'", path));
    return read_binary(path, text.substr(lines.offset()), *variant);
  }
  return read_ascii(path, text, lines, line, *variant);
}

}  // namespace roving
