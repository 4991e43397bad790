// Triangle mesh: positions, triangles and the per-face / per-vertex quantities every method uses.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "roving/core/shared_array.h"
#include "roving/core/texture.h"

namespace roving {

using Vec3 = Eigen::Vector3d;
using Triangle = std::array<int, 3>;
// Colour (texture.h): a colour as its stored encoding, sRGB code values on [0, 255] (the 8-bit
// values MPEG's metrics compare), in float so that a file's float or 16-bit colours keep their
// fraction of a step.

struct BoundingBox {
  Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 max = Vec3::Constant(-std::numeric_limits<double>::infinity());

  void extend(const Vec3& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  bool empty() const { return !(min.array() <= max.array()).all(); }
  Vec3 size() const { return max - min; }
  Vec3 centre() const { return 0.5 * (min + max); }
  double diagonal() const { return size().norm(); }
};

// An indexed triangle soup with derived data. Construction validates: every coordinate finite,
// every index within [0, vertex count); throws roving::Error naming `source` otherwise.
// Degenerate (zero-area) triangles are kept: they are harmless to intersect, and sampling skips them.
class TriangleMesh {
 public:
  TriangleMesh() = default;
  TriangleMesh(std::vector<Vec3> positions, std::vector<Triangle> triangles,
               const std::string& source = "mesh");
  // What reports name of a mesh whose geometry is read elsewhere a block at a time (streaming/),
  // as a mesh is after release_geometry(): its counts, box and area alone.
  struct Summary {
    std::size_t vertices = 0, triangles = 0, unreferenced_vertices = 0, degenerate_triangles = 0;
    BoundingBox box;
    double area = 0;
  };
  explicit TriangleMesh(const Summary& summary);
  // Faces whose areas are summed together before the blocks' sums are added in order: the total
  // area is the same whatever the threads (and a streamed pass can sum it alike).
  static constexpr std::size_t kAreaBlock = 4096;
  // The same from arrays that may be a caller's memory (shared_array.h), read in place.
  TriangleMesh(SharedArray<Vec3> positions, SharedArray<Triangle> triangles, const std::string& source = "mesh");

  const SharedArray<Vec3>& positions() const { return positions_; }
  const SharedArray<Triangle>& triangles() const { return triangles_; }
  // Counts as loaded (they stay after release_geometry(); the arrays do not).
  std::size_t vertex_count() const { return vertex_count_; }
  std::size_t triangle_count() const { return triangle_count_; }

  // Hands over the positions (a copy where they are lent) and frees the triangles, keeping what reports name (counts, area,
  // box, colour): for a reference nothing reads once it is sampled, so that the query runs
  // without it (240 MB at 10 M triangles). No method that reads geometry may be called after.
  std::vector<Vec3> release_geometry();

  // Unit face normal (right-hand rule); zero for a degenerate face. Face normals, areas and
  // vertex normals are computed when asked rather than stored: at 10 M triangles storing them
  // took 44 bytes a triangle, a quarter of a measurement's peak memory.
  Vec3 face_normal(std::size_t face) const;
  double face_area(std::size_t face) const;
  // Area-weighted average of the incident face normals, normalised; zero for unreferenced
  // vertices. Computed on each call (one pass over the triangles), with, if asked, a third of
  // each vertex's incident area (what a vertex sample stands for).
  std::vector<Vec3> vertex_normals(std::vector<double>* third_areas = nullptr) const;
  // True for vertices that at least one triangle uses.
  const std::vector<bool>& vertex_referenced() const { return vertex_referenced_; }
  std::size_t unreferenced_vertex_count() const { return unreferenced_vertices_; }
  std::size_t degenerate_triangle_count() const { return degenerate_triangles_; }
  // Box over the referenced vertices only (stray points do not inflate h).
  const BoundingBox& bounding_box() const { return bounding_box_; }
  double total_area() const { return total_area_; }

  Vec3 centroid(std::size_t face) const {
    const Triangle& t = triangles_[face];
    return centroid_of(positions_[t[0]], positions_[t[1]], positions_[t[2]]);
  }

  // Per-vertex colours (empty: the model has none). set_vertex_colours throws roving::Error naming
  // `source` unless there is one per vertex, each channel finite and within [0, 255].
  const std::vector<Colour>& vertex_colours() const { return vertex_colours_; }
  void set_vertex_colours(std::vector<Colour> colours, const std::string& source = "mesh");
  // Hands the vertex colours over; the mesh has none after.
  std::vector<Colour> release_vertex_colours() { return std::move(vertex_colours_); }
  // Materials and texture coordinates (null: none). set_texture_mapping throws roving::Error naming
  // `source` unless there are three finite coordinates per triangle and a valid material per
  // triangle, every factor within [0, 255]. A face's colour is then its vertex colour (white when
  // none) times its material's, in code values (colour.h).
  const TextureMapping* texture_mapping() const { return texture_mapping_.get(); }
  void set_texture_mapping(TextureMapping mapping, const std::string& source = "mesh");
  bool has_colour() const { return !vertex_colours_.empty() || texture_mapping_; }

  // The same mesh with every position mapped p -> scale * (p - origin).
  TriangleMesh transformed(const Vec3& origin, double scale) const;

  // A face from its corners a, b, c, by the arithmetic every face normal, area, centroid and face
  // sample uses, for faces read a block at a time and never held as a mesh (streaming/).
  struct FaceShape {
    Vec3 cross;  // (b - a) x (c - a)
    double twice_area;
    bool degenerate;
    Vec3 normal() const { return degenerate ? Vec3::Zero() : Vec3(cross / twice_area); }
    double area() const { return 0.5 * twice_area; }
  };
  static FaceShape shape_of(const Vec3& a, const Vec3& b, const Vec3& c);
  static Vec3 centroid_of(const Vec3& a, const Vec3& b, const Vec3& c) { return (a + b + c) / 3.0; }

 private:
  FaceShape face_shape(std::size_t face) const;

  SharedArray<Vec3> positions_;
  SharedArray<Triangle> triangles_;
  std::size_t vertex_count_ = 0, triangle_count_ = 0;
  std::vector<Colour> vertex_colours_;
  std::shared_ptr<const TextureMapping> texture_mapping_;  // shared: transformed() copies keep it
  std::vector<bool> vertex_referenced_;
  std::size_t unreferenced_vertices_ = 0;
  std::size_t degenerate_triangles_ = 0;
  BoundingBox bounding_box_;
  double total_area_ = 0;
};

}  // namespace roving
