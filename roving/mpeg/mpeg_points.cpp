#include "roving/mpeg/mpeg_points.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "roving/core/error.h"

namespace roving {
namespace {

std::array<float, 3> to_float(const Vec3& v, const std::string& name, const char* what, std::size_t i) {
  const double limit = std::numeric_limits<float>::max();
  if (!v.allFinite() || v.cwiseAbs().maxCoeff() > limit) {
    throw Error(fmt::format("{}: {} {} is not a finite single-precision value ({}, {}, {})", name, what, i, v.x(),
                            v.y(), v.z()));
  }
  return {float(v.x()), float(v.y()), float(v.z())};
}

}  // namespace

MpegPoints mpeg_points(const PointCloud& cloud, const std::string& name, bool with_normals, bool average_normals) {
  const std::size_t n = cloud.positions.size();
  if (n == 0) throw Error(fmt::format("{}: no points; expected a point cloud", name));
  if (with_normals && !cloud.normals.empty() && cloud.normals.size() != n) {
    throw Error(fmt::format("{}: {} normals for {} points; expected one per point or none", name,
                            cloud.normals.size(), n));
  }
  if (!cloud.colours.empty() && cloud.colours.size() != n) {
    throw Error(fmt::format("{}: {} colours for {} points; expected one per point or none", name,
                            cloud.colours.size(), n));
  }
  // Lexicographic order of the single-precision coordinates, equal points in file order: pc_error's.
  struct Entry {
    std::array<float, 3> position;
    std::uint32_t index;
    bool operator<(const Entry& other) const {
      return position != other.position ? position < other.position : index < other.index;
    }
  };
  std::vector<Entry> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = {to_float(cloud.positions[i], name, "point", i), std::uint32_t(i)};
  std::sort(order.begin(), order.end());

  const bool normals = with_normals && !cloud.normals.empty();
  MpegPoints points;
  points.points_read = n;
  for (std::size_t run = 0; run < n;) {
    std::size_t end = run + 1;
    while (end < n && order[end].position == order[run].position) ++end;
    const std::uint32_t first = order[run].index;
    points.positions.push_back(order[run].position);
    if (normals && average_normals) {
      std::array<float, 3> sum = {0, 0, 0};  // in single precision, in the sorted order, as mmetric
      for (std::size_t k = run; k < end; ++k) {
        const std::array<float, 3> n = to_float(cloud.normals[order[k].index], name, "normal", order[k].index);
        for (int c = 0; c < 3; ++c) sum[c] += n[c];
      }
      for (int c = 0; c < 3; ++c) sum[c] /= float(end - run);
      points.normals.push_back(sum);
    } else if (normals) {
      points.normals.push_back(to_float(cloud.normals[first], name, "normal", first));
    }
    if (!cloud.colours.empty()) {
      // pc_error sums the 8-bit values and divides as integers: the mean, truncated.
      long sum[3] = {0, 0, 0};
      for (std::size_t k = run; k < end; ++k) {
        for (int c = 0; c < 3; ++c) sum[c] += std::lround(std::clamp(cloud.colours[order[k].index][c], 0.0f, 255.0f));
      }
      const long count = long(end - run);
      points.colours.push_back({std::uint8_t(sum[0] / count), std::uint8_t(sum[1] / count),
                                std::uint8_t(sum[2] / count)});
    }
    run = end;
  }
  return points;
}

}  // namespace roving
