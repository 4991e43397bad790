// A binary STL's triangles a block at a time (triangle_stream.h). STL stores each facet's three
// corners, so a block's triangles number their own corners (3 a face, nothing held between
// blocks); the first pass also counts the distinct corners, which are the vertices read_stl
// merges by their bits, in a set of 12 bytes a slot (about 16 a vertex) freed when it ends.
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "roving/formats/meshes/triangle_stream.h"

namespace roving {

// The facet count of `path` where it is a binary STL (its size exactly 84 bytes and 50 a facet, as
// read_stl tells binary from ASCII); nullopt otherwise.
std::optional<std::size_t> binary_stl_facets(const std::string& path);

class StlTriangleStream final : public TriangleStream {
 public:
  StlTriangleStream(const std::string& path, std::size_t facets);
  ~StlTriangleStream() override;

  bool next(std::size_t count, std::vector<Triangle>& triangles) override;
  Vec3 position(int corner) const override { return corners_[corner]; }
  std::size_t position_count() const override { return corners_.size(); }
  VertexCensus census() const override;

 private:
  class CornerSet;
  struct CloseFile {
    void operator()(std::FILE* file) const { std::fclose(file); }
  };
  std::unique_ptr<std::FILE, CloseFile> file_;
  std::vector<char> buffer_;
  std::vector<Vec3> corners_;          // the block's kept faces', 3 a face
  std::unique_ptr<CornerSet> seen_;    // until the first pass ends
  BoundingBox referenced_box_;         // of the kept faces' corners, in the first pass
  std::optional<VertexCensus> census_;
};

}  // namespace roving
