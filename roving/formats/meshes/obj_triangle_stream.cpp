// An OBJ's triangles a block of faces at a time (obj_triangle_stream.h).
#include "roving/formats/meshes/obj_triangle_stream.h"

#include <fmt/format.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <stdexcept>
#include <string_view>

#include "roving/core/error.h"
#include "roving/core/memory_budget.h"
#include "roving/formats/meshes/obj_records.h"

namespace roving {

ObjTriangleStream::ObjTriangleStream(const std::string& path)
    : TriangleStream(path, 0), file_(path, "a .obj mesh") {}

std::unique_ptr<ObjTriangleStream> ObjTriangleStream::open(const std::string& path, std::size_t more_faces_than) {
  std::unique_ptr<ObjTriangleStream> stream(new ObjTriangleStream(path));
  const std::string_view text = stream->file_.bytes();
  if ((text.size() + 1) / 8 <= more_faces_than) return nullptr;  // "f 1 2 3\n": no face takes fewer bytes
  // The faces and vertices first, counted (a quick pass: lines whose first token is 'f' or 'v'), then
  // the vertices read into memory reserved for them: at 5 10^7 vertices, a vector grown by doubling
  // held 2.4 GB while it moved.
  LineCursor counting(text);
  std::size_t vertices = 0;
  for (std::string_view line; counting.next_line(line);) {
    const std::string_view keyword = next_token(line);
    stream->face_count_ += keyword == "f";
    vertices += keyword == "v";
    if ((counting.line_number() & 0xFFFF) == 0) stream->release_before(counting.offset());
  }
  stream->restart();
  if (stream->face_count_ <= more_faces_than) return nullptr;
  require_memory(fmt::format("{}: reading", path), 24.125 * static_cast<double>(vertices),
                 fmt::format("{} vertices", vertices));
  stream->positions_.reserve(vertices);
  // The vertices, checked as read_obj checks them.
  LineCursor lines(text);
  const obj::Fail fail = obj::line_error(path, lines);
  Place before_line;  // where the line just read starts, and the records before it
  bool found_face = false;
  for (std::string_view line; lines.next_line(line); before_line.offset = lines.offset(), ++before_line.lines) {
    std::string_view rest = line;
    const std::string_view keyword = next_token(rest);
    if (keyword == "v") {
      Vec3 position;
      double rgb[3];
      if (obj::parse_vertex(rest, position, rgb, fail)) return nullptr;  // a colour: read whole
      stream->positions_.push_back(position);
      ++before_line.vertices;
    } else if (keyword == "vt") {
      double uv[2];
      obj::parse_texture_coordinate(rest, uv, fail);
      ++before_line.texture_coordinates;
    } else if (keyword == "mtllib" || keyword == "usemtl") {
      return nullptr;
    } else if (keyword == "f" && !found_face) {
      stream->first_face_ = before_line;
      found_face = true;
    }
    if ((lines.line_number() & 0xFFFF) == 0) stream->release_before(lines.offset());
  }
  stream->restart();
  for (std::size_t v = 0; v < stream->positions_.size(); ++v) {
    if (!stream->positions_[v].allFinite()) {
      const Vec3& p = stream->positions_[v];
      throw Error(fmt::format("{}: vertex {} has a non-finite coordinate ({}, {}, {}); expected finite numbers", path,
                              v, p.x(), p.y(), p.z()));
    }
  }
  stream->referenced_.assign(stream->positions_.size(), false);
  return stream;
}

bool ObjTriangleStream::next(std::size_t count, std::vector<Triangle>& triangles) {
  triangles.clear();
  const std::string_view text = file_.bytes();
  LineCursor lines(text, at_.offset);
  const obj::Fail fail = obj::line_error(path_, lines, at_.lines);
  std::size_t faces = 0;
  std::string_view line;
  while (faces < count && lines.next_line(line)) {
    std::string_view rest = line;
    const std::string_view keyword = next_token(rest);
    if (keyword == "v") {
      ++at_.vertices;
    } else if (keyword == "vt") {
      ++at_.texture_coordinates;
    } else if (keyword == "f") {
      ++faces;
      obj::parse_face(rest, static_cast<long long>(at_.vertices), static_cast<long long>(at_.texture_coordinates),
                      corners_, corner_uv_, fail);
      if (obj::repeats_a_vertex(corners_)) {
        ++dropped_;
        continue;
      }
      if (corners_.size() > 3) ++triangulated_;
      for (std::size_t i = 1; i + 1 < corners_.size(); ++i) {
        triangles.push_back({corners_[0], corners_[i], corners_[i + 1]});
      }
      if (!census_) {
        for (const int v : corners_) referenced_[v] = true;
      }
    }
    if ((lines.line_number() & 0xFFFF) == 0) release_before(lines.offset());  // a long run of other lines
  }
  at_.lines += lines.line_number();
  at_.offset = lines.offset();
  release_before(at_.offset);
  next_face_ += faces;
  if (faces > 0) return true;
  if (!census_) {
    VertexCensus census;
    census.vertices = positions_.size();
    for (std::size_t v = 0; v < positions_.size(); ++v) {
      if (referenced_[v]) {
        census.box.extend(positions_[v]);
      } else {
        ++census.unreferenced;
      }
    }
    census_ = census;
    referenced_ = {};
  }
  return false;
}

void ObjTriangleStream::release_before(std::size_t end) {
  static const std::size_t page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  const std::size_t from = released_ / page * page, to = end / page * page;
  if (to <= from) return;
  madvise(const_cast<char*>(file_.bytes().data()) + from, to - from, MADV_DONTNEED);
  released_ = to;
}

void ObjTriangleStream::restart() {
  release_before(file_.size());
  at_ = first_face_;
  released_ = 0;
}

VertexCensus ObjTriangleStream::census() const {
  if (!census_) throw std::logic_error("ObjTriangleStream::census before a whole pass");
  return *census_;
}

}  // namespace roving
