// Triangle mesh construction, validation and derived per-face / per-vertex data.
#include "roving/core/triangle_mesh.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "roving/core/error.h"

namespace roving {

TriangleMesh::TriangleMesh(std::vector<Vec3> positions, std::vector<Triangle> triangles,
                           const std::string& source)
    : positions_(std::move(positions)), triangles_(std::move(triangles)) {
  for (std::size_t i = 0; i < positions_.size(); ++i) {
    if (!positions_[i].allFinite()) {
      throw Error(
          fmt::format("{}: vertex {} has a non-finite coordinate ({}, {}, {}); expected "
                      "finite numbers",
                      source, i, positions_[i].x(), positions_[i].y(), positions_[i].z()));
    }
  }
  const int vertex_count = static_cast<int>(positions_.size());
  face_normals_.resize(triangles_.size());
  face_areas_.resize(triangles_.size());
  // Indices, face normals and areas on all cores (at 10 M triangles this pass and the first
  // touch of its memory were most of a load); sums and the scatter to vertices stay in order.
  std::atomic<std::size_t> first_bad_face{triangles_.size()};
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, triangles_.size(), 4096),
      [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t f = range.begin(); f != range.end(); ++f) {
          const Triangle& t = triangles_[f];
          if (t[0] < 0 || t[1] < 0 || t[2] < 0 || t[0] >= vertex_count || t[1] >= vertex_count ||
              t[2] >= vertex_count) {
            std::size_t seen = first_bad_face.load();
            while (f < seen && !first_bad_face.compare_exchange_weak(seen, f)) {
            }
            continue;
          }
          const Vec3 cross = (positions_[t[1]] - positions_[t[0]]).cross(positions_[t[2]] - positions_[t[0]]);
          const double twice_area = cross.norm();
          face_areas_[f] = 0.5 * twice_area;
          // Degenerate: the area vanishes at double precision relative to the squared
          // longest edge, so that its normal would be rounding noise.
          const double longest_edge_squared = std::max({(positions_[t[1]] - positions_[t[0]]).squaredNorm(),
                                                        (positions_[t[2]] - positions_[t[1]]).squaredNorm(),
                                                        (positions_[t[0]] - positions_[t[2]]).squaredNorm()});
          const bool degenerate = !(twice_area > 1e-12 * longest_edge_squared);
          face_normals_[f] = degenerate ? Vec3::Zero() : Vec3(cross / twice_area);
        }
      });
  if (first_bad_face < triangles_.size()) {
    const std::size_t f = first_bad_face;
    for (int corner : triangles_[f]) {
      if (corner < 0 || corner >= vertex_count) {
        throw Error(fmt::format("{}: triangle {} refers to vertex {}; expected an index in [0, {})", source,
                                f, corner, vertex_count));
      }
    }
  }

  vertex_normals_.assign(positions_.size(), Vec3::Zero());
  vertex_referenced_.assign(positions_.size(), false);
  for (std::size_t f = 0; f < triangles_.size(); ++f) {
    const Triangle& t = triangles_[f];
    total_area_ += face_areas_[f];
    if (face_normals_[f].isZero(0)) ++degenerate_triangles_;
    const Vec3 cross = (positions_[t[1]] - positions_[t[0]]).cross(positions_[t[2]] - positions_[t[0]]);
    for (int corner : t) {
      vertex_normals_[corner] += cross;  // |cross| = 2 * area: area weighting for free
      vertex_referenced_[corner] = true;
    }
  }
  for (std::size_t v = 0; v < positions_.size(); ++v) {
    if (!vertex_referenced_[v]) {
      ++unreferenced_vertices_;
      continue;
    }
    bounding_box_.extend(positions_[v]);
    const double length = vertex_normals_[v].norm();
    vertex_normals_[v] = length > 0 ? Vec3(vertex_normals_[v] / length) : Vec3::Zero();
  }
}

TriangleMesh TriangleMesh::transformed(const Vec3& origin, double scale) const {
  std::vector<Vec3> moved(positions_.size());
  for (std::size_t i = 0; i < positions_.size(); ++i) moved[i] = scale * (positions_[i] - origin);
  return TriangleMesh(std::move(moved), triangles_);
}

}  // namespace roving
