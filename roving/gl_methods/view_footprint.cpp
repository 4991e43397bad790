// Cells of 8 x 8 pixels marked under each sample's reading, a summed-area table over them, and
// a test of every triangle's projected box against it.
#include "roving/gl_methods/view_footprint.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace roving {

ViewFootprint::ViewFootprint(const OrthoCamera& camera, int resolution, const SampleSet& samples,
                             const std::vector<std::uint32_t>& group, double reach)
    : camera_(camera), resolution_(resolution), cells_((resolution + kCell - 1) / kCell) {
  read_.assign(static_cast<std::size_t>(cells_) * cells_, 0);
  const auto pixel = [&](const Vec3& p) {
    const Vec3 q = camera_.to_normalised(p);
    return Vec3((0.5 * q.x() + 0.5) * resolution_, (0.5 * q.y() + 0.5) * resolution_, 0);
  };
  int low_x = cells_, low_y = cells_, high_x = -1, high_y = -1;
  for (std::uint32_t k : group) {
    const Vec3 a = pixel(samples.positions[k] + reach * samples.normals[k]);
    const Vec3 b = pixel(samples.positions[k] - reach * samples.normals[k]);
    // The reading touches pixels floor(u - 0.5) - 1 .. floor(u - 0.5) + 2 about any point u of
    // the segment (bilinear 2 x 2, crease test 4 x 4): within floor(u) -/+ 2; one more to spare.
    const auto cell = [&](double u, int offset) {
      return std::clamp((static_cast<int>(std::floor(u)) + offset) / kCell, 0, cells_ - 1);
    };
    const double u0 = std::min(a.x(), b.x()), u1 = std::max(a.x(), b.x());
    const double v0 = std::min(a.y(), b.y()), v1 = std::max(a.y(), b.y());
    if (!(u1 >= -kCell && u0 < resolution_ + kCell && v1 >= -kCell && v0 < resolution_ + kCell)) continue;
    const int cx0 = cell(std::max(u0, 0.0), -3), cx1 = cell(std::min(u1, double(resolution_)), 3);
    const int cy0 = cell(std::max(v0, 0.0), -3), cy1 = cell(std::min(v1, double(resolution_)), 3);
    for (int cy = cy0; cy <= cy1; ++cy) {
      for (int cx = cx0; cx <= cx1; ++cx) read_[static_cast<std::size_t>(cy) * cells_ + cx] = 1;
    }
    low_x = std::min(low_x, cx0), high_x = std::max(high_x, cx1);
    low_y = std::min(low_y, cy0), high_y = std::max(high_y, cy1);
  }
  if (high_x >= 0) {
    rect_ = {low_x * kCell, low_y * kCell, std::min((high_x + 1) * kCell, resolution_),
             std::min((high_y + 1) * kCell, resolution_)};
  }
  const int side = cells_ + 1;
  summed_.assign(static_cast<std::size_t>(side) * side, 0);
  for (int cy = 0; cy < cells_; ++cy) {
    for (int cx = 0; cx < cells_; ++cx) {
      summed_[(cy + 1) * side + cx + 1] = read_[cy * cells_ + cx] + summed_[cy * side + cx + 1] +
                                          summed_[(cy + 1) * side + cx] - summed_[cy * side + cx];
    }
  }
}

bool ViewFootprint::covers(int i, int j) const {
  if (i < 0 || j < 0 || i >= resolution_ || j >= resolution_) return false;
  return read_[static_cast<std::size_t>(j / kCell) * cells_ + i / kCell] != 0;
}

bool ViewFootprint::any_cell(int cx0, int cy0, int cx1, int cy1) const {
  cx0 = std::max(cx0, 0), cy0 = std::max(cy0, 0);
  cx1 = std::min(cx1, cells_ - 1), cy1 = std::min(cy1, cells_ - 1);
  if (cx0 > cx1 || cy0 > cy1) return false;
  const int side = cells_ + 1;
  return summed_[(cy1 + 1) * side + cx1 + 1] - summed_[cy0 * side + cx1 + 1] - summed_[(cy1 + 1) * side + cx0] +
             summed_[cy0 * side + cx0] >
         0;
}

std::vector<std::uint32_t> ViewFootprint::triangles_reaching(const TriangleMesh& mesh) const {
  if (rect_.empty()) return {};
  // Every vertex in pixel units once, then each triangle's box: the pixels whose centres it can
  // cover lie within [floor(min) - 1, floor(max) + 1] whatever the rasteriser's snapping.
  const auto& positions = mesh.positions();
  std::vector<float> u(positions.size()), v(positions.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, positions.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t k = range.begin(); k != range.end(); ++k) {
                        const Vec3 q = camera_.to_normalised(positions[k]);
                        u[k] = static_cast<float>((0.5 * q.x() + 0.5) * resolution_);
                        v[k] = static_cast<float>((0.5 * q.y() + 0.5) * resolution_);
                      }
                    });
  const auto& triangles = mesh.triangles();
  std::vector<std::uint8_t> keep(triangles.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t t = range.begin(); t != range.end(); ++t) {
                        const Triangle& c = triangles[t];
                        const float u0 = std::min({u[c[0]], u[c[1]], u[c[2]]});
                        const float u1 = std::max({u[c[0]], u[c[1]], u[c[2]]});
                        const float v0 = std::min({v[c[0]], v[c[1]], v[c[2]]});
                        const float v1 = std::max({v[c[0]], v[c[1]], v[c[2]]});
                        const auto cell = [](float x, int offset) {
                          return static_cast<int>(std::floor(std::clamp(x, -1e6f, 1e6f))) + offset;
                        };
                        // Truncating division only errs below 0, where any_cell clamps anyway.
                        keep[t] = any_cell(cell(u0, -1) / kCell, cell(v0, -1) / kCell, cell(u1, 1) / kCell,
                                           cell(v1, 1) / kCell);
                      }
                    });
  std::vector<std::uint32_t> kept;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    if (keep[t]) kept.push_back(static_cast<std::uint32_t>(t));
  }
  return kept;
}

}  // namespace roving
