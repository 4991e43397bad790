#include "roving/reconstruction/voxel_down_sample.h"

#include <fmt/format.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

#include "roving/core/error.h"
#include "roving/reconstruction/tanks_and_temples_protocol.h"

namespace roving {
namespace {

struct Cube {
  Vec3 sum = Vec3::Zero();
  std::uint32_t count = 0;
};

// A cube's three indices, as Open3D computes them.
struct CubeIndex {
  int x, y, z;
  bool operator==(const CubeIndex& o) const { return x == o.x && y == o.y && z == o.z; }
};

// Every point is at least half a cube above grid_low, so r > 0 and truncation is floor (without
// SSE4.1, std::floor is a call into libm).
inline CubeIndex cube_of(const Vec3& p, const Vec3& grid_low, double voxel_size) {
  const Vec3 r = (p - grid_low) / voxel_size;
  return {static_cast<int>(r[0]), static_cast<int>(r[1]), static_cast<int>(r[2])};
}

std::uint64_t mix(std::uint64_t h) {  // splitmix64's finaliser
  h = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9ull;
  h = (h ^ (h >> 27)) * 0x94D049BB133111EBull;
  return h ^ (h >> 31);
}

// Cubes by a key of 63 bits, open addressing with linear probing: one probe or two per point
// where std::unordered_map chases a node.
class CubeTable {
 public:
  // The cube of `key` (a new one, zero, where it is the first time).
  Cube& operator[](std::uint64_t key) {
    if (2 * (cubes_.size() + 1) > keys_.size()) grow();
    const std::size_t mask = keys_.size() - 1;
    for (std::size_t slot = mix(key) & mask;; slot = (slot + 1) & mask) {
      if (keys_[slot] == key) return cubes_[index_[slot]];
      if (keys_[slot] == kEmpty) {
        keys_[slot] = key;
        index_[slot] = static_cast<std::uint32_t>(cubes_.size());
        return cubes_.emplace_back();
      }
    }
  }
  void clear() {  // no cube, the room kept
    std::fill(keys_.begin(), keys_.end(), kEmpty);
    cubes_.clear();
  }
  const std::vector<Cube>& cubes() const { return cubes_; }
  // Each cube's key and its place in cubes().
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys() const {
    std::vector<std::pair<std::uint64_t, std::uint32_t>> out;
    out.reserve(cubes_.size());
    for (std::size_t s = 0; s < keys_.size(); ++s) {
      if (keys_[s] != kEmpty) out.emplace_back(keys_[s], index_[s]);
    }
    return out;
  }

