// A glTF 2.0 document and its data read and checked (gltf_document.h).
#include "roving/formats/meshes/gltf_document.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "roving/core/error.h"

namespace roving {
namespace {

using json = GltfDocument::json;
namespace fs = std::filesystem;

constexpr std::uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr std::uint32_t kJsonChunk = 0x4E4F534A, kBinChunk = 0x004E4942;

std::uint32_t u32(std::string_view bytes, std::size_t at) {
  std::uint32_t value;
  std::memcpy(&value, bytes.data() + at, 4);  // glTF is little-endian, as every target of ours
  return value;
}

// Strict base64 (RFC 4648, with padding); nullopt for anything else.
std::optional<std::string> decode_base64(std::string_view text) {
  if (text.size() % 4 != 0) return std::nullopt;
  const auto digit = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  };
  std::string out;
  out.reserve(text.size() / 4 * 3);
  for (std::size_t i = 0; i < text.size(); i += 4) {
    int d[4];
    for (int k = 0; k < 4; ++k) {
      const bool padding = text[i + k] == '=' && i + 4 == text.size() && k >= 2;
      d[k] = padding ? 0 : digit(text[i + k]);
      if (d[k] < 0) return std::nullopt;
    }
    const std::uint32_t n = d[0] << 18 | d[1] << 12 | d[2] << 6 | d[3];
    out += static_cast<char>(n >> 16);
    if (text[i + 2] != '=') out += static_cast<char>(n >> 8 & 0xFF);
    if (text[i + 3] != '=') out += static_cast<char>(n & 0xFF);
  }
  return out;
}

}  // namespace

GltfDocument::GltfDocument(const std::string& path)
    : path_(path), format_(fs::path(path).extension().string()), file_(path, "a glTF mesh") {
  for (char& c : format_) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  std::string_view text = file_.bytes();
  if (format_ == ".glb") text = glb_chunks(file_.bytes());
  try {
    document_ = json::parse(text.begin(), text.end());
  } catch (const json::exception& e) {
    fail(fmt::format("malformed JSON ({})", e.what()));
  }
  if (!document_.is_object()) fail("expected a JSON object at the top");
}

void GltfDocument::fail(const std::string& what) const {
  throw Error(fmt::format("{}: cannot read it as {}: {}", path_, format_, what));
}

// The GLB container: a 12-byte header, then a JSON chunk and an optional binary one.
std::string_view GltfDocument::glb_chunks(std::string_view bytes) {
  if (bytes.size() < 20 || u32(bytes, 0) != kGlbMagic) fail("expected the 'glTF' header of a binary glTF");
  if (u32(bytes, 4) != 2) fail(fmt::format("expected GLB version 2, found {}", u32(bytes, 4)));
  if (u32(bytes, 8) != bytes.size()) {
    fail(fmt::format("the header declares {} bytes, the file has {}", u32(bytes, 8), bytes.size()));
  }
  std::string_view json_chunk;
  for (std::size_t at = 12; at < bytes.size();) {
    if (bytes.size() - at < 8) fail(fmt::format("truncated chunk header at byte {}", at));
    const std::size_t length = u32(bytes, at), type = u32(bytes, at + 4);
    if (length > bytes.size() - at - 8) {
      fail(fmt::format("the chunk at byte {} declares {} bytes, {} remain", at, length,
                       bytes.size() - at - 8));
    }
    const std::string_view data = bytes.substr(at + 8, length);
    if (at == 12 && type != kJsonChunk) fail("expected the JSON chunk first");
    if (at == 12) json_chunk = data;
    if (at != 12 && type == kBinChunk && !binary_chunk_) binary_chunk_ = data;
    at += 8 + length;  // other chunk types are skipped, as the specification says
  }
  return json_chunk;
}

void GltfDocument::check_version_and_extensions() const {
  const json* asset = find(document_, "asset");
  const json* version = asset ? find(*asset, "version") : nullptr;
  if (!version || !version->is_string() || version->get<std::string>().rfind("2.", 0) != 0) {
    fail(fmt::format("expected asset.version \"2.x\" (glTF 2.0), found {}",
                     version ? version->dump() : "none"));
  }
  if (const json* required = find(document_, "extensionsRequired")) {
    if (required->is_array() && !required->empty()) {
      fail(fmt::format("it requires extension {}, which this reader does not read",
                       required->front().dump()));
    }
  }
}

