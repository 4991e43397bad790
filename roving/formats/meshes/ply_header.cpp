// A PLY header parsed and checked (ply_header.h).
#include "roving/formats/meshes/ply_header.h"

#include <fmt/format.h>

#include <algorithm>
#include <optional>

#include "roving/core/error.h"
#include "roving/formats/files/file_bytes.h"
#include "roving/formats/meshes/polygon_sink.h"

namespace roving::ply {
namespace {

std::optional<Scalar> scalar_named(std::string_view name) {
  static const std::pair<const char*, Scalar> names[] = {
      {"char", Scalar::Int8},      {"int8", Scalar::Int8},       {"uchar", Scalar::UInt8},
      {"uint8", Scalar::UInt8},    {"short", Scalar::Int16},     {"int16", Scalar::Int16},
      {"ushort", Scalar::UInt16},  {"uint16", Scalar::UInt16},   {"int", Scalar::Int32},
      {"int32", Scalar::Int32},    {"uint", Scalar::UInt32},     {"uint32", Scalar::UInt32},
      {"float", Scalar::Float32},  {"float32", Scalar::Float32}, {"double", Scalar::Float64},
      {"float64", Scalar::Float64}};
  for (const auto& [text, scalar] : names) {
    if (name == text) return scalar;
  }
  return std::nullopt;
}

// A header longer than this is not a model's header.
constexpr std::size_t kMaxHeaderBytes = 1 << 20;

// Smallest number of body bytes one item of `element` takes: fixed sizes in binary, a value and
// a separator per scalar in ASCII; a face's corner list holds at least 3 indices.
std::size_t minimum_item_size(const Element& element, Encoding encoding) {
  std::size_t size = 0;
  for (const Property& p : element.properties) {
    const std::size_t least_items = p.role == Role::Corners ? 3 : 0;
    if (encoding == Encoding::Ascii) {
      size += 2 * (1 + (p.is_list ? least_items : 0));
    } else {
      size += p.is_list ? size_of(p.count_type) + least_items * size_of(p.type) : size_of(p.type);
    }
  }
  return size;
}

}  // namespace

std::size_t size_of(Scalar s) {
  switch (s) {
    case Scalar::Int8:
    case Scalar::UInt8: return 1;
    case Scalar::Int16:
    case Scalar::UInt16: return 2;
    case Scalar::Int32:
    case Scalar::UInt32:
    case Scalar::Float32: return 4;
    case Scalar::Float64: return 8;
  }
  return 0;
}

Header parse_header(const std::string& path, std::string_view bytes) {
  LineCursor cursor(bytes.substr(0, std::min(bytes.size(), kMaxHeaderBytes)));
  std::string_view line;
  if (!cursor.next_line(line) || line != "ply") {
    throw Error(fmt::format("{}: expected the PLY magic line 'ply', found {}", path, quoted(line)));
  }
  Header header;
  bool have_format = false, ended = false;
  while (cursor.next_line(line)) {
    const auto fail = [&](const std::string& expected) {
      return Error(fmt::format("{}: header line {}: expected {}, found {}", path, cursor.line_number(),
                               expected, quoted(line)));
    };
    std::string_view rest = line;
    const std::string_view keyword = next_token(rest);
    if (keyword == "format") {
      const std::string_view format = next_token(rest), version = next_token(rest);
      if (format == "ascii")
        header.encoding = Encoding::Ascii;
      else if (format == "binary_little_endian")
        header.encoding = Encoding::BinaryLittle;
      else if (format == "binary_big_endian")
        header.encoding = Encoding::BinaryBig;
      else
        throw fail("'format ascii|binary_little_endian|binary_big_endian 1.0'");
      if (version != "1.0" || !next_token(rest).empty()) throw fail("'format <encoding> 1.0'");
      if (have_format) throw fail("one format line");
      have_format = true;
    } else if (keyword == "element") {
      Element element;
      element.name = std::string(next_token(rest));
      long long count = -1;
      if (element.name.empty() || !parse_number(next_token(rest), count) || count < 0 ||
          !next_token(rest).empty()) {
        throw fail("'element NAME COUNT' with a whole-number COUNT");
      }
      element.count = static_cast<unsigned long long>(count);
      element.header_line = cursor.line_number();
      header.elements.push_back(std::move(element));
    } else if (keyword == "property") {
      if (header.elements.empty()) throw fail("an 'element' line before its properties");
      Property property;
      std::string_view type = next_token(rest);
      if (type == "list") {
        const auto count_type = scalar_named(next_token(rest));
        const auto item_type = scalar_named(next_token(rest));
        if (!count_type || !item_type || !is_integral(*count_type)) {
          throw fail("'property list COUNT_TYPE ITEM_TYPE NAME' with an integer COUNT_TYPE");
        }
        property.is_list = true;
        property.count_type = *count_type;
        property.type = *item_type;
      } else {
        const auto scalar = scalar_named(type);
        if (!scalar)
          throw fail("a known PLY property type (char, uchar, short, ushort, int, uint, float, double)");
        property.type = *scalar;
      }
      property.name = std::string(next_token(rest));
      if (property.name.empty() || !next_token(rest).empty()) throw fail("'property TYPE NAME'");
      header.elements.back().properties.push_back(std::move(property));
    } else if (keyword == "end_header") {
      ended = true;
      break;
    } else if (keyword != "comment" && keyword != "obj_info" && !keyword.empty()) {
      throw fail("a PLY header keyword (format, element, property, comment, obj_info, end_header)");
    }
  }
  if (!ended) {
    throw Error(fmt::format("{}: expected 'end_header' within the first {} bytes, found none", path,
                            std::min(bytes.size(), kMaxHeaderBytes)));
  }
  if (!have_format) throw Error(fmt::format("{}: the PLY header has no 'format' line", path));
  header.body_offset = cursor.offset();
  header.lines = cursor.line_number();
  return header;
}

// Gives the vertex and face properties their roles; checks that a mesh or point cloud can be
// read from them.
void assign_roles(const std::string& path, Header& header) {
  for (Element& element : header.elements) {
    if (element.properties.empty() && element.count > 0) {
      throw Error(fmt::format("{}: header line {}: element '{}' declares {} items but no property", path,
                              element.header_line, element.name, element.count));
    }
    for (std::size_t i = 0; i < element.properties.size(); ++i) {
      for (std::size_t j = 0; j < i; ++j) {
        if (element.properties[i].name == element.properties[j].name) {
          throw Error(fmt::format("{}: element '{}' declares property '{}' twice", path, element.name,
                                  element.properties[i].name));
        }
      }
    }
    for (Property& p : element.properties) {
      if (element.name == "vertex" && !p.is_list) {
        static const std::pair<const char*, Role> roles[] = {
            {"x", Role::X},     {"y", Role::Y},         {"z", Role::Z},
            {"nx", Role::NX},   {"ny", Role::NY},       {"nz", Role::NZ},
            {"red", Role::Red}, {"green", Role::Green}, {"blue", Role::Blue}};
        for (const auto& [name, role] : roles) {
          if (p.name == name) p.role = role;
        }
      }
      const bool colour = p.role == Role::Red || p.role == Role::Green || p.role == Role::Blue;
      if (colour && p.type != Scalar::UInt8 && p.type != Scalar::Float32 && p.type != Scalar::Float64) {
        throw Error(
            fmt::format("{}: vertex property '{}': expected a colour as uchar (0-255) or float/double "
                        "(0-1), found another type",
                        path, p.name));
      }
      if (element.name == "face" && p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) {
        if (!is_integral(p.type)) {
          throw Error(fmt::format(
              "{}: face property '{}' holds floating-point values; expected integer indices", path, p.name));
        }
        p.role = Role::Corners;
      }
    }
  }
}

Header checked_header(const std::string& path, std::string_view bytes) {
  Header header = parse_header(path, bytes);
  assign_roles(path, header);
  // Every declared count against the bytes left, before anything is allocated.
  std::size_t left = bytes.size() - header.body_offset;
  for (const Element& element : header.elements) {
    const std::size_t item = minimum_item_size(element, header.encoding);
    if (item == 0) continue;
    // ASCII: the last value needs no separator after it.
    const std::size_t available = left + (header.encoding == Encoding::Ascii ? 1 : 0);
    if (element.count > available / item) {
      throw Error(fmt::format(
          "{}: truncated or corrupt: header line {} declares {} {} items of at least {} bytes; the file "
          "holds {} bytes after the header",
          path, element.header_line, element.count, element.name, item, bytes.size() - header.body_offset));
    }
    left = available - element.count * item;
  }
  unsigned long long vertices = 0, faces = 0;
  for (const Element& element : header.elements) {
    if (element.name == "vertex") vertices = element.count;
    if (element.name == "face") faces = element.count;
  }
  require_mesh_memory(path, vertices, faces);
  return header;
}

}  // namespace roving::ply
