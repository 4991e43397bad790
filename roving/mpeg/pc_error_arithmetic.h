// pc_error's arithmetic, which its figures are to the last bit: the k-d tree it searches (nanoflann's,
// leaves of 10 points, over single-precision points, squared distances summed x, y, z in double of
// the single-precision differences) and its colour spaces. Where a figure depends on which of several
// equally near points a search finds first, or how many it looks at, only the same tree over the
// same points in the same order finds the same ones.
#pragma once

#include <array>
#include <cstdint>
#include <nanoflann.hpp>
#include <vector>

namespace roving {

struct MpegPointsAdaptor {
  const std::vector<std::array<float, 3>>& points;
  std::size_t kdtree_get_point_count() const { return points.size(); }
  float kdtree_get_pt(std::uint32_t i, std::size_t axis) const { return points[i][axis]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

using MpegKdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Adaptor<float, MpegPointsAdaptor, double>,
                                                       MpegPointsAdaptor, 3, std::uint32_t>;

inline constexpr std::size_t kMpegTreeLeaf = 10;  // pc_error's my_kd_tree_t(3, points, 10)

// The squared distance of two points as the tree's metric and pc_error compute it.
inline double mpeg_squared_distance(const std::array<float, 3>& p, const std::array<float, 3>& q) {
  double sum = 0;
  for (int c = 0; c < 3; ++c) {
    const double d = p[c] - q[c];
    sum += d * d;
  }
  return sum;
}

// BT.709 Y'CbCr on [0, 1] (its --mseSpace=1), in single precision as pc_error stores it.
inline std::array<float, 3> pc_error_ycbcr(const std::array<std::uint8_t, 3>& c) {
  const double r = c[0], g = c[1], b = c[2];
  return {float((0.2126 * r + 0.7152 * g + 0.0722 * b) / 255.0),
          float((-0.1146 * r - 0.3854 * g + 0.5000 * b) / 255.0 + 0.5000),
          float((0.5000 * r - 0.4542 * g - 0.0458 * b) / 255.0 + 0.5000)};
}

// YCoCg-R (its --mseSpace=8), lossless in integers: Y on [0, 255], Co and Cg offset by 256 to
// [1, 511]; the PSNRs' peaks are 255, 511 and 511.
inline std::array<float, 3> pc_error_ycocg(const std::array<std::uint8_t, 3>& c) {
  const int r = c[0], g = c[1], b = c[2];
  const int co = r - b;
  const int t = b + (co >> 1);  // an arithmetic shift, as pc_error's: floor of a half
  const int cg = g - t;
  const int y = t + (cg >> 1);
  return {float(y), float(co + 256), float(cg + 256)};
}

}  // namespace roving
