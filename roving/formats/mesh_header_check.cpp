// Header checks of PLY, OFF and STL files (see mesh_header_check.h for why).
#include "mesh_header_check.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "roving/core/error.h"

namespace roving {
namespace {

bool parse_count(const std::string& text, unsigned long long& count) {
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), count);
  return !text.empty() && error == std::errc() && end == text.data() + text.size();
}

std::size_t ply_type_size(const std::string& type) {
  static const std::map<std::string, std::size_t> sizes = {
      {"char", 1},  {"uchar", 1},   {"int8", 1},   {"uint8", 1},  {"short", 2}, {"ushort", 2},
      {"int16", 2}, {"uint16", 2},  {"int", 4},    {"uint", 4},   {"int32", 4}, {"uint32", 4},
      {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  const auto it = sizes.find(type);
  return it == sizes.end() ? 0 : it->second;
}

void check_ply(const std::string& path, std::ifstream& file, std::uintmax_t file_size) {
  std::string line;
  std::getline(file, line);
  if (line != "ply" && line != "ply\r") {
    throw Error(fmt::format("{}: expected the PLY magic line 'ply', found '{}'", path, line.substr(0, 40)));
  }
  bool binary = false, ended = false;
  // Smallest number of body bytes the header promises (binary: exact fixed sizes; ASCII: one
  // byte per value).
  unsigned long long promised = 0, element_count = 0;
  std::size_t element_min_size = 0;
  std::string element_name;
  const auto close_element = [&] { promised += element_count * element_min_size; };
  for (int line_number = 2; std::getline(file, line); ++line_number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    const auto bad = [&](const std::string& expected) {
      return Error(
          fmt::format("{}: header line {}: expected {}, found '{}'", path, line_number, expected, line));
    };
    if (keyword == "format") {
      std::string format, version;
      words >> format >> version;
      if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian") {
        throw bad("format ascii, binary_little_endian or binary_big_endian");
      }
      binary = format != "ascii";
    } else if (keyword == "element") {
      close_element();
      std::string count_text;
      words >> element_name >> count_text;
      if (!parse_count(count_text, element_count))
        throw bad("'element NAME COUNT' with a whole-number COUNT");
      element_min_size = 0;
    } else if (keyword == "property") {
      std::string type;
      words >> type;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type;
        if (!ply_type_size(count_type) || !ply_type_size(item_type)) throw bad("a known PLY list type");
        // A face lists at least three vertex indices.
        const std::size_t items = element_name == "face" ? 3 : 0;
        element_min_size += binary ? ply_type_size(count_type) + items * ply_type_size(item_type) : 1 + items;
      } else {
        if (!ply_type_size(type)) throw bad("a known PLY property type");
        element_min_size += binary ? ply_type_size(type) : 1;
      }
    } else if (keyword == "end_header") {
      ended = true;
      break;
    } else if (keyword != "comment" && keyword != "obj_info" && !keyword.empty()) {
      throw bad("a PLY header keyword");
    }
    if (line_number > 10000) break;
  }
  if (!ended) throw Error(fmt::format("{}: expected 'end_header' in the PLY header, found none", path));
  close_element();
  const auto body = file_size - static_cast<std::uintmax_t>(file.tellg());
  if (promised > body) {
    throw Error(fmt::format("{}: truncated: the header promises at least {} bytes of data, found {}", path,
                            promised, body));
  }
}

void check_off(const std::string& path, std::ifstream& file, std::uintmax_t file_size) {
  std::string magic;
  file >> magic;
  if (magic.size() < 3 || magic.compare(magic.size() - 3, 3, "OFF") != 0) {
    throw Error(fmt::format("{}: expected an OFF header ('OFF', 'COFF', 'NOFF'...), found '{}'", path,
                            magic.substr(0, 40)));
  }
  std::string binary_word;
  const auto position = file.tellg();
  file >> binary_word;
  if (binary_word == "BINARY") return;  // OpenMesh checks sizes of its binary variant
  file.seekg(position);
  std::string v_text, f_text;
  file >> v_text >> f_text;
  unsigned long long vertices = 0, faces = 0;
  if (!parse_count(v_text, vertices) || !parse_count(f_text, faces)) {
    throw Error(fmt::format("{}: expected whole-number vertex and face counts after '{}', found '{} {}'",
                            path, magic, v_text, f_text));
  }
  // ASCII: each vertex needs at least 6 bytes ("0 0 0\n"), each face 8 ("3 0 1 2\n").
  if (6 * vertices + 8 * faces > file_size) {
    throw Error(fmt::format("{}: truncated or wrong counts: {} vertices and {} faces cannot fit in {} bytes",
                            path, vertices, faces, file_size));
  }
  if (magic != "OFF") return;  // colour / normal variants carry extra columns
  std::string rest_of_line;
  std::getline(file, rest_of_line);  // the edge count, if any
  for (unsigned long long v = 0; v < vertices; ++v) {
    std::string line;
    if (!std::getline(file, line)) {
      throw Error(fmt::format("{}: truncated: expected {} vertices, found {}", path, vertices, v));
    }
    std::istringstream words(line);
    for (int axis = 0; axis < 3; ++axis) {
      std::string token;
      words >> token;
      double value = 0;
      const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
      if (token.empty() || error != std::errc() || end != token.data() + token.size() ||
          !std::isfinite(value)) {
        throw Error(fmt::format("{}: vertex {}: expected 3 finite numbers, found '{}'", path, v, line));
      }
    }
  }
}

void check_stl(const std::string& path, std::ifstream& file, std::uintmax_t file_size) {
  char start[5] = {};
  file.read(start, 5);
  if (std::string(start, 5) == "solid" && file_size >= 84) {
    // Either ASCII, or a binary file whose 80-byte comment happens to begin with "solid":
    // binary only when the size matches its triangle count exactly.
    file.seekg(80);
    std::uint32_t count = 0;
    file.read(reinterpret_cast<char*>(&count), 4);
    if (84 + 50ull * count != file_size) return;
  }
  if (file_size < 84) {
    throw Error(
        fmt::format("{}: truncated: a binary STL needs an 84-byte header, found {} bytes", path, file_size));
  }
  file.seekg(80);
  std::uint32_t count = 0;
  file.read(reinterpret_cast<char*>(&count), 4);
  if (84 + 50ull * count > file_size) {
    throw Error(fmt::format("{}: truncated: the header promises {} triangles ({} bytes), found {} bytes",
                            path, count, 84 + 50ull * count, file_size));
  }
}

}  // namespace

void check_mesh_header(const std::string& path, const std::string& ext) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw Error(fmt::format("{}: cannot open for reading", path));
  const std::uintmax_t size = std::filesystem::file_size(path);
  if (ext == "ply") check_ply(path, file, size);
  if (ext == "off") check_off(path, file, size);
  if (ext == "stl") check_stl(path, file, size);
}

}  // namespace roving
