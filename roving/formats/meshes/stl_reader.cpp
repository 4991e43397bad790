// Strict STL reader. OpenMesh's accepted a truncated ASCII file (3 of 4 facets) and merged
// vertices through a std::map; here a binary file's size must match its count exactly, an ASCII
// file must close every facet and solid, and corners merge through a hash of their bits.
#include "roving/formats/meshes/stl_reader.h"

#include <fmt/format.h>

#include <cstring>
#include <unordered_map>

#include "roving/formats/files/file_bytes.h"
#include "roving/formats/meshes/polygon_sink.h"
#include "roving/core/error.h"

namespace roving {
namespace {

// Corners with bit-identical coordinates share one vertex (STL stores each facet's corners).
class VertexMerger {
 public:
  explicit VertexMerger(std::size_t expected_corners) { index_.reserve(expected_corners / 4 + 16); }
  int add(const Vec3& p) {
    Key key;
    std::memcpy(key.bits, p.data(), sizeof key.bits);
    const auto [it, added] = index_.try_emplace(key, static_cast<int>(positions.size()));
    if (added) positions.push_back(p);
    return it->second;
  }
  std::vector<Vec3> positions;

 private:
  struct Key {
    std::uint64_t bits[3];
    bool operator==(const Key& o) const { return std::memcmp(bits, o.bits, sizeof bits) == 0; }
  };
  struct Hash {
    std::size_t operator()(const Key& k) const {
      std::uint64_t h = k.bits[0] * 0x9E3779B97F4A7C15ull;
      h = (h ^ (h >> 29) ^ k.bits[1]) * 0xBF58476D1CE4E5B9ull;
      h = (h ^ (h >> 32) ^ k.bits[2]) * 0x94D049BB133111EBull;
      return static_cast<std::size_t>(h ^ (h >> 31));
    }
  };
  std::unordered_map<Key, int, Hash> index_;
};

LoadedMesh finish(const std::string& path, VertexMerger& merger, std::vector<Triangle>& triangles,
                  std::size_t repeated) {
  LoadedMesh loaded;
  loaded.path = path;
  loaded.dropped_repeated_vertex_faces = repeated;
  loaded.mesh = TriangleMesh(std::move(merger.positions), std::move(triangles), path);
  return loaded;
}

LoadedMesh read_binary(const std::string& path, std::string_view bytes, std::uint32_t count) {
  require_mesh_memory(path, count / 2, count);  // closed meshes have half as many vertices
  VertexMerger merger(3ull * count);
  std::vector<Triangle> triangles;
  triangles.reserve(count);
  std::size_t repeated = 0;
  for (std::uint32_t f = 0; f < count; ++f) {
    const char* record = bytes.data() + 84 + 50ull * f;
    Triangle t;
    for (int c = 0; c < 3; ++c) {
      float xyz[3];
      std::memcpy(xyz, record + 12 + 12 * c, 12);  // after the facet normal; little-endian
      t[c] = merger.add(Vec3(xyz[0], xyz[1], xyz[2]));
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      ++repeated;
      continue;
    }
    triangles.push_back(t);
  }
  return finish(path, merger, triangles, repeated);
}

// ASCII: solid NAME, then facets "facet normal nx ny nz / outer loop / vertex x y z (3 or more)
// / endloop / endfacet", then "endsolid [NAME]"; several solids may follow each other.
class AsciiStl {
 public:
  AsciiStl(const std::string& path, std::string_view text) : path_(path), cursor_(text) {}

