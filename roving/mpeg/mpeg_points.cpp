#include "roving/mpeg/mpeg_points.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numeric>

#include "roving/core/error.h"

namespace roving {
namespace {

bool representable(const Vec3& v) {
  const double limit = std::numeric_limits<float>::max();
  return std::fabs(v.x()) <= limit && std::fabs(v.y()) <= limit && std::fabs(v.z()) <= limit;  // NaN fails
}

std::array<float, 3> to_float(const Vec3& v, const std::string& name, const char* what, std::size_t i) {
  if (!representable(v)) {
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
  // On all cores; the first point that is not representable (in file order) is the one named.
  std::vector<Entry> order(n);
  std::atomic<std::size_t> first_bad{n};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 65536), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const Vec3& p = cloud.positions[i];
      if (!representable(p)) {
        for (std::size_t seen = first_bad; i < seen && !first_bad.compare_exchange_weak(seen, i);) {
        }
        return;
      }
      order[i] = {{float(p.x()), float(p.y()), float(p.z())}, std::uint32_t(i)};
    }
  });
  if (first_bad < n) to_float(cloud.positions[first_bad], name, "point", first_bad);  // throws
  tbb::parallel_sort(order.begin(), order.end());

  const bool normals = with_normals && !cloud.normals.empty();
  MpegPoints points;
  points.points_read = n;
  points.positions.reserve(n);
  if (normals) points.normals.reserve(n);
  if (!cloud.colours.empty()) points.colours.reserve(n);
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
