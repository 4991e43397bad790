// Binary PLY triangles a block at a time (ply_triangle_stream.h).
#include "roving/formats/meshes/ply_triangle_stream.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "roving/core/error.h"
#include "roving/core/memory_budget.h"

namespace roving {
namespace {

void read_at(std::FILE* file, const std::string& path, std::uint64_t offset, char* into, std::size_t bytes) {
  if (fseeko(file, static_cast<off_t>(offset), SEEK_SET) != 0 || std::fread(into, 1, bytes, file) != bytes) {
    throw Error(fmt::format("{}: could not read {} bytes at byte {}; the file changed or cannot be read", path, bytes,
                            offset));
  }
}

}  // namespace

PlyTriangleStream::PlyTriangleStream(const std::string& path, const PlyTriangleLayout& layout)
    : TriangleStream(path, layout.face_count), layout_(layout), file_(std::fopen(path.c_str(), "rb")) {
  if (!file_) throw Error(fmt::format("{}: cannot open the file", path));
  if (layout.vertex_count > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw Error(fmt::format("{}: {} vertices; at most {} are supported", path, layout.vertex_count,
                            std::numeric_limits<int>::max()));
  }
  require_memory(fmt::format("{}: reading", path), (layout.coordinates_double ? 24.125 : 12.125) * layout.vertex_count,
                 fmt::format("{} vertices", layout.vertex_count));
  (layout.coordinates_double ? double_positions_.resize(3 * layout.vertex_count)
                             : float_positions_.resize(3 * layout.vertex_count));
  referenced_.assign(layout.vertex_count, false);
  // Read a million vertices at a time, each block's copied and checked on every core; where one
  // is not finite, the first such is named.
  constexpr std::size_t kBlock = 1 << 20;
  for (std::size_t first = 0; first < layout.vertex_count; first += kBlock) {
    const std::size_t count = std::min(kBlock, layout.vertex_count - first);
    buffer_.resize(count * layout.vertex_stride);
    read_at(file_.get(), path, layout.vertices_at + first * layout.vertex_stride, buffer_.data(), buffer_.size());
    const auto copy = [&](std::size_t i, double xyz[3]) {
      const char* item = buffer_.data() + i * layout.vertex_stride;
      for (int axis = 0; axis < 3; ++axis) {
        const char* at = item + layout.coordinate_offset[axis];
        if (layout.coordinates_double) {
          std::memcpy(&double_positions_[3 * (first + i) + axis], at, sizeof(double));
          xyz[axis] = double_positions_[3 * (first + i) + axis];
        } else {
          std::memcpy(&float_positions_[3 * (first + i) + axis], at, sizeof(float));
          xyz[axis] = float_positions_[3 * (first + i) + axis];
        }
      }
      return std::isfinite(xyz[0]) && std::isfinite(xyz[1]) && std::isfinite(xyz[2]);
    };
    std::atomic<bool> all_finite{true};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 16384), [&](const tbb::blocked_range<std::size_t>& range) {
      bool finite = true;
      for (std::size_t i = range.begin(); i != range.end(); ++i) {
        double xyz[3];
        finite = copy(i, xyz) && finite;
      }
      if (!finite) all_finite = false;
    });
    if (all_finite) continue;
    for (std::size_t i = 0; i < count; ++i) {
      double xyz[3];
      if (!copy(i, xyz)) {
        throw Error(fmt::format("{}: vertex {} has a non-finite coordinate ({}, {}, {}); expected finite numbers",
                                path, first + i, xyz[0], xyz[1], xyz[2]));
      }
    }
  }
}

Vec3 PlyTriangleStream::position(int vertex) const {
  const std::size_t at = 3 * static_cast<std::size_t>(vertex);
  if (layout_.coordinates_double) return {double_positions_[at], double_positions_[at + 1], double_positions_[at + 2]};
  return {float_positions_[at], float_positions_[at + 1], float_positions_[at + 2]};
}

bool PlyTriangleStream::next(std::size_t count, std::vector<Triangle>& triangles) {
  triangles.clear();
  if (next_face_ >= layout_.face_count) {
    if (!census_) count_vertices();
    return false;
  }
  count = std::min(count, layout_.face_count - next_face_);
  constexpr std::size_t kItem = 1 + 3 * 4;
  buffer_.resize(count * kItem);
  read_at(file_.get(), path_, layout_.faces_at + next_face_ * kItem, buffer_.data(), buffer_.size());
  triangles.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t face = next_face_ + i;
    const char* raw = buffer_.data() + i * kItem;
    if (raw[0] != 3) {
      // The file's size holds 13 bytes a face: a count other than 3 means it is not what it seemed.
      throw Error(fmt::format("{}: face {} has {} corners; expected a triangle where the file's size holds only "
                              "triangles",
                              path_, face, static_cast<unsigned>(static_cast<unsigned char>(raw[0]))));
    }
    std::uint32_t index[3];
    std::memcpy(index, raw + 1, sizeof index);
    for (const std::uint32_t v : index) {
      const long long given = layout_.indices_signed ? static_cast<long long>(static_cast<std::int32_t>(v)) : v;
      if (given < 0 || static_cast<unsigned long long>(given) >= layout_.vertex_count) {
        throw Error(fmt::format("{}: face {} refers to vertex {}; expected an index in [0, {})", path_, face, given,
                                layout_.vertex_count));
      }
    }
    if (index[0] == index[1] || index[1] == index[2] || index[0] == index[2]) {
      ++dropped_;
      continue;
    }
    triangles.push_back({static_cast<int>(index[0]), static_cast<int>(index[1]), static_cast<int>(index[2])});
    if (!census_) {
      for (const std::uint32_t v : index) referenced_[v] = true;
    }
  }
  next_face_ += count;
  return true;
}

void PlyTriangleStream::count_vertices() {
  VertexCensus census;
  census.vertices = layout_.vertex_count;
  for (std::size_t v = 0; v < referenced_.size(); ++v) {
    if (referenced_[v]) {
      census.box.extend(position(static_cast<int>(v)));
    } else {
      ++census.unreferenced;
    }
  }
  census_ = census;
  referenced_ = {};
}

VertexCensus PlyTriangleStream::census() const {
  if (!census_) throw std::logic_error("PlyTriangleStream::census before a whole pass");
  return *census_;
}

}  // namespace roving
