// Strict, bounded PLY reader. OpenMesh's reader crashed on a property declared before any
// element, looped forever on a format line without a version, allocated gigabytes for a
// 287-byte file whose count overflowed a size check, accepted truncated and stray-token files,
// and built half-edge topology nothing used (half of a load). This one reads the header into a
// schema, checks every declared count against the bytes left, then reads exactly that.
#include "roving/formats/meshes/ply_reader.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <optional>
#include <type_traits>

#include "roving/core/error.h"
#include "roving/formats/files/file_bytes.h"
#include "roving/formats/meshes/ply_header.h"
#include "roving/formats/meshes/polygon_sink.h"

namespace roving {
namespace {

using namespace ply;

// Reads binary values with bounds checks; `swap` for big-endian files.
class BinaryBody {
 public:
  BinaryBody(const std::string& path, std::string_view bytes, bool swap)
      : path_(path), bytes_(bytes), swap_(swap) {}

  double read(Scalar type, const Element& element, unsigned long long item) {
    const std::size_t size = size_of(type);
    if (bytes_.size() - position_ < size) {
      throw Error(fmt::format("{}: truncated: {} {} of {} ends after {} bytes of data", path_, element.name,
                              item, element.count, position_));
    }
    unsigned char raw[8];
    std::memcpy(raw, bytes_.data() + position_, size);
    position_ += size;
    if (swap_) std::reverse(raw, raw + size);
    switch (type) {
      case Scalar::Int8: return static_cast<std::int8_t>(raw[0]);
      case Scalar::UInt8: return raw[0];
      case Scalar::Int16: return value<std::int16_t>(raw);
      case Scalar::UInt16: return value<std::uint16_t>(raw);
      case Scalar::Int32: return value<std::int32_t>(raw);
      case Scalar::UInt32: return value<std::uint32_t>(raw);
      case Scalar::Float32: return value<float>(raw);
      case Scalar::Float64: return value<double>(raw);
    }
    return 0;
  }
  std::size_t remaining() const { return bytes_.size() - position_; }
  const char* peek() const { return bytes_.data() + position_; }
  bool swapped() const { return swap_; }

  // The next `size` bytes, bounds-checked.
  const char* take(std::size_t size, const Element& element, unsigned long long item) {
    if (bytes_.size() - position_ < size) {
      throw Error(fmt::format("{}: truncated: {} {} of {} ends after {} bytes of data", path_, element.name,
                              item, element.count, position_));
    }
    const char* at = bytes_.data() + position_;
    position_ += size;
    return at;
  }

 private:
  template <class T>
  static double value(const unsigned char* raw) {
    T v;
    std::memcpy(&v, raw, sizeof v);
    return static_cast<double>(v);
  }
  const std::string& path_;
  std::string_view bytes_;
  bool swap_;
  std::size_t position_ = 0;
};

// Reads ASCII values one line per item, every token accounted for.
class AsciiBody {
 public:
  AsciiBody(const std::string& path, std::string_view bytes, std::size_t header_lines)
      : path_(path), cursor_(bytes), header_lines_(header_lines) {}

  void start_item(const Element& element, unsigned long long item) {
    element_ = &element;
    item_ = item;
    do {
      if (!cursor_.next_line(rest_)) {
        throw Error(fmt::format("{}: truncated: expected {} {} of {}, found the end of the file", path_,
                                element.name, item, element.count));
      }
    } while (rest_.find_first_not_of(" \t") == std::string_view::npos);
  }
  double read(bool integral) {
    const std::string_view token = next_token(rest_);
    double value = 0;
    long long whole = 0;
    const bool ok = integral ? parse_number(token, whole) : parse_number(token, value);
    if (!ok) throw fail(integral ? "an integer" : "a number", token);
    return integral ? static_cast<double>(whole) : value;
  }
  // Bytes left on the item's line: a list cannot hold more values than that.
  std::size_t remaining() const { return rest_.size(); }
  void end_item() {
    const std::string_view stray = next_token(rest_);
    if (!stray.empty()) throw fail("the end of the line", stray);
  }
  void end_body() {
    std::string_view line;
    while (cursor_.next_line(line)) {
      std::string_view rest = line;
      const std::string_view token = next_token(rest);
      if (!token.empty()) {
        throw Error(fmt::format("{}:{}: expected the end of the file after the last element, found {}", path_,
                                header_lines_ + cursor_.line_number(), quoted(token)));
      }
    }
  }

