// Uniform grid of triangle buckets (counting sort into one flat array).
#include "triangle_grid.h"

#include <algorithm>
#include <cmath>

namespace roving {

TriangleGrid::TriangleGrid(const TriangleMesh& mesh, double triangles_per_cell, double margin) {
  build(mesh, nullptr, triangles_per_cell, margin, 0);
}

TriangleGrid::TriangleGrid(const TriangleMesh& mesh, const std::vector<std::uint32_t>& faces, double reach) {
  build(mesh, &faces, 2.0, 1e-3, reach);
}

void TriangleGrid::build(const TriangleMesh& mesh, const std::vector<std::uint32_t>* faces,
                         double triangles_per_cell, double margin, double reach) {
  const std::size_t count = faces ? faces->size() : mesh.triangle_count();
  const auto face = [&](std::size_t i) { return faces ? (*faces)[i] : static_cast<std::uint32_t>(i); };
  BoundingBox box = mesh.bounding_box();
  if (faces) {
    box = BoundingBox();
    for (const std::uint32_t f : *faces) {
      for (const std::uint32_t v : mesh.triangles()[f]) box.extend(mesh.positions()[v]);
    }
    if (faces->empty()) box.extend(Vec3::Zero());
  }
  const Vec3 size = box.size().cwiseMax(1e-12 * box.diagonal()).cwiseMax(1e-300);
  // About count / triangles_per_cell cubic cells over the box, at most 256 a side; the grid
  // overhangs the box by `margin` of a cell on each side, so that inflated boxes fit.
  const double estimate = std::cbrt(size.prod() / std::max(1.0, count / triangles_per_cell));
  const double pad = std::max(margin * estimate, reach);
  origin_ = box.min - Vec3::Constant(pad);
  cell_ = 0;
  for (int axis = 0; axis < 3; ++axis) {
    dims_[axis] = std::clamp(static_cast<int>(std::ceil(size[axis] / estimate)), 1, 256);
    cell_ = std::max(cell_, (size[axis] + 2 * pad) / dims_[axis]);
  }

  const auto cell_range = [&](const Triangle& t, int low[3], int high[3]) {
    const auto& p = mesh.positions();
    for (int axis = 0; axis < 3; ++axis) {
      const double lo = std::min({p[t[0]][axis], p[t[1]][axis], p[t[2]][axis]}) - pad;
      const double hi = std::max({p[t[0]][axis], p[t[1]][axis], p[t[2]][axis]}) + pad;
      low[axis] = std::clamp(static_cast<int>(std::floor((lo - origin_[axis]) / cell_)), 0, dims_[axis] - 1);
      high[axis] = std::clamp(static_cast<int>(std::floor((hi - origin_[axis]) / cell_)), 0, dims_[axis] - 1);
    }
  };
  offsets_.assign(std::size_t(dims_[0]) * dims_[1] * dims_[2] + 1, 0);
  int low[3], high[3];
  for (std::size_t i = 0; i < count; ++i) {  // count
    cell_range(mesh.triangles()[face(i)], low, high);
    for (int z = low[2]; z <= high[2]; ++z)
      for (int y = low[1]; y <= high[1]; ++y)
        for (int x = low[0]; x <= high[0]; ++x) ++offsets_[cell_index(x, y, z) + 1];
  }
  for (std::size_t c = 1; c < offsets_.size(); ++c) offsets_[c] += offsets_[c - 1];
  entries_.resize(offsets_.back());
  std::vector<std::uint32_t> fill(offsets_.begin(), offsets_.end() - 1);
  for (std::size_t i = 0; i < count; ++i) {  // place
    cell_range(mesh.triangles()[face(i)], low, high);
    for (int z = low[2]; z <= high[2]; ++z)
      for (int y = low[1]; y <= high[1]; ++y)
        for (int x = low[0]; x <= high[0]; ++x) entries_[fill[cell_index(x, y, z)]++] = face(i);
  }
}

}  // namespace roving
