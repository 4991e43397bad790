// Internal: a uniform grid of triangle buckets, walked along a segment (Amanatides and Woo's
// 3D DDA), to find the few triangles that can reach one surface-roving camera's view volume.
#pragma once

#include <cstdint>
#include <vector>

#include "roving/core/triangle_mesh.h"
#include "roving/gl/depth_renderer.h"

namespace roving {

class TriangleGrid {
 public:
  // About `triangles_per_cell` triangles per occupied cell on average; each triangle is listed
  // in every cell its box (inflated by `margin` of a cell) meets, so a point of the triangle
  // that rounding puts in a neighbouring cell is still found.
  explicit TriangleGrid(const TriangleMesh& mesh, double triangles_per_cell = 2.0, double margin = 1e-3);
  // Only the mesh's triangles `faces` (listed by their ids in the mesh), over their own box, each
  // listed also in the cells within `reach` (model units) of its box.
  TriangleGrid(const TriangleMesh& mesh, const std::vector<std::uint32_t>& faces, double reach);

  double cell_size() const { return cell_; }
  // The buckets as the compute pass walks them (DepthRenderer::upload_grid()); they point into this grid.
  GridBuckets buckets() const {
    return {origin_, cell_, {dims_[0], dims_[1], dims_[2]}, &offsets_, &entries_};
  }

  // Calls visit(triangle) for every triangle listed in a cell that the segment a -> b passes
  // through; a triangle can be visited more than once.
  template <class Visit>
  void for_each_along(const Vec3& a, const Vec3& b, Visit&& visit) const {
    walk(a, b, [&](std::size_t cell) {
      for (std::uint32_t i = offsets_[cell]; i < offsets_[cell + 1]; ++i) visit(entries_[i]);
    });
  }

 private:
  template <class VisitCell>
  void walk(const Vec3& a, const Vec3& b, VisitCell&& visit_cell) const;
  // Every triangle of the mesh where `faces` is null.
  void build(const TriangleMesh& mesh, const std::vector<std::uint32_t>* faces, double triangles_per_cell,
             double margin, double reach);
  std::size_t cell_index(int x, int y, int z) const { return (std::size_t(z) * dims_[1] + y) * dims_[0] + x; }

  Vec3 origin_;
  double cell_ = 1;
  int dims_[3] = {1, 1, 1};
  std::vector<std::uint32_t> offsets_;  // cell c lists entries_[offsets_[c] .. offsets_[c + 1])
  std::vector<std::uint32_t> entries_;
};

template <class VisitCell>
void TriangleGrid::walk(const Vec3& a, const Vec3& b, VisitCell&& visit_cell) const {
  // Clip the segment to the grid's box (slabs), then step cell to cell.
  const Vec3 delta = b - a;
  double enter = 0, leave = 1;
  for (int axis = 0; axis < 3; ++axis) {
    const double low = origin_[axis], high = origin_[axis] + dims_[axis] * cell_;
    if (delta[axis] == 0) {
      if (a[axis] < low || a[axis] > high) return;
      continue;
    }
    double t0 = (low - a[axis]) / delta[axis], t1 = (high - a[axis]) / delta[axis];
    if (t0 > t1) std::swap(t0, t1);
    enter = std::max(enter, t0);
    leave = std::min(leave, t1);
    if (enter > leave) return;
  }
  const Vec3 start = a + enter * delta;
  int cell[3], step[3];
  double next[3], increment[3];
  const double length = leave - enter;
  for (int axis = 0; axis < 3; ++axis) {
    const double position = (start[axis] - origin_[axis]) / cell_;
    cell[axis] = std::clamp(static_cast<int>(std::floor(position)), 0, dims_[axis] - 1);
    const double d = delta[axis] / cell_;  // cells per unit of t
    if (d > 0) {
      step[axis] = 1;
      next[axis] = (cell[axis] + 1 - position) / d;
      increment[axis] = 1 / d;
    } else if (d < 0) {
      step[axis] = -1;
      next[axis] = (position - cell[axis]) / -d;
      increment[axis] = -1 / d;
    } else {
      step[axis] = 0;
      next[axis] = increment[axis] = std::numeric_limits<double>::infinity();
    }
  }
  for (double t = 0;;) {
    visit_cell(cell_index(cell[0], cell[1], cell[2]));
    const int axis = next[0] < next[1] ? (next[0] < next[2] ? 0 : 2) : (next[1] < next[2] ? 1 : 2);
    t = next[axis];
    if (t > length) return;
    cell[axis] += step[axis];
    if (cell[axis] < 0 || cell[axis] >= dims_[axis]) return;
    next[axis] += increment[axis];
  }
}

}  // namespace roving