 private:
  Error fail(const char* expected, std::string_view found) const {
    return Error(fmt::format("{}:{}: {} {}: expected {}, found {}", path_,
                             header_lines_ + cursor_.line_number(), element_->name, item_, expected,
                             quoted(found)));
  }
  const std::string& path_;
  LineCursor cursor_;
  std::size_t header_lines_;
  std::string_view rest_;
  const Element* element_ = nullptr;
  unsigned long long item_ = 0;
};

// One face of a binary file as a triangle: a count byte of 3 and three 4-byte indices (host
// order), every index below `vertex_count` and the three distinct. False for anything else.
bool plain_triangle(const char* raw, std::size_t vertex_count, Triangle& triangle) {
  std::uint32_t index[3];
  std::memcpy(index, raw + 1, sizeof index);
  // A negative int32 reads as a uint32 above any vertex count (< 2^31).
  if (raw[0] != 3 || index[0] >= vertex_count || index[1] >= vertex_count || index[2] >= vertex_count ||
      index[0] == index[1] || index[1] == index[2] || index[0] == index[2])
    return false;
  triangle = {static_cast<int>(index[0]), static_cast<int>(index[1]), static_cast<int>(index[2])};
  return true;
}

// A face element of plain triangles only (a scan's or a tool's output) read on all cores. False,
// with nothing read, when any face is another; the general loop then reads (and reports) them.
bool read_plain_triangles(const Element& element, BinaryBody& body, std::size_t vertex_count,
                          std::vector<Triangle>& triangles) {
  constexpr std::size_t kItem = 1 + 3 * 4;
  if (body.remaining() / kItem < element.count) return false;
  const char* items = body.peek();
  triangles.resize(element.count);
  std::atomic<bool> plain{true};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, element.count, 16384),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t f = range.begin(); f != range.end() && plain; ++f) {
                        if (!plain_triangle(items + kItem * f, vertex_count, triangles[f])) plain = false;
                      }
                    });
  if (!plain) {
    triangles.clear();
    return false;
  }
  body.take(kItem * element.count, element, 0);
  return true;
}

// Vertices of fixed-size properties, the layout nearly every binary PLY uses (in native byte
// order): float or double coordinates and normals, uchar colours, any other scalar skipped; read
// on all cores by byte offsets, without per-value dispatch. False for another layout, or where the
// file ends early (the general path then names the item).
bool read_fixed_vertices(const Element& element, BinaryBody& body, std::vector<Vec3>& positions,
                         std::vector<Vec3>& normals, bool have_normals, std::vector<Colour>& colours,
                         bool have_colours) {
  struct Field {
    std::size_t offset = 0;
    bool is_double = false;
  };
  Field field[10];  // indexed by Role - 1: x y z nx ny nz (corners) red green blue
  std::size_t stride = 0;
  for (const Property& p : element.properties) {
    if (p.is_list) return false;
    const int slot = static_cast<int>(p.role) - 1;
    const bool colour = p.role == Role::Red || p.role == Role::Green || p.role == Role::Blue;
    if (p.role != Role::Skip) {
      if (colour ? p.type != Scalar::UInt8 : p.type != Scalar::Float32 && p.type != Scalar::Float64) return false;
      field[slot] = {stride, p.type == Scalar::Float64};
    }
    stride += size_of(p.type);
  }
  if (stride == 0 || body.remaining() / stride < element.count) return false;
  const char* items = body.take(stride * element.count, element, 0);
  positions.resize(element.count);
  if (have_normals) normals.resize(element.count);
  if (have_colours) colours.resize(element.count);
  const auto value = [](const char* item, const Field& f) {
    if (f.is_double) {
      double v;
      std::memcpy(&v, item + f.offset, sizeof v);
      return v;
    }
    float v;
    std::memcpy(&v, item + f.offset, sizeof v);
    return double(v);
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, element.count, 16384),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        const char* item = items + stride * i;
                        positions[i] = Vec3(value(item, field[0]), value(item, field[1]), value(item, field[2]));
                        if (have_normals)
                          normals[i] = Vec3(value(item, field[3]), value(item, field[4]), value(item, field[5]));
                        if (have_colours) {
                          const auto code = [&](const Field& f) { return float(std::uint8_t(item[f.offset])); };
                          colours[i] = Colour(code(field[7]), code(field[8]), code(field[9]));
                        }
                      }
                    });
  return true;
}

