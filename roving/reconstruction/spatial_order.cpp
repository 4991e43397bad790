#include "roving/reconstruction/spatial_order.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cstdint>

#include "roving/core/geometry.h"

namespace roving {

std::vector<std::uint32_t> spatial_order(const std::vector<Vec3>& points) {
  const std::size_t n = points.size();
  std::vector<std::uint32_t> order(n);
  if (n < 2) {
    for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(i);
    return order;
  }
  const BoundingBox box = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n, 1 << 14), BoundingBox{},
      [&](const tbb::blocked_range<std::size_t>& range, BoundingBox b) {
        for (std::size_t i = range.begin(); i < range.end(); ++i) b.extend(points[i]);
        return b;
      },
      [](BoundingBox a, const BoundingBox& b) {
        a.extend(b.min);
        a.extend(b.max);
        return a;
      });
  constexpr int kCodeBits = 30;  // morton_code's: 10 a coordinate
  int bucket_bits = 1;           // about 1,024 points a bucket
  while (bucket_bits < 18 && (n >> (bucket_bits + 10)) != 0) ++bucket_bits;
  const std::size_t buckets = std::size_t{1} << bucket_bits;
  const auto bucket_of = [&](const Vec3& p) {
    return std::size_t(morton_code(p, box) >> (kCodeBits - bucket_bits));
  };
  // Chunks of points, each counted and then scattered by one task, in order.
  const std::size_t chunks = std::min<std::size_t>(64, (n + 65535) / 65536);
  const auto chunk_range = [&](std::size_t c) { return std::pair{n * c / chunks, n * (c + 1) / chunks}; };
  std::vector<std::size_t> place(chunks * buckets, 0);  // [chunk][bucket]: counts, then where it goes
  tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
    const auto [begin, end] = chunk_range(c);
    for (std::size_t i = begin; i < end; ++i) ++place[c * buckets + bucket_of(points[i])];
  });
  std::size_t at = 0;
  for (std::size_t b = 0; b < buckets; ++b) {
    for (std::size_t c = 0; c < chunks; ++c) {
      const std::size_t count = place[c * buckets + b];
      place[c * buckets + b] = at;
      at += count;
    }
  }
  tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
    const auto [begin, end] = chunk_range(c);
    for (std::size_t i = begin; i < end; ++i)
      order[place[c * buckets + bucket_of(points[i])]++] = static_cast<std::uint32_t>(i);
  });
  return order;
}

void order_in_space(std::vector<Vec3>& points) {
  if (points.size() < 2) return;
  const std::vector<std::uint32_t> order = spatial_order(points);
  std::vector<Vec3> ordered(points.size());
  tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t k) { ordered[k] = points[order[k]]; });
  points.swap(ordered);
}

}  // namespace roving
