#include "roving/mpeg/mpeg_points.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <cmath>
#include <limits>
#include <numeric>

#include "roving/core/error.h"
#include "roving/core/radix_sort.h"

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

// Lowers `least` to `value` where that is smaller, from any thread.
void keep_least(std::atomic<std::size_t>& least, std::size_t value) {
  for (std::size_t seen = least; value < seen && !least.compare_exchange_weak(seen, value);) {
  }
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
  // Sorted as integers (stably, so equal points keep the file's order): each coordinate's bits
  // turned to keep float's order (-0 taken as +0, which float's == merges and which changes no
  // distance), beside the point's index.
  struct Entry {
    std::uint64_t xy, z_index;
    RadixKey position() const { return RadixKey(xy) << 32 | z_index >> 32; }
    bool same_position(const Entry& other) const { return xy == other.xy && z_index >> 32 == other.z_index >> 32; }
    std::uint32_t index() const { return std::uint32_t(z_index); }
  };
  const auto ordered = [](double v) {
    const float f = float(v) + 0.0f;
    std::uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    return std::uint64_t(bits & 0x80000000u ? ~bits : bits | 0x80000000u);
  };
  const auto coordinate = [](std::uint64_t key) {
    const std::uint32_t k = std::uint32_t(key), bits = k & 0x80000000u ? k & 0x7fffffffu : ~k;
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
  };
  // On all cores; the first point that is not representable (in file order) is the one named.
  // The normals and colours are made small here, in the file's order, so that the merging below,
  // which reads them in sorted order (at random in the file's), has less to fetch: single
  // precision (NaN where the value is not representable) and 8 bits.
  const bool normals = with_normals && !cloud.normals.empty();
  std::vector<Entry> order(n);
  std::vector<std::array<float, 3>> small_normals(normals ? n : 0);
  std::vector<std::array<std::uint8_t, 4>> small_colours(cloud.colours.empty() ? 0 : n);
  std::atomic<std::size_t> first_bad{n};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 65536), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const Vec3& p = cloud.positions[i];
      if (!representable(p)) {
        keep_least(first_bad, i);
        return;
      }
      order[i] = {ordered(p.x()) << 32 | ordered(p.y()), ordered(p.z()) << 32 | i};
      if (normals) {
        const Vec3& normal = cloud.normals[i];
        small_normals[i] = representable(normal)
                               ? std::array<float, 3>{float(normal.x()), float(normal.y()), float(normal.z())}
                               : std::array<float, 3>{NAN, NAN, NAN};
      }
      if (!small_colours.empty()) {
        for (int c = 0; c < 3; ++c) {
          small_colours[i][c] = std::uint8_t(std::lround(std::clamp(cloud.colours[i][c], 0.0f, 255.0f)));
        }
      }
    }
  });
  if (first_bad < n) to_float(cloud.positions[first_bad], name, "point", first_bad);  // throws
  radix_sort(order, [](const Entry& e) { return e.position(); });

  // Runs of equal points, found and merged block by block on all cores: each block merges the runs
  // that begin in it, into the places counted before it.
  constexpr std::size_t kBlock = 65536;
  constexpr std::size_t kAhead = 16;
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
  std::vector<std::size_t> first_run(blocks + 1, 0);
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    std::size_t count = 0;
    for (std::size_t k = b * kBlock; k < std::min(n, (b + 1) * kBlock); ++k) {
      count += k == 0 || !order[k].same_position(order[k - 1]);
    }
    first_run[b + 1] = count;
  });
  std::partial_sum(first_run.begin(), first_run.end(), first_run.begin());
  const std::size_t runs = first_run.back();

  // A normal that is used must be finite; the first such in sorted order is the one named.
  std::atomic<std::size_t> first_bad_normal{n};
  const auto normal_at = [&](std::size_t k) {
    const std::array<float, 3>& normal = small_normals[order[k].index()];
    if (std::isnan(normal[0])) keep_least(first_bad_normal, k);
    return normal;
  };
  MpegPoints points;
  points.points_read = n;
  points.positions.resize(runs);
  if (normals) points.normals.resize(runs);
  if (!cloud.colours.empty()) points.colours.resize(runs);
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    std::size_t out = first_run[b];
    std::size_t run = b * kBlock;
    while (run < n && run > 0 && order[run].same_position(order[run - 1])) ++run;  // the block before's
    for (const std::size_t stop = std::min(n, (b + 1) * kBlock); run < stop; ++out) {
      // The colours and normals are read in sorted order, at random in the file's: asked for
      // ahead, their cache misses overlap instead of following one another.
      if (run + kAhead < n) {
        const std::uint32_t ahead = order[run + kAhead].index();
        if (!small_colours.empty()) __builtin_prefetch(&small_colours[ahead]);
        if (normals) __builtin_prefetch(&small_normals[ahead]);
      }
      std::size_t end = run + 1;
      while (end < n && order[end].same_position(order[run])) ++end;
      points.positions[out] = {coordinate(order[run].xy >> 32), coordinate(order[run].xy),
                               coordinate(order[run].z_index >> 32)};
      if (normals && average_normals) {
        std::array<float, 3> sum = {0, 0, 0};  // in single precision, in the sorted order, as mmetric
        for (std::size_t k = run; k < end; ++k) {
          const std::array<float, 3> normal = normal_at(k);
          for (int c = 0; c < 3; ++c) sum[c] += normal[c];
        }
        for (int c = 0; c < 3; ++c) sum[c] /= float(end - run);
        points.normals[out] = sum;
      } else if (normals) {
        points.normals[out] = normal_at(run);
      }
      if (!cloud.colours.empty()) {
        // pc_error sums the 8-bit values and divides as integers: the mean, truncated.
        long sum[3] = {0, 0, 0};
        for (std::size_t k = run; k < end; ++k) {
          for (int c = 0; c < 3; ++c) sum[c] += small_colours[order[k].index()][c];
        }
        const long count = long(end - run);
        points.colours[out] = {std::uint8_t(sum[0] / count), std::uint8_t(sum[1] / count), std::uint8_t(sum[2] / count)};
      }
      run = end;
    }
  });
  if (first_bad_normal < n) {  // throws
    const std::uint32_t i = order[first_bad_normal].index();
    to_float(cloud.normals[i], name, "normal", i);
  }
  return points;
}

void use_normals_of(MpegPoints& a, MpegPoints& normals, const std::string& name) {
  if (normals.normals.empty()) {
    throw Error(fmt::format("{}: no normals (nx, ny, nz); expected A's points with their normals", name));
  }
  if (normals.size() != a.size()) {
    throw Error(fmt::format("{}: {} points at distinct positions ({} read); expected A's {}", name, normals.size(),
                            normals.points_read, a.size()));
  }
  const auto differs = std::mismatch(a.positions.begin(), a.positions.end(), normals.positions.begin());
  if (differs.first != a.positions.end()) {
    // Both sorted: the first difference is a point of the file's that A lacks, or else one of A's
    // that the file lacks.
    const std::array<float, 3>& theirs = *differs.second;
    if (!std::binary_search(a.positions.begin(), a.positions.end(), theirs)) {
      throw Error(fmt::format("{}: has a point at ({}, {}, {}) that A has not; expected A's points with their normals",
                              name, theirs[0], theirs[1], theirs[2]));
    }
    const std::array<float, 3>& ours = *differs.first;
    throw Error(fmt::format("{}: has no point at A's ({}, {}, {}); expected A's points with their normals", name,
                            ours[0], ours[1], ours[2]));
  }
  a.normals = std::move(normals.normals);
}

}  // namespace roving
