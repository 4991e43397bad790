// Triangle mesh construction, validation and derived per-face / per-vertex data.
#include "roving/core/triangle_mesh.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "roving/core/error.h"

namespace roving {

TriangleMesh::TriangleMesh(std::vector<Vec3> positions, std::vector<Triangle> triangles,
                           const std::string& source)
    : TriangleMesh(SharedArray<Vec3>(std::move(positions)), SharedArray<Triangle>(std::move(triangles)), source) {}

TriangleMesh::TriangleMesh(const Summary& summary)
    : vertex_count_(summary.vertices),
      triangle_count_(summary.triangles),
      unreferenced_vertices_(summary.unreferenced_vertices),
      degenerate_triangles_(summary.degenerate_triangles),
      bounding_box_(summary.box),
      total_area_(summary.area) {}

TriangleMesh::TriangleMesh(SharedArray<Vec3> positions, SharedArray<Triangle> triangles, const std::string& source)
    : positions_(std::move(positions)),
      triangles_(std::move(triangles)),
      vertex_count_(positions_.size()),
      triangle_count_(triangles_.size()) {
  for (std::size_t i = 0; i < positions_.size(); ++i) {
    if (!positions_[i].allFinite()) {
      throw Error(
          fmt::format("{}: vertex {} has a non-finite coordinate ({}, {}, {}); expected "
                      "finite numbers",
                      source, i, positions_[i].x(), positions_[i].y(), positions_[i].z()));
    }
  }
  const int vertex_count = static_cast<int>(positions_.size());
  // Indices, areas and degenerate faces on all cores (at 10 M triangles this pass and the first
  // touch of its memory were most of a load), in fixed blocks whose sums are added in order, so
  // that the total area does not depend on the threads.
  constexpr std::size_t kBlock = kAreaBlock;
  const std::size_t blocks = (triangles_.size() + kBlock - 1) / kBlock;
  std::vector<double> block_area(blocks, 0.0);
  std::vector<std::size_t> block_degenerate(blocks, 0);
  std::atomic<std::size_t> first_bad_face{triangles_.size()};
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t block) {
    for (std::size_t f = block * kBlock; f < std::min(triangles_.size(), (block + 1) * kBlock); ++f) {
      const Triangle& t = triangles_[f];
      if (t[0] < 0 || t[1] < 0 || t[2] < 0 || t[0] >= vertex_count || t[1] >= vertex_count ||
          t[2] >= vertex_count) {
        std::size_t seen = first_bad_face.load();
        while (f < seen && !first_bad_face.compare_exchange_weak(seen, f)) {
        }
        continue;
      }
      const FaceShape shape = face_shape(f);
      block_area[block] += shape.area();
      block_degenerate[block] += shape.degenerate;
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
  for (std::size_t block = 0; block < blocks; ++block) {
    total_area_ += block_area[block];
    degenerate_triangles_ += block_degenerate[block];
  }

  vertex_referenced_.assign(positions_.size(), false);
  for (const Triangle& t : triangles_) {
    for (int corner : t) vertex_referenced_[corner] = true;
  }
  for (std::size_t v = 0; v < positions_.size(); ++v) {
    if (vertex_referenced_[v]) {
      bounding_box_.extend(positions_[v]);
    } else {
      ++unreferenced_vertices_;
    }
  }
}

TriangleMesh::FaceShape TriangleMesh::face_shape(std::size_t face) const {
  const Triangle& t = triangles_[face];
  return shape_of(positions_[t[0]], positions_[t[1]], positions_[t[2]]);
}

TriangleMesh::FaceShape TriangleMesh::shape_of(const Vec3& a, const Vec3& b, const Vec3& c) {
  FaceShape shape;
  shape.cross = (b - a).cross(c - a);
  shape.twice_area = shape.cross.norm();
  // Degenerate: the area vanishes at double precision relative to the squared longest edge, so
  // that its normal would be rounding noise.
  const double longest_edge_squared =
      std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  shape.degenerate = !(shape.twice_area > 1e-12 * longest_edge_squared);
  return shape;
}

Vec3 TriangleMesh::face_normal(std::size_t face) const {
  return face_shape(face).normal();
}

double TriangleMesh::face_area(std::size_t face) const {
  return face_shape(face).area();
}

std::vector<Vec3> TriangleMesh::vertex_normals(std::vector<double>* third_areas) const {
  std::vector<Vec3> normals(positions_.size(), Vec3::Zero());
  if (third_areas) third_areas->assign(positions_.size(), 0.0);
  // Each thread owns a range of vertices and scans every triangle for the corners in its range:
  // no two threads add to one vertex, and each vertex sums its faces in file order, so the
  // normals are the same bits on any number of threads, with no copy per thread.
  const std::size_t parts = std::max(1, tbb::this_task_arena::max_concurrency());
  const std::size_t per_part = (positions_.size() + parts - 1) / parts;
  tbb::parallel_for(std::size_t{0}, parts, [&](std::size_t part) {
    const auto low = static_cast<int>(part * per_part);
    const auto high = static_cast<int>(std::min(positions_.size(), (part + 1) * per_part));
    for (const Triangle& t : triangles_) {
      const auto mine = [&](int corner) { return corner >= low && corner < high; };
      if (!mine(t[0]) && !mine(t[1]) && !mine(t[2])) continue;
      const Vec3 cross = (positions_[t[1]] - positions_[t[0]]).cross(positions_[t[2]] - positions_[t[0]]);
      const double third_area = 0.5 * cross.norm() / 3.0;
      for (int corner : t) {
        if (!mine(corner)) continue;
        normals[corner] += cross;  // |cross| = 2 * area: area weighting for free
        if (third_areas) (*third_areas)[corner] += third_area;
      }
    }
    for (int v = low; v < high; ++v) {
      const double length = normals[v].norm();
      normals[v] = length > 0 ? Vec3(normals[v] / length) : Vec3::Zero();
    }
  });
  return normals;
}

std::vector<Vec3> TriangleMesh::release_geometry() {
  triangles_ = {};
  return positions_.release();
}

TriangleMesh TriangleMesh::transformed(const Vec3& origin, double scale) const {
  std::vector<Vec3> moved(positions_.size());
  for (std::size_t i = 0; i < positions_.size(); ++i) moved[i] = scale * (positions_[i] - origin);
  TriangleMesh mesh(SharedArray<Vec3>(std::move(moved)), triangles_);
  mesh.vertex_colours_ = vertex_colours_;
  mesh.texture_mapping_ = texture_mapping_;
  return mesh;
}

namespace {
// NaN fails both comparisons.
bool valid_colour(const Colour& c) {
  return (c.array() >= 0).all() && (c.array() <= 255).all();
}
}  // namespace

void TriangleMesh::set_vertex_colours(std::vector<Colour> colours, const std::string& source) {
  if (colours.size() != positions_.size()) {
    throw Error(fmt::format("{}: {} vertex colours for {} vertices; expected one per vertex", source,
                            colours.size(), positions_.size()));
  }
  for (std::size_t i = 0; i < colours.size(); ++i) {
    const Colour& c = colours[i];
    if (!valid_colour(c)) {
      throw Error(
          fmt::format("{}: vertex {} has colour ({}, {}, {}); expected sRGB code values "
                      "within [0, 255]",
                      source, i, c.x(), c.y(), c.z()));
    }
  }
  vertex_colours_ = std::move(colours);
}

void TriangleMesh::set_texture_mapping(TextureMapping mapping, const std::string& source) {
  if (mapping.face_material.size() != triangles_.size() ||
      mapping.corner_uv.size() != 3 * triangles_.size()) {
    throw Error(
        fmt::format("{}: {} materials and {} texture coordinates for {} triangles; expected one "
                    "material and three coordinates per triangle",
                    source, mapping.face_material.size(), mapping.corner_uv.size(), triangles_.size()));
  }
  for (std::size_t f = 0; f < triangles_.size(); ++f) {
    const int m = mapping.face_material[f];
    if (m < 0 || static_cast<std::size_t>(m) >= mapping.materials.size()) {
      throw Error(fmt::format("{}: triangle {} has material {}; expected 0..{}", source, f, m,
                              static_cast<long long>(mapping.materials.size()) - 1));
    }
  }
  for (std::size_t i = 0; i < mapping.corner_uv.size(); ++i) {
    if (!mapping.corner_uv[i].allFinite()) {
      throw Error(fmt::format("{}: triangle {} has a non-finite texture coordinate", source, i / 3));
    }
  }
  for (const Material& material : mapping.materials) {
    if (!valid_colour(material.factor)) {
      throw Error(
          fmt::format("{}: material '{}' has colour factor ({}, {}, {}); expected code values within "
                      "[0, 255]",
                      source, material.name, material.factor.x(), material.factor.y(), material.factor.z()));
    }
    const Texture* t = material.texture.get();
    if (t && (t->width <= 0 || t->height <= 0 || t->rgb.size() != std::size_t(t->width) * t->height * 3)) {
      throw Error(fmt::format("{}: material '{}' has a malformed texture", source, material.name));
    }
  }
  texture_mapping_ = std::make_shared<const TextureMapping>(std::move(mapping));
}

}  // namespace roving
