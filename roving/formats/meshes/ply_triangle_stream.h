// A binary PLY's triangles a block at a time (triangle_stream.h): its vertices held as the file
// stores them (float or double: 12 or 24 bytes each, where a loaded mesh holds 24 per vertex and
// 12 per triangle), its faces read from the file per block, numbered as the file numbers them.
#pragma once

#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "roving/formats/meshes/ply_reader.h"
#include "roving/formats/meshes/triangle_stream.h"

namespace roving {

class PlyTriangleStream final : public TriangleStream {
 public:
  // Reads the vertices; throws roving::Error naming `path` on a non-finite coordinate or a read
  // that fails.
  PlyTriangleStream(const std::string& path, const PlyTriangleLayout& layout);

  bool next(std::size_t count, std::vector<Triangle>& triangles) override;
  Vec3 position(int vertex) const override;
  std::size_t position_count() const override { return layout_.vertex_count; }
  VertexCensus census() const override;

 private:
  void count_vertices();  // at the end of the first pass


  PlyTriangleLayout layout_;
  struct CloseFile {
    void operator()(std::FILE* file) const { std::fclose(file); }
  };
  std::unique_ptr<std::FILE, CloseFile> file_;  // closed however the constructor ends
  std::vector<float> float_positions_;    // x y z per vertex, where the file stores float
  std::vector<double> double_positions_;  // or double
  std::vector<char> buffer_;
  std::vector<bool> referenced_;  // by a kept face, until the first pass ends
  std::optional<VertexCensus> census_;
};

}  // namespace roving
