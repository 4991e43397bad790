// Bitmaps of the pixels each sample's reading may touch, and a test of every triangle's
// projected box against them.
#include "roving/gl_methods/view_footprint.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace roving {
namespace {

// floor(x) as an int, for any x (far outside the image, or NaN, is far outside it).
int floor_pixel(double x) {
  x = x > -1e6 ? (x < 1e6 ? x : 1e6) : -1e6;
  const int i = static_cast<int>(x);  // truncation: one too high below 0
  return i - (x < i);
}

// Bits lo..hi (inclusive, 0..63) of a word.
std::uint64_t bit_range(int lo, int hi) {
  return (~std::uint64_t{0} << lo) & (~std::uint64_t{0} >> (63 - hi));
}

}  // namespace

ViewFootprint::Bitmap::Bitmap(int resolution, int shift)
    : shift_(shift), side_(((resolution - 1) >> shift) + 1), words_((side_ + 63) / 64) {
  bits_.assign(static_cast<std::size_t>(words_) * side_, 0);
}

void ViewFootprint::Bitmap::mark(int i0, int j0, int i1, int j1) {
  i0 >>= shift_, j0 >>= shift_, i1 >>= shift_, j1 >>= shift_;
  for (int j = j0; j <= j1; ++j) {
    std::uint64_t* row = bits_.data() + static_cast<std::size_t>(j) * words_;
    for (int w = i0 / 64; w <= i1 / 64; ++w)
      row[w] |= bit_range(w == i0 / 64 ? i0 % 64 : 0, w == i1 / 64 ? i1 % 64 : 63);
  }
}

bool ViewFootprint::Bitmap::any(int i0, int j0, int i1, int j1) const {
  i0 >>= shift_, j0 >>= shift_, i1 >>= shift_, j1 >>= shift_;
  const std::uint64_t* row = bits_.data() + static_cast<std::size_t>(j0) * words_;
  if (i0 / 64 == i1 / 64) {  // the usual case: one word a row
    const std::uint64_t mask = bit_range(i0 % 64, i1 % 64);
    std::uint64_t seen = 0;
    for (int j = j0; j <= j1; ++j, row += words_) seen |= row[i0 / 64];
    return (seen & mask) != 0;
  }
  for (int j = j0; j <= j1; ++j, row += words_) {
    for (int w = i0 / 64; w <= i1 / 64; ++w) {
      if (row[w] & bit_range(w == i0 / 64 ? i0 % 64 : 0, w == i1 / 64 ? i1 % 64 : 63)) return true;
    }
  }
  return false;
}

template <class Test>
bool ViewFootprint::Bitmap::any_where(int i0, int j0, int i1, int j1, const Test& test) const {
  i0 >>= shift_, j0 >>= shift_, i1 >>= shift_, j1 >>= shift_;
  for (int j = j0; j <= j1; ++j) {
    const std::uint64_t* row = bits_.data() + static_cast<std::size_t>(j) * words_;
    for (int w = i0 / 64; w <= i1 / 64; ++w) {
      std::uint64_t bits = row[w] & bit_range(w == i0 / 64 ? i0 % 64 : 0, w == i1 / 64 ? i1 % 64 : 63);
      for (; bits != 0; bits &= bits - 1) {
        if (test(64 * w + __builtin_ctzll(bits), j)) return true;
      }
    }
  }
  return false;
}

std::vector<PixelRect> ViewFootprint::Bitmap::runs() const {
  std::vector<PixelRect> runs;
  for (int j = 0; j < side_; ++j) {
    const std::uint64_t* row = bits_.data() + static_cast<std::size_t>(j) * words_;
    int start = -1;  // the open run's first square
    for (int i = 0; i <= side_; ++i) {
      const bool marked = i < side_ && (row[i / 64] >> (i % 64) & 1);
      if (marked && start < 0) start = i;
      if (!marked && start >= 0) runs.push_back({start, j, i, j + 1}), start = -1;
    }
  }
  return runs;
}