 private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
  void grow() {
    std::vector<std::uint64_t> keys(std::max<std::size_t>(1024, 2 * keys_.size()), kEmpty);
    std::vector<std::uint32_t> index(keys.size());
    const std::size_t mask = keys.size() - 1;
    for (std::size_t s = 0; s < keys_.size(); ++s) {
      if (keys_[s] == kEmpty) continue;
      std::size_t slot = mix(keys_[s]) & mask;
      while (keys[slot] != kEmpty) slot = (slot + 1) & mask;
      keys[slot] = keys_[s];
      index[slot] = index_[s];
    }
    keys_.swap(keys);
    index_.swap(index);
  }
  std::vector<std::uint64_t> keys_;
  std::vector<std::uint32_t> index_;
  std::vector<Cube> cubes_;
};

// The 21 low bits of `v` spread to every third bit (for a Morton code of three).
std::uint64_t spread(std::uint64_t v) {
  v &= 0x1FFFFF;
  v = (v | v << 32) & 0x1F00000000FFFFull;
  v = (v | v << 16) & 0x1F0000FF0000FFull;
  v = (v | v << 8) & 0x100F00F00F00F00Full;
  v = (v | v << 4) & 0x10C30C30C30C30C3ull;
  v = (v | v << 2) & 0x1249249249249249ull;
  return v;
}

}  // namespace

std::vector<Vec3> voxel_down_sample(const std::vector<Vec3>& points, double voxel_size, const std::string& name,
                                    const std::vector<std::uint8_t>* keep, const Eigen::Matrix4d* move) {
  if (!(std::isfinite(voxel_size) && voxel_size > 0)) {
    throw Error(fmt::format("{}: voxel down-sampling: voxel size {}; expected a length > 0", name, voxel_size));
  }
  const auto kept = [&](std::size_t i) { return !keep || (*keep)[i]; };
  const auto point = [&](std::size_t i) { return move ? transformed_point(*move, points[i]) : points[i]; };
  std::size_t first = 0;
  while (first < points.size() && !kept(first)) ++first;
  if (first == points.size()) return {};
  using Box = std::pair<Vec3, Vec3>;
  const Box start{point(first), point(first)};
  const auto [low, high] = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(first, points.size(), 1 << 14), start,
      [&](const tbb::blocked_range<std::size_t>& range, Box box) {
        for (std::size_t i = range.begin(); i < range.end(); ++i) {
          if (!kept(i)) continue;
          const Vec3 p = point(i);
          box.first = box.first.cwiseMin(p);
          box.second = box.second.cwiseMax(p);
        }
        return box;
      },
      [](const Box& a, const Box& b) { return Box{a.first.cwiseMin(b.first), a.second.cwiseMax(b.second)}; });
  const Vec3 half = Vec3::Constant(voxel_size) * 0.5;
  const Vec3 grid_low = low - half, grid_high = high + half;
  if (voxel_size * std::numeric_limits<int>::max() < (grid_high - grid_low).maxCoeff()) {
    throw Error(fmt::format("{}: voxel down-sampling: voxel size {} is too small for points spanning {} (a cube's "
                            "index would not fit an int)",
                            name, voxel_size, (grid_high - grid_low).maxCoeff()));
  }
  const auto means_of = [](const std::vector<Cube>& cubes, std::vector<Vec3>& means) {
    for (const Cube& cube : cubes) means.push_back(cube.sum / double(cube.count));
  };
  std::vector<Vec3> means;
  const CubeIndex last = cube_of(high, grid_low, voxel_size);
  constexpr int kBits = 21;
  if (std::max({last.x, last.y, last.z}) >= (1 << kBits)) {
    // Over 2 million cubes along an axis: keyed by the three ints whole (slower, never on a scene).
    struct Hash {
      std::size_t operator()(const CubeIndex& k) const {
        return mix((std::uint64_t(std::uint32_t(k.x)) << 32 | std::uint32_t(k.y)) ^ (std::uint64_t(std::uint32_t(k.z)) << 16));
      }
    };
    std::unordered_map<CubeIndex, std::uint32_t, Hash> index;
    std::vector<Cube> cubes;
    for (std::size_t i = first; i < points.size(); ++i) {
      if (!kept(i)) continue;
      const Vec3 p = point(i);
      const auto [it, added] = index.try_emplace(cube_of(p, grid_low, voxel_size), std::uint32_t(cubes.size()));
      if (added) cubes.emplace_back();
      cubes[it->second].sum += p;
      ++cubes[it->second].count;
    }
    means_of(cubes, means);
    return means;
  }
  // The cubes' Morton codes (x, y, z interleaved) ordered, their leading bits name a bucket: a
  // compact region of space. The kept points are first listed bucket by bucket, each bucket's in
  // the points' order; then every bucket is summed on some core in a table that stays in cache (a
  // table of all the cubes does not: at 30 M points each point would cost a trip to memory), and
  // its cubes put in Morton order. The means come out in Morton order of the cubes, neighbours in
  // space neighbours in memory, so that the k-d trees built on them and the searches from them run
  // from cache; each cube's sum is over its points in their order, whatever the number of cores.
  if (points.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw Error(fmt::format("{}: voxel down-sampling: {} points; at most {}", name, points.size(),
                            std::numeric_limits<std::uint32_t>::max()));
  }
  const auto morton_of = [&](std::size_t i) {
    const CubeIndex c = cube_of(point(i), grid_low, voxel_size);
    return spread(std::uint64_t(c.x)) | spread(std::uint64_t(c.y)) << 1 | spread(std::uint64_t(c.z)) << 2;
  };
  int code_bits = 3;
  while (code_bits < 3 * kBits && (std::max({last.x, last.y, last.z}) >> (code_bits / 3)) != 0) code_bits += 3;
  const std::size_t count = points.size() - first;
  int bucket_bits = 0;  // about 4,096 points a bucket, at most 2^14 buckets
  while (bucket_bits < std::min(14, code_bits) && (count >> (bucket_bits + 12)) != 0) ++bucket_bits;
  const std::size_t buckets = std::size_t{1} << bucket_bits;
  const auto bucket_of = [&](std::size_t i) { return std::size_t(morton_of(i) >> (code_bits - bucket_bits)); };
  // Chunks of points, each counted and then listed by one task, in order.
  const std::size_t chunks = std::min<std::size_t>(64, (count + 65535) / 65536);
  const auto chunk_range = [&](std::size_t c) {
    return std::pair{first + count * c / chunks, first + count * (c + 1) / chunks};
  };
  std::vector<std::uint32_t> place(chunks * buckets, 0);  // [chunk][bucket]: counts, then where it lists
  tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
    const auto [begin, end] = chunk_range(c);
    for (std::size_t i = begin; i < end; ++i) {
      if (kept(i)) ++place[c * buckets + bucket_of(i)];
    }
  });
  std::vector<std::size_t> bucket_start(buckets + 1, 0);
  std::size_t listed = 0;
  for (std::size_t b = 0; b < buckets; ++b) {
    bucket_start[b] = listed;
    for (std::size_t c = 0; c < chunks; ++c) {
      const std::uint32_t n = place[c * buckets + b];
      place[c * buckets + b] = std::uint32_t(listed);
      listed += n;
    }
  }
  bucket_start[buckets] = listed;
  std::vector<std::uint32_t> order(listed);
  tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
    const auto [begin, end] = chunk_range(c);
    for (std::size_t i = begin; i < end; ++i) {
      if (kept(i)) order[place[c * buckets + bucket_of(i)]++] = std::uint32_t(i);
    }
  });
  std::vector<std::vector<Vec3>> bucket_means(buckets);
  tbb::enumerable_thread_specific<CubeTable> tables;
  tbb::parallel_for(std::size_t(0), buckets, [&](std::size_t b) {
    if (bucket_start[b] == bucket_start[b + 1]) return;
    CubeTable& table = tables.local();
    table.clear();
    for (std::size_t k = bucket_start[b]; k < bucket_start[b + 1]; ++k) {
      // A bucket's points lie anywhere in a file in random order: asked for ahead, their cache
      // misses overlap instead of following one another.
      constexpr std::size_t kAhead = 16;
      if (k + kAhead < bucket_start[b + 1]) __builtin_prefetch(&points[order[k + kAhead]]);
      const Vec3 p = point(order[k]);
      const CubeIndex c = cube_of(p, grid_low, voxel_size);
      Cube& cube = table[std::uint64_t(c.x) | std::uint64_t(c.y) << kBits | std::uint64_t(c.z) << (2 * kBits)];
      cube.sum += p;
      ++cube.count;
    }
    std::vector<std::pair<std::uint64_t, std::uint32_t>> cubes = table.keys();
    const std::uint64_t mask = (std::uint64_t{1} << kBits) - 1;
    for (auto& [key, index] : cubes) {
      key = spread(key & mask) | spread(key >> kBits & mask) << 1 | spread(key >> (2 * kBits)) << 2;
    }
    std::sort(cubes.begin(), cubes.end());
    std::vector<Vec3>& out = bucket_means[b];
    out.reserve(cubes.size());
    for (const auto& [morton, index] : cubes) {
      const Cube& cube = table.cubes()[index];
      out.push_back(cube.sum / double(cube.count));
    }
  });
  std::vector<std::size_t> out_start(buckets + 1, 0);
  for (std::size_t b = 0; b < buckets; ++b) out_start[b + 1] = out_start[b] + bucket_means[b].size();
  means.resize(out_start[buckets]);
  tbb::parallel_for(std::size_t(0), buckets, [&](std::size_t b) {
    std::copy(bucket_means[b].begin(), bucket_means[b].end(), means.begin() + std::ptrdiff_t(out_start[b]));
  });
  return means;
}

}  // namespace roving
