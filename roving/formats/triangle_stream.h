// A binary PLY's triangles read a block at a time, for a reference too large to hold whole: its
// vertices are held as the file stores them (float or double: 12 or 24 bytes each, where a
// loaded mesh holds 24 per vertex and 12 per triangle), its faces read from the file per block.
// Every value is checked as read_ply checks it; faces repeating a vertex are dropped and counted.
#pragma once

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "roving/core/triangle_mesh.h"
#include "roving/formats/ply_reader.h"

namespace roving {

class TriangleStream {
 public:
  // Reads the vertices; throws roving::Error naming `path` on a non-finite coordinate or a read
  // that fails.
  TriangleStream(const std::string& path, const PlyTriangleLayout& layout);

  const std::string& path() const { return path_; }
  std::size_t vertex_count() const { return layout_.vertex_count; }
  std::size_t face_count() const { return layout_.face_count; }  // as declared, dropped ones included
  Vec3 position(int vertex) const;

  // The next faces, up to `count` of the file's, as triangles (the dropped ones left out); false
  // when none is left. Throws roving::Error naming the face on a count other than 3 or an index
  // out of range.
  bool next(std::size_t count, std::vector<Triangle>& triangles);
  // Back to the first face, for another pass.
  void rewind();
  // Faces dropped so far for repeating a vertex (of the file's faces read so far in this pass).
  std::size_t dropped_repeated_vertex_faces() const { return dropped_; }

 private:
  std::string path_;
  PlyTriangleLayout layout_;
  struct CloseFile {
    void operator()(std::FILE* file) const { std::fclose(file); }
  };
  std::unique_ptr<std::FILE, CloseFile> file_;  // closed however the constructor ends
  std::vector<float> float_positions_;    // x y z per vertex, where the file stores float
  std::vector<double> double_positions_;  // or double
  std::vector<char> buffer_;
  std::size_t next_face_ = 0, dropped_ = 0;
};

}  // namespace roving
