// An OBJ's triangles a block of faces at a time (triangle_stream.h). A first pass reads the
// vertices (24 bytes each, as a whole read holds them) and counts the faces; each block then
// parses its faces from the text where the last one stopped (the first block from the first face,
// past the vertices before it), fan-triangulated and checked as read_obj does, with the vertices
// and texture coordinates defined so far. The file is mapped, and the pages a pass has left
// behind are handed back, so the text never sits in memory whole.
// Files with vertex colours or materials are read whole (what they carry needs every face).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "roving/formats/files/file_bytes.h"
#include "roving/formats/meshes/triangle_stream.h"

namespace roving {

class ObjTriangleStream final : public TriangleStream {
 public:
  // The stream of `path` where it has more than `more_faces_than` faces and no vertex colour,
  // 'mtllib' or 'usemtl'; nullptr otherwise. Throws roving::Error naming the line of a bad 'v'
  // or 'vt' record.
  static std::unique_ptr<ObjTriangleStream> open(const std::string& path, std::size_t more_faces_than);

  bool next(std::size_t count, std::vector<Triangle>& triangles) override;
  Vec3 position(int vertex) const override { return positions_[vertex]; }
  std::size_t position_count() const override { return positions_.size(); }
  VertexCensus census() const override;

 private:
  explicit ObjTriangleStream(const std::string& path);
  // Back to the start of the text; the pages read so far are handed back.
  void restart() override;
  // Hands the mapped pages from the last call's `end` to `end` back (they stay in the page cache).
  void release_before(std::size_t end);

  // Where a pass is in the text: the byte, the lines before it, the records defined before it.
  struct Place {
    std::size_t offset = 0, lines = 0, vertices = 0, texture_coordinates = 0;
  };
  FileBytes file_;
  std::vector<Vec3> positions_;
  Place at_, first_face_;  // a pass over the faces starts at the first (the vertices before it are read)
  std::size_t released_ = 0;       // pages before this byte were handed back in this pass
  std::vector<bool> referenced_;   // by a kept face, until the first pass ends
  std::optional<VertexCensus> census_;
  std::vector<int> corners_, corner_uv_;
};

}  // namespace roving