ViewFootprint::ViewFootprint(const OrthoCamera& camera, int resolution, const SampleSet& samples,
                             const std::vector<std::uint32_t>& group, double reach)
    : camera_(camera), resolution_(resolution), fine_(resolution, 0), coarse_(resolution, kCoarseShift) {
  rect_ = {resolution_, resolution_, 0, 0};
  const auto pixel = [&](const Vec3& p) {
    const Vec3 q = camera_.to_normalised(p);
    return Vec3((0.5 * q.x() + 0.5) * resolution_, (0.5 * q.y() + 0.5) * resolution_, 0);
  };
  // The reading of a point u (pixel units) touches pixels floor(u - 0.5) - 1 .. floor(u - 0.5) + 2
  // (bilinear 2 x 2, crease test 4 x 4). Steps p along the segment are under a pixel apart, so
  // every u lies within half a pixel of one: u - 0.5 in [p - 1, p], and the pixels read lie in
  // floor(p) - 2 .. floor(p) + 2.
  for (std::uint32_t k : group) {
    const Vec3 a = pixel(samples.positions[k] + reach * samples.normals[k]);
    const Vec3 b = pixel(samples.positions[k] - reach * samples.normals[k]);
    const double length = (b - a).cwiseAbs().maxCoeff();
    if (!std::isfinite(length)) continue;
    const int steps = length == 0 ? 0 : static_cast<int>(std::ceil(std::min(length, 4.0 * resolution_))) + 1;
    for (int step = 0; step <= steps; ++step) {
      const Vec3 p = steps == 0 ? a : a + (b - a) * (double(step) / steps);
      const int i = floor_pixel(p.x()), j = floor_pixel(p.y());
      mark(i - 2, j - 2, i + 2, j + 2);
    }
  }
  if (rect_.empty()) rect_ = {};
}

void ViewFootprint::mark(int i0, int j0, int i1, int j1) {
  i0 = std::max(i0, 0), j0 = std::max(j0, 0);
  i1 = std::min(i1, resolution_ - 1), j1 = std::min(j1, resolution_ - 1);
  if (i0 > i1 || j0 > j1) return;
  fine_.mark(i0, j0, i1, j1);
  coarse_.mark(i0, j0, i1, j1);
  rect_ = {std::min(rect_.x0, i0), std::min(rect_.y0, j0), std::max(rect_.x1, i1 + 1),
           std::max(rect_.y1, j1 + 1)};
}

bool ViewFootprint::covers(int i, int j) const {
  return i >= 0 && j >= 0 && i < resolution_ && j < resolution_ && fine_.any(i, j, i, j);
}

std::vector<PixelRect> ViewFootprint::read_squares() const {
  std::vector<PixelRect> squares = coarse_.runs();
  for (PixelRect& r : squares) {  // squares -> pixels, within rect_
    r = {std::max(r.x0 << kCoarseShift, rect_.x0), std::max(r.y0 << kCoarseShift, rect_.y0),
         std::min(r.x1 << kCoarseShift, rect_.x1), std::min(r.y1 << kCoarseShift, rect_.y1)};
  }
  return squares;
}

bool ViewFootprint::any_marked(int i0, int j0, int i1, int j1) const {
  i0 = std::max(i0, rect_.x0), j0 = std::max(j0, rect_.y0);
  i1 = std::min(i1, rect_.x1 - 1), j1 = std::min(j1, rect_.y1 - 1);
  return i0 <= i1 && j0 <= j1 && coarse_.any(i0, j0, i1, j1) && fine_.any(i0, j0, i1, j1);
}

