// A glTF 2.0 file's document (gltf_reader.cpp reads the scene from it): the JSON (a .gltf, or a
// .glb's JSON chunk) and the bytes it refers to (a GLB's binary chunk, base64 data URIs, files
// beside the .gltf), read through buffers, buffer views and accessors, each checked against the
// bytes that exist before it is read. Every failure names the file and what it expected.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "roving/core/triangle_mesh.h"
#include "roving/formats/files/file_bytes.h"

namespace roving {

class GltfDocument {
 public:
  using json = nlohmann::json;

  // Reads the JSON (or the GLB's framing and JSON chunk); checks nothing else yet.
  explicit GltfDocument(const std::string& path);

  const std::string& path() const { return path_; }
  const json& document() const { return document_; }

  struct Accessor {
    std::string_view bytes;  // from the first element
    std::size_t count = 0, stride = 0;
    std::size_t component_type = 0, components = 0;
    bool normalized = false;
  };

  [[noreturn]] void fail(const std::string& what) const;

  void check_version_and_extensions() const;

  static const json* find(const json& object, const char* key);

  // A top-level array (empty when absent).
  const json& array(const char* key) const;

  // An unsigned integer member; `fallback` when absent (none: required).
  std::size_t natural(const json& object, const char* key, const std::string& where,
                        std::optional<std::size_t> fallback = std::nullopt) const;

  // Element `index` of top-level array `key`.
  const json& element(const char* key, std::size_t index, const std::string& where) const;

  // The bytes of a base64 data URI; nullopt for a file name. Fails on a malformed data URI and
  // on any other scheme: only files beside the .gltf are read.
  std::optional<std::string> data_uri_bytes(const std::string& text, const std::string& where) const;

  // The bytes of buffer `index`, at least its declared byteLength: the GLB's binary chunk, a
  // base64 data URI, or a file beside the .gltf.
  std::string_view buffer(std::size_t index);

  // The bytes of bufferViews[index] (`where` names who refers to it), checked to lie in its buffer.
  std::string_view view_bytes(std::size_t index, const std::string& where);

  // Element k's first `n` components of a float or normalized unsigned accessor (glTF's colours
  // and texture coordinates), as doubles on the accessor's scale ([0, 1] for normalized ones).
  void read_floats(const Accessor& a, std::size_t k, std::size_t n, double* out, const std::string& where) const;

  // Accessor `index` checked to lie in its view and its buffer; `types` its allowed types
  // ("VEC3", or "VEC3|VEC4").
  Accessor accessor(std::size_t index, const std::string& types, const std::string& role);

  std::vector<Vec3> read_positions(std::size_t index);

  std::vector<std::uint32_t> read_indices(std::size_t index, std::size_t vertex_count);

 private:
  // The GLB container: a 12-byte header, then a JSON chunk and an optional binary one.
  std::string_view glb_chunks(std::string_view bytes);

  std::string path_, format_;
  FileBytes file_;  // mapped while the document lives: the GLB's binary chunk points into it
  json document_;
  std::optional<std::string_view> binary_chunk_;
  std::deque<std::string> storage_;  // decoded data URIs and external files (a deque: views stay valid)
  std::vector<std::optional<std::string_view>> buffers_;
};

}  // namespace roving