  LoadedMesh read() {
    VertexMerger merger(cursor_.at_end() ? 0 : 1024);
    std::vector<Triangle> triangles;
    std::vector<int> corners;
    std::size_t repeated = 0, solids = 0;
    for (std::string_view keyword = token(); !keyword.empty(); keyword = token()) {
      if (keyword != "solid") throw fail(solids ? "'solid' or the end of the file" : "'solid'", keyword);
      ++solids;
      rest_ = {};  // the solid's name runs to the end of its line
      for (keyword = require("'facet' or 'endsolid'"); keyword != "endsolid";
           keyword = require("'facet' or 'endsolid'")) {
        if (keyword != "facet") throw fail("'facet' or 'endsolid'", keyword);
        expect("normal");
        for (int axis = 0; axis < 3; ++axis) number();
        expect("outer");
        expect("loop");
        corners.clear();
        for (keyword = require("'vertex' or 'endloop'"); keyword == "vertex";
             keyword = require("'vertex' or 'endloop'")) {
          Vec3 p;
          for (int axis = 0; axis < 3; ++axis) p[axis] = number();
          corners.push_back(merger.add(p));
        }
        if (keyword != "endloop") throw fail("'vertex' or 'endloop'", keyword);
        if (corners.size() < 3)
          throw fail_at(fmt::format("a facet with at least 3 vertices, found {}", corners.size()));
        expect("endfacet");
        bool has_repeat = false;
        for (std::size_t i = 0; i < corners.size(); ++i)
          for (std::size_t j = i + 1; j < corners.size(); ++j) has_repeat |= corners[i] == corners[j];
        if (has_repeat) {
          ++repeated;
          continue;
        }
        for (std::size_t i = 1; i + 1 < corners.size(); ++i)
          triangles.push_back({corners[0], corners[i], corners[i + 1]});
      }
      rest_ = {};  // "endsolid NAME"
    }
    if (solids == 0) throw Error(fmt::format("{}: expected 'solid', found only white space", path_));
    return finish(path_, merger, triangles, repeated);
  }

 private:
  // The next token, crossing lines; empty at the end of the file.
  std::string_view token() {
    for (;;) {
      const std::string_view t = next_token(rest_);
      if (!t.empty()) return t;
      if (!cursor_.next_line(rest_)) return {};
    }
  }
  std::string_view require(const char* expected) {
    const std::string_view t = token();
    if (t.empty())
      throw Error(fmt::format("{}: truncated: expected {}, found the end of the file", path_, expected));
    return t;
  }
  void expect(const char* word) {
    const std::string_view t = require(fmt::format("'{}'", word).c_str());
    if (t != word) throw fail(fmt::format("'{}'", word), t);
  }
  double number() {
    const std::string_view t = require("a number");
    double value = 0;
    if (!parse_number(t, value)) throw fail("a number", t);
    return value;
  }
  Error fail(const std::string& expected, std::string_view found) const {
    return Error(
        fmt::format("{}:{}: expected {}, found {}", path_, cursor_.line_number(), expected, quoted(found)));
  }
  Error fail_at(const std::string& expected) const {
    return Error(fmt::format("{}:{}: expected {}", path_, cursor_.line_number(), expected));
  }

  const std::string& path_;
  LineCursor cursor_;
  std::string_view rest_;
};

}  // namespace

LoadedMesh read_stl(const std::string& path) {
  const FileBytes file(path, "a .stl mesh");
  const std::string_view bytes = file.bytes();
  const bool starts_solid = bytes.substr(0, 5) == "solid";
  if (bytes.size() >= 84) {
    std::uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    const unsigned long long expected = 84 + 50ull * count;
    // A binary file's comment may begin with "solid" too: the exact size tells them apart.
    if (expected == bytes.size()) return read_binary(path, bytes, count);
    if (!starts_solid) {
      throw Error(fmt::format(
          "{}: {}: the binary STL header promises {} triangles ({} bytes), found {} bytes", path,
          expected > bytes.size() ? "truncated" : "trailing data", count, expected, bytes.size()));
    }
  } else if (!starts_solid) {
    throw Error(fmt::format("{}: truncated: a binary STL needs an 84-byte header, found {} bytes", path,
                            bytes.size()));
  }
  return AsciiStl(path, bytes).read();
}

}  // namespace roving