std::vector<std::uint32_t> ViewFootprint::corners_reaching(const TriangleClusters& clusters) const {
  if (rect_.empty()) return {};
  // Box centre (relative to the clusters' origin) -> pixel coordinates, the camera's map folded
  // into one affine map, and how far a box's projection reaches per unit of its half-size. Float
  // is enough for coordinates relative to the model (~1e-7 of the image, under 0.01 pixel).
  Eigen::Matrix<double, 2, 3> linear;
  linear.row(0) = (0.5 * resolution_ / camera_.half_width) * camera_.right.transpose();
  linear.row(1) = (0.5 * resolution_ / camera_.half_height) * camera_.up.transpose();
  const Eigen::Vector2d offset =
      Eigen::Vector2d::Constant(0.5 * resolution_) + linear * (clusters.origin() - camera_.centre);
  const Eigen::Matrix<float, 2, 3> to_pixel = linear.cast<float>(), extent = linear.cwiseAbs().cast<float>();
  // A box [low, high] (pixel units) can cover the pixels whose centres i + 0.5 lie in it:
  // floor(low - 0.5) < i <= floor(high - 0.5). The rasteriser sees the box a little differently
  // (vertices in float, snapped to 1/256 pixel; ~0.01 pixel at 16384 pixels): a quarter of a
  // pixel more on each side holds that with room to spare.
  constexpr double kSlack = 0.25;
  const Eigen::Vector2f low_offset = (offset.array() - 0.5 - kSlack).cast<float>();
  const Eigen::Vector2f high_offset = (offset.array() - 0.5 + kSlack).cast<float>();
  const auto reaches = [&](const TriangleClusters::Box& box) {
    const Eigen::Vector2f centre = to_pixel * Eigen::Map<const Eigen::Vector3f>(box.centre);
    const Eigen::Vector2f reach = extent * Eigen::Map<const Eigen::Vector3f>(box.half_size);
    const Eigen::Vector2f low = centre - reach + low_offset, high = centre + reach + high_offset;
    return any_marked(floor_pixel(low.x()) + 1, floor_pixel(low.y()) + 1, floor_pixel(high.x()),
                      floor_pixel(high.y()));
  };
  // A triangle whose box passes is kept where a read pixel's centre lies within kSlack of it: on
  // the inner side of each edge's line moved out by kSlack in x and in y (which holds the
  // triangle grown by a square of kSlack). In double: projected as the box centres are, a few
  // thousand triangles a view, while the GL thread draws another view.
  const SharedArray<Vec3>& positions = clusters.positions();
  const auto covers_read_pixel = [&](const std::uint32_t* corners) {
    Eigen::Vector2d p[3];
    for (int k = 0; k < 3; ++k) p[k] = offset + linear * (positions[corners[k]] - clusters.origin());
    const Eigen::Vector2d u = p[1] - p[0], v = p[2] - p[0];
    const double area = u.x() * v.y() - u.y() * v.x();
    if (!(std::abs(area) > 0)) return true;  // degenerate (or not finite): the box decided
    double a[3], b[3], c[3];                 // a x + b y + c >= 0 within the widened edge
    for (int e = 0; e < 3; ++e) {
      const Eigen::Vector2d& from = p[e];
      const Eigen::Vector2d edge = p[(e + 1) % 3] - from;
      a[e] = area > 0 ? -edge.y() : edge.y();
      b[e] = area > 0 ? edge.x() : -edge.x();
      c[e] = -(a[e] * from.x() + b[e] * from.y()) + kSlack * (std::abs(a[e]) + std::abs(b[e]));
    }
    const Eigen::Vector2d low = p[0].cwiseMin(p[1]).cwiseMin(p[2]), high = p[0].cwiseMax(p[1]).cwiseMax(p[2]);
    const int i0 = std::max(floor_pixel(low.x() - 0.5 - kSlack) + 1, rect_.x0);
    const int j0 = std::max(floor_pixel(low.y() - 0.5 - kSlack) + 1, rect_.y0);
    const int i1 = std::min(floor_pixel(high.x() - 0.5 + kSlack), rect_.x1 - 1);
    const int j1 = std::min(floor_pixel(high.y() - 0.5 + kSlack), rect_.y1 - 1);
    return i0 <= i1 && j0 <= j1 && fine_.any_where(i0, j0, i1, j1, [&](int i, int j) {
      const double x = i + 0.5, y = j + 0.5;
      return a[0] * x + b[0] * y + c[0] >= 0 && a[1] * x + b[1] * y + c[1] >= 0 &&
             a[2] * x + b[2] * y + c[2] >= 0;
    });
  };
  // A cluster whose box reaches no read pixel is passed over whole; the others are decided
  // triangle by triangle. Blocks of clusters keep their triangles in cluster order.
  constexpr std::size_t kBlock = 64;
  std::vector<std::vector<std::uint32_t>> kept((clusters.count() + kBlock - 1) / kBlock);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, kept.size()), [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t block = range.begin(); block != range.end(); ++block) {
          for (std::size_t c = block * kBlock; c < std::min(clusters.count(), (block + 1) * kBlock); ++c) {
            if (!reaches(clusters.cluster_box(c))) continue;
            for (std::size_t t = 0; t < clusters.size(c); ++t) {
              const std::uint32_t* corners = clusters.corners(c) + 3 * t;
              if (!reaches(clusters.boxes(c)[t]) || !covers_read_pixel(corners)) continue;
              kept[block].insert(kept[block].end(), corners, corners + 3);
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
