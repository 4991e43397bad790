// A streamed reference's faces as small meshes, a block at a time, for what needs REF's triangles
// rather than its samples (the certified Hausdorff bound): each block holds its own faces, in the
// file's order, and the vertices they use, numbered in order of first use.
#pragma once

#include <cstddef>
#include <vector>

#include "roving/core/triangle_mesh.h"
#include "roving/formats/meshes/triangle_stream.h"

namespace roving {

class MeshBlocks {
 public:
  // From the stream's first face, `chunk_faces` (> 0) of the file's faces a block.
  MeshBlocks(TriangleStream& stream, std::size_t chunk_faces);

  // The next block (its faces that repeat no vertex); false when none is left.
  bool next(TriangleMesh& block);
  std::size_t faces_read() const { return faces_read_; }  // of the file's, so far

 private:
  TriangleStream& stream_;
  std::size_t chunk_faces_;
  std::size_t faces_read_ = 0;
  std::vector<int> local_;  // the block's number of each of the stream's positions, -1 where unused
  std::vector<Triangle> triangles_;
};

}  // namespace roving