// Faces of one list of uchar count and 32-bit indices, read without per-value dispatch (in native
// byte order). Same checks as the general path; false when `element` has another layout.
bool read_plain_faces(const Element& element, BinaryBody& body, std::size_t vertex_count,
                      std::optional<PolygonSink>& sink, std::vector<Triangle>& triangles) {
  if (element.name != "face" || element.properties.size() != 1) return false;
  const Property& p = element.properties[0];
  if (p.role != Role::Corners || p.count_type != Scalar::UInt8 || size_of(p.type) != 4) return false;
  if (read_plain_triangles(element, body, vertex_count, triangles)) return true;
  const bool is_signed = p.type == Scalar::Int32;
  std::vector<long long> corners;
  for (unsigned long long item = 0; item < element.count; ++item) {
    const auto count = static_cast<unsigned char>(*body.take(1, element, item));
    const char* raw = body.take(4ull * count, element, item);
    corners.resize(count);
    for (unsigned c = 0; c < count; ++c) {
      std::uint32_t index;
      std::memcpy(&index, raw + 4 * c, 4);
      corners[c] = is_signed ? static_cast<long long>(static_cast<std::int32_t>(index)) : index;
    }
    sink->add(corners, item, triangles);
  }
  return true;
}

// A colour property's value as an sRGB code value on [0, 255]: uchar as stored, float and double
// (0-1) scaled by 255. Out of range or not finite: an error naming the vertex.
float colour_code(const std::string& path, const Element& element, unsigned long long item, const Property& p,
                  double value) {
  if (p.type == Scalar::UInt8) {
    if (!(value >= 0 && value <= 255)) {
      throw Error(fmt::format("{}: {} {}: colour '{}' is {}; expected a uchar within [0, 255]", path,
                              element.name, item, p.name, value));
    }
    return static_cast<float>(value);
  }
  if (!(value >= 0 && value <= 1)) {
    throw Error(fmt::format("{}: {} {}: colour '{}' is {}; expected a float within [0, 1]", path,
                            element.name, item, p.name, value));
  }
  return static_cast<float>(value * 255);
}