const json* GltfDocument::find(const json& object, const char* key) {
  if (!object.is_object()) return nullptr;
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

// A top-level array (empty when absent).
const json& GltfDocument::array(const char* key) const {
  static const json empty = json::array();
  const json* value = find(document_, key);
  if (!value) return empty;
  if (!value->is_array()) fail(fmt::format("expected '{}' to be an array", key));
  return *value;
}

// An unsigned integer member; `fallback` when absent (none: required).
std::size_t GltfDocument::natural(const json& object, const char* key, const std::string& where,
                                  std::optional<std::size_t> fallback) const {
  const json* value = find(object, key);
  if (!value) {
    if (!fallback) fail(fmt::format("{} has no '{}'", where, key));
    return *fallback;
  }
  if (!value->is_number_unsigned())
    fail(fmt::format("{}: expected '{}' a non-negative integer, found {}", where, key, value->dump()));
  return value->get<std::size_t>();
}

// Element `index` of top-level array `key`.
const json& GltfDocument::element(const char* key, std::size_t index, const std::string& where) const {
  const json& items = array(key);
  if (index >= items.size()) {
    fail(fmt::format("{} refers to {}[{}]; the file has {}", where, key, index, items.size()));
  }
  if (!items[index].is_object()) fail(fmt::format("expected {}[{}] to be an object", key, index));
  return items[index];
}

// The bytes of a base64 data URI; nullopt for a file name. Fails on a malformed data URI and
// on any other scheme: only files beside the .gltf are read.
std::optional<std::string> GltfDocument::data_uri_bytes(const std::string& text, const std::string& where) const {
  if (text.rfind("data:", 0) == 0) {
    const std::size_t comma = text.find(";base64,");
    std::optional<std::string> decoded;
    if (comma != std::string::npos) decoded = decode_base64(std::string_view(text).substr(comma + 8));
    if (!decoded) fail(where + ": expected a base64 data URI");
    return decoded;
  }
  if (text.find("://") != std::string::npos) {
    fail(fmt::format("{}: expected a data URI or a file beside the .gltf, found '{}'", where, text));
  }
  return std::nullopt;
}

// The bytes of buffer `index`, at least its declared byteLength: the GLB's binary chunk, a
// base64 data URI, or a file beside the .gltf.
std::string_view GltfDocument::buffer(std::size_t index) {
  if (index < buffers_.size() && buffers_[index]) return *buffers_[index];
  const std::string where = fmt::format("buffers[{}]", index);
  const json& b = element("buffers", index, where);
  const std::size_t length = natural(b, "byteLength", where);
  std::string_view data;
  const json* uri = find(b, "uri");
  if (!uri) {
    if (index != 0 || !binary_chunk_) fail(where + " has no 'uri' and is not a GLB's binary chunk");
    data = *binary_chunk_;
  } else {
    if (!uri->is_string()) fail(where + ": expected 'uri' to be a string");
    const std::string text = uri->get<std::string>();
    if (std::optional<std::string> decoded = data_uri_bytes(text, where)) {
      storage_.push_back(std::move(*decoded));
    } else {
      const fs::path file = resolve_reference(path_, text, where + "'s uri");
      try {
        require_regular_file(file.string(), where + "'s bytes");
      } catch (const Error& e) {
        fail(fmt::format("{}: {}", where, e.what()));
      }
      std::ifstream in(file, std::ios::binary);
      std::error_code error;
      const auto size = fs::file_size(file, error);
      if (!in || error || !fs::is_regular_file(file))
        fail(fmt::format("{}: cannot open '{}'", where, file.string()));
      if (size < length) fail(fmt::format("{}: '{}' has {} bytes, {} declared", where, text, size, length));
      std::string bytes(length, '\0');
      in.read(bytes.data(), static_cast<std::streamsize>(length));
      storage_.push_back(std::move(bytes));
    }
    data = storage_.back();
  }
  if (data.size() < length) fail(fmt::format("{} declares {} bytes, {} exist", where, length, data.size()));
  buffers_.resize(std::max(buffers_.size(), index + 1));
  buffers_[index] = data.substr(0, length);
  return *buffers_[index];
}

// The bytes of bufferViews[index] (`where` names who refers to it), checked to lie in its buffer.
std::string_view GltfDocument::view_bytes(std::size_t index, const std::string& where) {
  const std::string view_where = fmt::format("bufferViews[{}]", index);
  const json& view = element("bufferViews", index, where);
  const std::string_view data = buffer(natural(view, "buffer", view_where));
  const std::size_t offset = natural(view, "byteOffset", view_where, 0);
  const std::size_t length = natural(view, "byteLength", view_where);
  if (offset > data.size() || length > data.size() - offset) {
    fail(fmt::format("{} spans bytes [{}, {} + {}) of a {}-byte buffer", view_where, offset, offset, length,
                     data.size()));
  }
  return data.substr(offset, length);
}

// Element k's first `n` components of a float or normalized unsigned accessor (glTF's colours
// and texture coordinates), as doubles on the accessor's scale ([0, 1] for normalized ones).
void GltfDocument::read_floats(const Accessor& a, std::size_t k, std::size_t n, double* out,
                               const std::string& where) const {
  const char* at = a.bytes.data() + k * a.stride;
  for (std::size_t c = 0; c < n; ++c) {
    if (a.component_type == 5126) {
      float x;
      std::memcpy(&x, at + 4 * c, 4);
      out[c] = x;
    } else if (a.component_type == 5121 && a.normalized) {
      out[c] = static_cast<unsigned char>(at[c]) / 255.0;
    } else if (a.component_type == 5123 && a.normalized) {
      std::uint16_t x;
      std::memcpy(&x, at + 2 * c, 2);
      out[c] = x / 65535.0;
    } else {
      fail(
          fmt::format("{}: expected float or normalized unsigned byte or short components, found "
                      "componentType {}{}",
                      where, a.component_type, a.normalized ? " (normalized)" : ""));
    }
  }
}

// Accessor `index` checked to lie in its view and its buffer; `types` its allowed types
// ("VEC3", or "VEC3|VEC4").
GltfDocument::Accessor GltfDocument::accessor(std::size_t index, const std::string& types,
                                              const std::string& role) {
  const std::string where = fmt::format("accessors[{}] ({})", index, role);
  const json& a = element("accessors", index, where);
  if (find(a, "sparse")) fail(where + ": sparse accessors are not read");
  const json* actual_type = find(a, "type");
  const std::string type = actual_type && actual_type->is_string() ? actual_type->get<std::string>() : "";
  const std::size_t components = type == "SCALAR" ? 1
                                 : type == "VEC2" ? 2
                                 : type == "VEC3" ? 3
                                 : type == "VEC4" ? 4
                                                  : 0;
  if (components == 0 || ("|" + types + "|").find("|" + type + "|") == std::string::npos) {
    fail(fmt::format("{}: expected type {}, found {}", where, types,
                     actual_type ? actual_type->dump() : "none"));
  }
  Accessor out;
  out.components = components;
  const json* normalized = find(a, "normalized");
  out.normalized = normalized && normalized->is_boolean() && normalized->get<bool>();
  out.component_type = natural(a, "componentType", where);
  out.count = natural(a, "count", where);
  std::size_t component_size = 0;
  switch (out.component_type) {
    case 5120:
    case 5121: component_size = 1; break;
    case 5122:
    case 5123: component_size = 2; break;
    case 5125:
    case 5126: component_size = 4; break;
    default: fail(fmt::format("{}: unknown componentType {}", where, out.component_type));
  }
  const std::size_t element_size = component_size * components;
  if (!find(a, "bufferView")) fail(where + " has no bufferView (all zeros); expected data");
  const std::size_t view_index = natural(a, "bufferView", where);
  const std::string view_where = fmt::format("bufferViews[{}]", view_index);
  const json& view = element("bufferViews", view_index, where);
  const std::string_view view_data = view_bytes(view_index, where);
  const std::size_t view_length = view_data.size();
  out.stride = natural(view, "byteStride", view_where, element_size);
  if (out.stride < element_size)
    fail(fmt::format("{}: byteStride {} is less than an element ({})", view_where, out.stride,
                     element_size));
  const std::size_t offset = natural(a, "byteOffset", where, 0);
  // The last element must end inside the view: offset + stride * (count - 1) + element_size.
  if (out.count > 0 && (offset > view_length || view_length - offset < element_size ||
                        (view_length - offset - element_size) / out.stride < out.count - 1)) {
    fail(fmt::format("{}: {} elements from byte {} do not fit in {} of {} bytes", where, out.count, offset,
                     view_where, view_length));
  }
  out.bytes = view_data.substr(offset);
  return out;
}

std::vector<Vec3> GltfDocument::read_positions(std::size_t index) {
  const Accessor a = accessor(index, "VEC3", "POSITION");
  if (a.component_type != 5126)
    fail(fmt::format("accessors[{}] (POSITION): expected float components (5126), found {}", index,
                     a.component_type));
  std::vector<Vec3> out(a.count);
  for (std::size_t k = 0; k < a.count; ++k) {
    float xyz[3];
    std::memcpy(xyz, a.bytes.data() + k * a.stride, sizeof xyz);
    out[k] = Vec3(xyz[0], xyz[1], xyz[2]);
  }
  return out;
}

std::vector<std::uint32_t> GltfDocument::read_indices(std::size_t index, std::size_t vertex_count) {
  const Accessor a = accessor(index, "SCALAR", "indices");
  std::vector<std::uint32_t> out(a.count);
  for (std::size_t k = 0; k < a.count; ++k) {
    const char* at = a.bytes.data() + k * a.stride;
    if (a.component_type == 5121) {
      out[k] = static_cast<unsigned char>(*at);
    } else if (a.component_type == 5123) {
      std::uint16_t v;
      std::memcpy(&v, at, 2);
      out[k] = v;
    } else if (a.component_type == 5125) {
      std::memcpy(&out[k], at, 4);
    } else {
      fail(fmt::format("accessors[{}] (indices): expected unsigned components, found {}", index,
                       a.component_type));
    }
    if (out[k] >= vertex_count) {
      fail(fmt::format("accessors[{}] (indices): index {} is {}; the primitive has {} vertices", index, k,
                       out[k], vertex_count));
    }
  }
  return out;
}

}  // namespace roving
