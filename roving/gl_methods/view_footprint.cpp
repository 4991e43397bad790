// Cells of kCell x kCell pixels marked along each sample's reading, a summed-area table over them, and
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
  // The reading touches pixels floor(u - 0.5) - 1 .. floor(u - 0.5) + 2 about any point u of the
  // segment (bilinear 2 x 2, crease test 4 x 4): within floor(u) -/+ 2. The segment is stepped
  // at most a pixel at a time, so every u is within half a pixel of a step p, and floor(p) -/+ 3
  // holds what u reads.
  const auto mark = [&](double u, double v) {
    const int i = static_cast<int>(std::floor(std::clamp(u, -1e6, 1e6)));
    const int j = static_cast<int>(std::floor(std::clamp(v, -1e6, 1e6)));
    if (i + 3 < 0 || j + 3 < 0 || i - 3 >= resolution_ || j - 3 >= resolution_) return;
    const int cx0 = std::max(i - 3, 0) / kCell, cx1 = std::min(i + 3, resolution_ - 1) / kCell;
    const int cy0 = std::max(j - 3, 0) / kCell, cy1 = std::min(j + 3, resolution_ - 1) / kCell;
    for (int cy = cy0; cy <= cy1; ++cy) {
      for (int cx = cx0; cx <= cx1; ++cx) read_[static_cast<std::size_t>(cy) * cells_ + cx] = 1;
    }
    low_x = std::min(low_x, cx0), high_x = std::max(high_x, cx1);
    low_y = std::min(low_y, cy0), high_y = std::max(high_y, cy1);
  };
  for (std::uint32_t k : group) {
    const Vec3 a = pixel(samples.positions[k] + reach * samples.normals[k]);
    const Vec3 b = pixel(samples.positions[k] - reach * samples.normals[k]);
    const double length = (b - a).cwiseAbs().maxCoeff();
    if (!std::isfinite(length)) continue;
    const int steps = static_cast<int>(std::ceil(std::min(length, 4.0 * resolution_)));
    for (int step = 0; step <= steps; ++step) {
      const Vec3 p = steps == 0 ? a : a + (b - a) * (double(step) / steps);
      mark(p.x(), p.y());
    }
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
  return summed_[(cy1 + 1) * side + cx1 + 1] - summed_[cy0 * side + cx1 + 1] -
             summed_[(cy1 + 1) * side + cx0] + summed_[cy0 * side + cx0] >
         0;
}

std::vector<std::uint32_t> ViewFootprint::triangles_reaching(const TriangleClusters& clusters) const {
  if (rect_.empty()) return {};
  // Model point -> pixel coordinates, the camera's map folded into one affine map.
  Eigen::Matrix<double, 2, 3> linear;
  linear.row(0) = (0.5 * resolution_ / camera_.half_width) * camera_.right.transpose();
  linear.row(1) = (0.5 * resolution_ / camera_.half_height) * camera_.up.transpose();
  const Eigen::Vector2d offset = Eigen::Vector2d::Constant(0.5 * resolution_) - linear * camera_.centre;
  const auto pixel = [&](const Vec3& p) -> Eigen::Vector2d { return linear * p + offset; };
  // How far a box's projection reaches from its centre's, per unit of its half-size.
  const Eigen::Matrix<double, 2, 3> extent = linear.cwiseAbs();
  // The pixels whose centres a box [low, high] (pixel units) can cover lie within
  // [floor(low) - 1, floor(high) + 1] whatever the rasteriser's snapping.
  const auto reaches = [&](const Eigen::Vector2d& low, const Eigen::Vector2d& high) {
    const auto cell = [](double x, int offset) {
      return static_cast<int>(std::floor(std::clamp(x, -1e6, 1e6))) + offset;
    };
    // Truncating division only errs below 0, where any_cell clamps anyway.
    return any_cell(cell(low.x(), -1) / kCell, cell(low.y(), -1) / kCell, cell(high.x(), 1) / kCell,
                    cell(high.y(), 1) / kCell);
  };
  const Eigen::Vector2d pixels_per_unit(0.5 * resolution_ / camera_.half_width,
                                        0.5 * resolution_ / camera_.half_height);
  // A cluster whose projected sphere reaches no read cell is passed over whole; the others are
  // decided triangle by triangle, by their boxes. Blocks of clusters keep their triangles in cluster order.
  constexpr std::size_t kBlock = 64;
  std::vector<std::vector<std::uint32_t>> kept((clusters.count() + kBlock - 1) / kBlock);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, kept.size()), [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t block = range.begin(); block != range.end(); ++block) {
          for (std::size_t c = block * kBlock; c < std::min(clusters.count(), (block + 1) * kBlock); ++c) {
            const Eigen::Vector2d centre = pixel(clusters.centre(c));
            const Eigen::Vector2d reach = clusters.radius(c) * pixels_per_unit;
            if (!reaches(centre - reach, centre + reach)) continue;
            const TriangleClusters::Box* box = clusters.boxes(c);
            for (const std::uint32_t* t = clusters.begin(c); t != clusters.end(c); ++t, ++box) {
              const Eigen::Vector2d centre = pixel(Eigen::Vector3f(box->centre).cast<double>());
              const Eigen::Vector2d reach = extent * Eigen::Vector3f(box->half_size).cast<double>();
              if (reaches(centre - reach, centre + reach)) kept[block].push_back(*t);
            }
          }
        }
      });
  std::vector<std::uint32_t> all;
  std::size_t total = 0;
  for (const auto& block : kept) total += block.size();
  all.reserve(total);
  for (const auto& block : kept) all.insert(all.end(), block.begin(), block.end());
  return all;
}

}  // namespace roving