template <class Body>
void read_body(const std::string& path, const Header& header, Body& body, PlyContents& out, bool drop_non_finite) {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  std::vector<long long> corners;
  std::vector<Colour> colours;
  bool have_normals = false, have_colours = false;
  for (const Element& element : header.elements) {
    const bool is_vertex = element.name == "vertex";
    const bool is_face = element.name == "face";
    if (is_vertex) {
      int axes = 0, normal_axes = 0, colour_channels = 0;
      for (const Property& p : element.properties) {
        axes += p.role == Role::X || p.role == Role::Y || p.role == Role::Z;
        normal_axes += p.role == Role::NX || p.role == Role::NY || p.role == Role::NZ;
        colour_channels += p.role == Role::Red || p.role == Role::Green || p.role == Role::Blue;
      }
      if (colour_channels != 0 && colour_channels != 3) {
        throw Error(
            fmt::format("{}: header line {}: the vertex element has {} of the colour properties red, "
                        "green and blue; expected all three or none",
                        path, element.header_line, colour_channels));
      }
      have_colours = colour_channels == 3;
      if (have_colours) colours.reserve(element.count);
      if (axes != 3) {
        throw Error(fmt::format("{}: header line {}: the vertex element needs properties x, y and z", path,
                                element.header_line));
      }
      have_normals = normal_axes == 3;
      positions.reserve(element.count);
      if (have_normals) out.normals.reserve(element.count);
    }
    std::optional<PolygonSink> sink;
    if (is_face) {
      out.declares_faces = element.count > 0;
      bool has_corners = false;
      for (const Property& p : element.properties) has_corners |= p.role == Role::Corners;
      if (!has_corners && element.count > 0) {
        throw Error(fmt::format("{}: header line {}: the face element needs a list 'vertex_indices'", path,
                                element.header_line));
      }
      sink.emplace(path, positions.size(), out.mesh);
      triangles.reserve(element.count);
    }
    if constexpr (std::is_same_v<Body, BinaryBody>) {
      if (!body.swapped() &&
          (is_vertex ? read_fixed_vertices(element, body, positions, out.normals, have_normals, colours, have_colours)
                     : read_plain_faces(element, body, positions.size(), sink, triangles))) {
        continue;
      }
    }
    for (unsigned long long item = 0; item < element.count; ++item) {
      if constexpr (std::is_same_v<Body, AsciiBody>) body.start_item(element, item);
      Vec3 position = Vec3::Zero(), normal = Vec3::Zero();
      Colour colour = Colour::Zero();
      for (const Property& p : element.properties) {
        const auto read = [&](Scalar type) {
          if constexpr (std::is_same_v<Body, AsciiBody>) {
            return body.read(is_integral(type));
          } else {
            return body.read(type, element, item);
          }
        };
        if (!p.is_list) {
          const double v = read(p.type);
          switch (p.role) {
            case Role::X: position.x() = v; break;
            case Role::Y: position.y() = v; break;
            case Role::Z: position.z() = v; break;
            case Role::NX: normal.x() = v; break;
            case Role::NY: normal.y() = v; break;
            case Role::NZ: normal.z() = v; break;
            case Role::Red: colour.x() = colour_code(path, element, item, p, v); break;
            case Role::Green: colour.y() = colour_code(path, element, item, p, v); break;
            case Role::Blue: colour.z() = colour_code(path, element, item, p, v); break;
            default: break;
          }
          continue;
        }
        const double count = read(p.count_type);
        // A list cannot hold more values than bytes remain (ASCII: 2 per value).
        if (count < 0 || count > double(body.remaining())) {
          throw Error(fmt::format("{}: {} {}: list '{}' declares {} values; the file holds at most {} more",
                                  path, element.name, item, p.name, count, body.remaining()));
        }
        const auto n = static_cast<std::size_t>(count);
        if (p.role == Role::Corners) corners.clear();
        for (std::size_t i = 0; i < n; ++i) {
          const double v = read(p.type);
          if (p.role == Role::Corners) corners.push_back(static_cast<long long>(v));
        }
      }
      if constexpr (std::is_same_v<Body, AsciiBody>) body.end_item();
      if (is_vertex && drop_non_finite && !position.allFinite()) {
        ++out.non_finite_dropped;
      } else if (is_vertex) {
        positions.push_back(position);
        if (have_normals) out.normals.push_back(normal);
        if (have_colours) colours.push_back(colour);
      }
      if (is_face) sink->add(corners, item, triangles);
    }
  }
  if constexpr (std::is_same_v<Body, AsciiBody>) {
    body.end_body();
  } else if (body.remaining() != 0) {
    throw Error(fmt::format("{}: {} bytes follow the last element; expected the end of the file", path,
                            body.remaining()));
  }
  out.mesh.path = path;
  out.mesh.mesh = TriangleMesh(std::move(positions), std::move(triangles), path);
  if (have_colours) out.mesh.mesh.set_vertex_colours(std::move(colours), path);
}

}  // namespace

PlyContents read_ply(const std::string& path, bool drop_non_finite_points) {
  const FileBytes file(path, "a .ply model");
  const Header header = checked_header(path, file.bytes());
  const std::string_view body_bytes = file.bytes().substr(header.body_offset);
  PlyContents out;
  // Vertices are left out only where no face numbers them.
  for (const Element& element : header.elements) {
    if (element.name == "face" && element.count > 0) drop_non_finite_points = false;
  }
  if (header.encoding == Encoding::Ascii) {
    AsciiBody body(path, body_bytes, header.lines);
    read_body(path, header, body, out, drop_non_finite_points);
  } else {
    const bool big_endian_host = false;  // x86-64 and arm64 Linux
    BinaryBody body(path, body_bytes, (header.encoding == Encoding::BinaryBig) != big_endian_host);
    read_body(path, header, body, out, drop_non_finite_points);
  }
  return out;
}

bool ply_declares_no_faces(const std::string& path) {
  const FileBytes file(path, "a .ply model");
  const Header header = parse_header(path, file.bytes());
  for (const Element& element : header.elements) {
    if (element.name == "face" && element.count > 0) return false;
  }
  return true;
}

bool ply_colours_are_floats(const std::string& path) {
  const FileBytes file(path, "a .ply model");
  Header header = parse_header(path, file.bytes());
  assign_roles(path, header);
  for (const Element& element : header.elements) {
    for (const Property& p : element.properties) {
      if (p.role == Role::Red && (p.type == Scalar::Float32 || p.type == Scalar::Float64)) return true;
    }
  }
  return false;
}

