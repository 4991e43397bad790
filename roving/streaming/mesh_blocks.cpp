// A streamed reference's faces as one small mesh per block (mesh_blocks.h).
#include "mesh_blocks.h"

#include <algorithm>

namespace roving {

MeshBlocks::MeshBlocks(TriangleStream& stream, std::size_t chunk_faces)
    : stream_(stream), chunk_faces_(std::max<std::size_t>(chunk_faces, 1)) {
  stream_.rewind();
}

bool MeshBlocks::next(TriangleMesh& block) {
  if (!stream_.next(chunk_faces_, triangles_)) return false;
  faces_read_ = std::min(faces_read_ + chunk_faces_, stream_.face_count());
  if (local_.size() < stream_.position_count()) local_.resize(stream_.position_count(), -1);
  std::vector<int> used;  // the file's vertices, in the block's order
  std::vector<Vec3> positions;
  for (Triangle& t : triangles_) {
    for (int& corner : t) {
      int& local = local_[corner];
      if (local < 0) {
        local = static_cast<int>(used.size());
        used.push_back(corner);
        positions.push_back(stream_.position(corner));
      }
      corner = local;
    }
  }
  for (const int v : used) local_[v] = -1;  // only what this block touched: the next starts clean
  block = TriangleMesh(std::move(positions), std::move(triangles_), stream_.path());
  triangles_ = {};
  return true;
}

}  // namespace roving
