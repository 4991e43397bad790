// A reference's triangles read a block at a time, for a reference too large to hold whole: a
// binary PLY's (ply_triangle_stream.h), a binary STL's (stl_triangle_stream.h) or an OBJ's
// (obj_triangle_stream.h). Every value is checked as the whole file's reader checks it; faces
// repeating a vertex are dropped and counted.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "roving/core/triangle_mesh.h"

namespace roving {

// REF's vertices as its whole mesh counts them.
struct VertexCensus {
  std::size_t vertices = 0, unreferenced = 0;
  BoundingBox box;  // of the vertices a kept face uses
};

class TriangleStream {
 public:
  virtual ~TriangleStream() = default;

  const std::string& path() const { return path_; }
  std::size_t face_count() const { return face_count_; }  // the file's, dropped ones included

  // The next faces, up to `count` of the file's, as triangles (the dropped ones left out); false
  // when none is left. Their corners are numbers for position(), below position_count(), valid
  // until the next call. Throws roving::Error naming the file and the face on a bad face.
  virtual bool next(std::size_t count, std::vector<Triangle>& triangles) = 0;
  virtual Vec3 position(int corner) const = 0;
  virtual std::size_t position_count() const = 0;

  // Back to the first face, for another pass.
  void rewind() {
    next_face_ = 0;
    dropped_ = 0;
    triangulated_ = 0;
    restart();
  }
  // Faces dropped so far for repeating a vertex (of the file's faces read so far in this pass), and
  // polygons of more than 3 corners fan-triangulated (an OBJ's).
  std::size_t dropped_repeated_vertex_faces() const { return dropped_; }
  std::size_t triangulated_polygons() const { return triangulated_; }
  // The vertices, counted in the first pass that reads every face (throws before).
  virtual VertexCensus census() const = 0;

 protected:
  TriangleStream(std::string path, std::size_t face_count) : path_(std::move(path)), face_count_(face_count) {}

  virtual void restart() {}  // what rewind() resets beyond the counts

  std::string path_;
  std::size_t face_count_ = 0;
  std::size_t next_face_ = 0, dropped_ = 0, triangulated_ = 0;
};

// `path`'s stream where it is a binary PLY of plain triangles (ply_triangle_layout), a binary STL
// or an OBJ without colour or materials, with more than `more_faces_than` faces; nullptr for any
// other file (read it whole).
std::unique_ptr<TriangleStream> open_triangle_stream(const std::string& path, std::size_t more_faces_than);

}  // namespace roving