std::optional<PlyTriangleLayout> ply_triangle_layout(const std::string& path) {
  const FileBytes file(path, "a .ply model");
  Header header = parse_header(path, file.bytes());
  assign_roles(path, header);
  if (header.encoding != Encoding::BinaryLittle || header.elements.size() != 2) return std::nullopt;
  const Element &vertex = header.elements[0], &face = header.elements[1];
  if (vertex.name != "vertex" || face.name != "face" || face.properties.size() != 1) return std::nullopt;
  const Property& corners = face.properties[0];
  if (corners.role != Role::Corners || corners.count_type != Scalar::UInt8 ||
      (corners.type != Scalar::Int32 && corners.type != Scalar::UInt32)) {
    return std::nullopt;
  }
  PlyTriangleLayout layout;
  std::optional<Scalar> coordinate_type;
  for (const Property& p : vertex.properties) {
    if (p.is_list || p.role == Role::Red || p.role == Role::Green || p.role == Role::Blue) return std::nullopt;
    const int axis = p.role == Role::X ? 0 : p.role == Role::Y ? 1 : p.role == Role::Z ? 2 : -1;
    if (axis >= 0) {
      if ((p.type != Scalar::Float32 && p.type != Scalar::Float64) || (coordinate_type && *coordinate_type != p.type)) {
        return std::nullopt;
      }
      coordinate_type = p.type;
      layout.coordinate_offset[axis] = layout.vertex_stride;
    }
    layout.vertex_stride += size_of(p.type);
  }
  if (!coordinate_type) return std::nullopt;  // read_ply names what is missing
  layout.coordinates_double = *coordinate_type == Scalar::Float64;
  layout.indices_signed = corners.type == Scalar::Int32;
  layout.vertex_count = vertex.count;
  layout.face_count = face.count;
  layout.vertices_at = header.body_offset;
  const unsigned long long body = file.size() - header.body_offset;
  // Counts beyond what the file could hold fail read_ply's checks, not this product.
  if (vertex.count > body / layout.vertex_stride || face.count > body / 13) return std::nullopt;
  layout.faces_at = layout.vertices_at + vertex.count * layout.vertex_stride;
  if (layout.faces_at + 13 * face.count != file.size()) return std::nullopt;
  return layout;
}


std::optional<PackedPointCloud> ply_packed_points(const std::string& path, std::string_view bytes) {
  Header header = parse_header(path, bytes);
  assign_roles(path, header);
  if (header.encoding != Encoding::BinaryLittle) return std::nullopt;
  const Element* vertex = nullptr;
  for (const Element& element : header.elements) {
    if (element.name == "vertex" && !vertex) {
      vertex = &element;
    } else if (element.count > 0) {
      return std::nullopt;
    }
  }
  if (!vertex || vertex->count == 0) return std::nullopt;
  PackedPointCloud packed;
  int axes = 0, normal_axes = 0, colour_channels = 0;
  for (const Property& p : vertex->properties) {
    if (p.is_list) return std::nullopt;
    const bool real = p.type == Scalar::Float32 || p.type == Scalar::Float64;
    const PackedPointCloud::Field field = {packed.stride, p.type == Scalar::Float64};
    switch (p.role) {
      case Role::X: case Role::Y: case Role::Z:
        if (!real) return std::nullopt;
        packed.position[static_cast<int>(p.role) - static_cast<int>(Role::X)] = field, ++axes;
        break;
      case Role::NX: case Role::NY: case Role::NZ:
        if (!real) return std::nullopt;
        packed.normal[static_cast<int>(p.role) - static_cast<int>(Role::NX)] = field, ++normal_axes;
        break;
      case Role::Red: case Role::Green: case Role::Blue:
        if (p.type != Scalar::UInt8) return std::nullopt;
        packed.colour[static_cast<int>(p.role) - static_cast<int>(Role::Red)] = packed.stride;
        ++colour_channels;
        break;
      default: break;
    }
    packed.stride += size_of(p.type);
  }
  if (axes != 3 || (normal_axes != 0 && normal_axes != 3) || (colour_channels != 0 && colour_channels != 3)) {
    return std::nullopt;
  }
  packed.normals = normal_axes == 3;
  packed.colours = colour_channels == 3;
  const std::size_t body = bytes.size() - header.body_offset;
  if (vertex->count > body / packed.stride || vertex->count * packed.stride != body) return std::nullopt;
  packed.count = vertex->count;
  packed.records = bytes.data() + header.body_offset;
  return packed;
}

}  // namespace roving
