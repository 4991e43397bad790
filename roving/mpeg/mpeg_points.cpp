#include "roving/mpeg/mpeg_points.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

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

// A coordinate's single-precision bits turned to keep float's order as unsigned integers (-0 taken
// as +0, which float's == merges and which changes no distance), and back.
std::uint32_t ordered_bits(float v) {
  const float f = v + 0.0f;
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  return bits & 0x80000000u ? ~bits : bits | 0x80000000u;
}

// A position's ordered bits; false where a coordinate is not a finite single-precision value.
bool ordered_position(const Vec3& p, std::array<std::uint32_t, 3>& bits) {
  if (!representable(p)) return false;
  bits = {ordered_bits(float(p.x())), ordered_bits(float(p.y())), ordered_bits(float(p.z()))};
  return true;
}

float from_ordered_bits(std::uint32_t k) {
  const std::uint32_t bits = k & 0x80000000u ? k & 0x7fffffffu : ~k;
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

// Where the points' ordered coordinate bits differ: the bits each coordinate keeps in a sort key.
// Bits outside a coordinate's span are the same in every point (the first one's).
struct KeyLayout {
  std::array<std::uint32_t, 3> first{};  // the first point's ordered bits
  std::array<int, 3> low{}, width{};     // each coordinate's span of varying bits
  int index_bits = 0;                    // below the coordinates, the point's index
  int bits() const { return width[0] + width[1] + width[2] + index_bits; }
};

// Sort entries by position, then (stably) by index. Packed: where the varying bits and the index
// fit in 64 bits (a voxelised cloud's do: 3 x 13 bits and 20 for a million points at 11 bits), a
// sort moves 8 bytes an entry over those bits alone; Wide holds any floats in 16.
struct PackedEntry {
  std::uint64_t word;  // x span, y span, z span, index
};
struct WideEntry {
  std::uint64_t xy, z_index;
};

struct PackedCodec {
  KeyLayout layout;
  PackedEntry make(const std::array<std::uint32_t, 3>& bits, std::size_t i) const {
    std::uint64_t word = 0;
    for (int c = 0; c < 3; ++c) {
      const std::uint64_t mask = (std::uint64_t{1} << layout.width[c]) - 1;
      word = word << layout.width[c] | (bits[c] >> layout.low[c] & mask);
    }
    return {word << layout.index_bits | i};
  }
  std::uint64_t position(const PackedEntry& e) const { return e.word >> layout.index_bits; }
  std::uint32_t index(const PackedEntry& e) const {
    return std::uint32_t(e.word & ((std::uint64_t{1} << layout.index_bits) - 1));
  }
  std::array<float, 3> point(const PackedEntry& e) const {
    std::uint64_t word = e.word >> layout.index_bits;
    std::array<float, 3> p;
    for (int c = 2; c >= 0; --c) {
      const std::uint32_t mask = std::uint32_t((std::uint64_t{1} << layout.width[c]) - 1) << layout.low[c];
      p[c] = from_ordered_bits((layout.first[c] & ~mask) | (std::uint32_t(word) << layout.low[c] & mask));
      word >>= layout.width[c];
    }
    return p;
  }
};

struct WideCodec {
  WideEntry make(const std::array<std::uint32_t, 3>& bits, std::size_t i) const {
    return {std::uint64_t(bits[0]) << 32 | bits[1], std::uint64_t(bits[2]) << 32 | i};
  }
  RadixKey position(const WideEntry& e) const { return RadixKey(e.xy) << 32 | e.z_index >> 32; }
  std::uint32_t index(const WideEntry& e) const { return std::uint32_t(e.z_index); }
  std::array<float, 3> point(const WideEntry& e) const {
    return {from_ordered_bits(std::uint32_t(e.xy >> 32)), from_ordered_bits(std::uint32_t(e.xy)),
            from_ordered_bits(std::uint32_t(e.z_index >> 32))};
  }
};

// Where mpeg_points reads a cloud. Each gives a point's position as read, its normal in single
// precision (NaN where not representable) and its colour in 8 bits, at random in file order.

// A cloud in memory. Its normals and colours are first made small (single precision and 8 bits),
// in file order, by `prepare` in the pass that checks the positions, so that the merging, which
// reads them in sorted order, has less to fetch. Pointers, not vectors: each task works on a copy
// of its own (sorted_and_merged), the room is the caller's.
struct MemoryCloud {
  const PointCloud* cloud;
  std::array<float, 3>* normals = nullptr;         // null: none
  std::array<std::uint8_t, 4>* colours = nullptr;  // null: none

  std::size_t size() const { return cloud->positions.size(); }
  Vec3 position(std::size_t i) const { return cloud->positions[i]; }
  bool ordered_position(std::size_t i, std::array<std::uint32_t, 3>& bits) const {
    return roving::ordered_position(position(i), bits);
  }
  bool has_normals() const { return normals != nullptr; }
  bool has_colours() const { return colours != nullptr; }
  Vec3 normal_as_read(std::size_t i) const { return cloud->normals[i]; }
  const std::array<float, 3>& normal(std::size_t i) const { return normals[i]; }
  std::uint8_t colour(std::size_t i, int c) const { return colours[i][c]; }
  void prefetch(std::size_t i) const {
    if (has_colours()) __builtin_prefetch(&colours[i]);
    if (has_normals()) __builtin_prefetch(&normals[i]);
  }
  void prepare(std::size_t i) const {
    if (has_normals()) normals[i] = small_normal(cloud->normals[i]);
    if (has_colours()) {
      for (int c = 0; c < 3; ++c) {
        // Rounded half away from zero, as lround (the difference from the whole part is exact).
        const float value = cloud->colours[i][c];
        const float code = value >= 0.0f ? std::min(value, 255.0f) : 0.0f;  // NaN: 0
        const int whole = int(code);
        colours[i][c] = std::uint8_t(whole + (code - float(whole) >= 0.5f));
      }
    }
  }
  static std::array<float, 3> small_normal(const Vec3& normal) {
    return representable(normal) ? std::array<float, 3>{float(normal.x()), float(normal.y()), float(normal.z())}
                                 : std::array<float, 3>{NAN, NAN, NAN};
  }
};

// A binary file's records where they lie, read in place: already small, as pc_error reads them
// (coordinates and normals stored in double are rounded to single precision).
struct PackedRecords {
  PackedPointCloud packed;  // a copy: each task works on a copy of its own (sorted_and_merged)
  bool with_normals;
  bool float_positions = std::none_of(packed.position.begin(), packed.position.end(),
                                      [](const PackedPointCloud::Field& f) { return f.is_double; });

  std::size_t size() const { return packed.count; }
  Vec3 position(std::size_t i) const { return read(i, packed.position); }
  // As the free function, read straight from single precision where the file stores it so (the
  // usual case: the points' check and sort keys then take half the instructions).
  bool ordered_position(std::size_t i, std::array<std::uint32_t, 3>& bits) const {
    if (!float_positions) return roving::ordered_position(position(i), bits);
    const char* item = packed.records + packed.stride * i;
    std::array<float, 3> p;
    for (int c = 0; c < 3; ++c) std::memcpy(&p[c], item + packed.position[c].offset, sizeof(float));
    if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))) return false;
    bits = {ordered_bits(p[0]), ordered_bits(p[1]), ordered_bits(p[2])};
    return true;
  }
  bool has_normals() const { return with_normals && packed.normals; }
  bool has_colours() const { return packed.colours; }
  Vec3 normal_as_read(std::size_t i) const { return read(i, packed.normal); }
  std::array<float, 3> normal(std::size_t i) const { return MemoryCloud::small_normal(normal_as_read(i)); }
  std::uint8_t colour(std::size_t i, int c) const {
    return std::uint8_t(packed.records[packed.stride * i + packed.colour[c]]);
  }
  void prefetch(std::size_t i) const { __builtin_prefetch(packed.records + packed.stride * i); }
  void prepare(std::size_t) const {}

  Vec3 read(std::size_t i, const std::array<PackedPointCloud::Field, 3>& fields) const {
    const char* item = packed.records + packed.stride * i;
    Vec3 v;
    for (int c = 0; c < 3; ++c) {
      if (fields[c].is_double) {
        std::memcpy(&v[c], item + fields[c].offset, sizeof(double));
      } else {
        float f;
        std::memcpy(&f, item + fields[c].offset, sizeof f);
        v[c] = f;
      }
    }
    return v;
  }
};

// The cloud's points sorted by `codec` (the order pc_error's sort gives: lexicographic, equal
// points in file order) and runs of equal points merged into one.
template <class Codec, class Cloud>
MpegPoints sorted_and_merged(const Cloud& cloud, const Codec& codec, const MpegReading& reading,
                             const std::string& name) {
  const bool keep_all = reading.dropdups == 0;
  using Entry = decltype(codec.make({}, 0));
  const std::size_t n = cloud.size();
  std::vector<Entry> order(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 65536), [&](const tbb::blocked_range<std::size_t>& range) {
    std::array<std::uint32_t, 3> bits{};
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      cloud.ordered_position(i, bits);  // true: checked before
      order[i] = codec.make(bits, i);
    }
  });
  radix_sort(order, [&codec](const Entry& e) { return codec.position(e); });

  // Runs of equal points, found and merged block by block on all cores: each block merges the runs
  // that begin in it, into the places counted before it.
  constexpr std::size_t kBlock = 65536;
  constexpr std::size_t kAhead = 16;
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
  std::vector<std::size_t> first_run(blocks + 1, 0);
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    std::size_t count = 0;
    for (std::size_t k = b * kBlock; k < std::min(n, (b + 1) * kBlock); ++k) {
      count += keep_all || k == 0 || codec.position(order[k]) != codec.position(order[k - 1]);
    }
    first_run[b + 1] = count;
  });
  std::partial_sum(first_run.begin(), first_run.end(), first_run.begin());
  const std::size_t runs = first_run.back();

  // A normal that is used must be finite (or NaN, where kept); the first such in the file's order
  // is the one named.
  const bool normals = cloud.has_normals(), colours = cloud.has_colours();
  std::atomic<std::size_t> first_bad_normal{n}, first_nan_normal{n}, nan_normals{0};
  MpegPoints points;
  points.points_read = n;
  points.positions.resize(runs);
  if (normals) points.normals.resize(runs);
  if (colours) points.colours.resize(runs);
  if (reading.merged_counts) points.merged.resize(runs);
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    // What the loop reads, copied into this frame: the colours' byte stores might otherwise be
    // into any of it, and the compiler would read it all again after each.
    const Cloud source = cloud;
    const Codec keys = codec;
    const Entry* const sorted = order.data();
    std::array<float, 3>* const positions_out = points.positions.data();
    std::array<float, 3>* const normals_out = points.normals.data();
    std::array<std::uint8_t, 3>* const colours_out = points.colours.data();
    const auto same_position = [&](std::size_t k, std::size_t j) {
      return keys.position(sorted[k]) == keys.position(sorted[j]);
    };
    const auto normal_at = [&](std::size_t k) {
      const std::uint32_t i = keys.index(sorted[k]);
      const std::array<float, 3> normal = source.normal(i);
      if (std::isnan(normal[0])) {
        const Vec3 read = source.normal_as_read(i);
        const bool nan = std::isnan(read.x()) || std::isnan(read.y()) || std::isnan(read.z());
        const auto fits = [](double c) { return std::isnan(c) || std::fabs(c) <= std::numeric_limits<float>::max(); };
        if (nan && fits(read.x()) && fits(read.y()) && fits(read.z())) {
          keep_least(first_nan_normal, i);
          ++nan_normals;
        } else {
          keep_least(first_bad_normal, i);
        }
      }
      return normal;
    };
    std::size_t out = first_run[b];
    std::size_t run = b * kBlock;
    while (!keep_all && run < n && run > 0 && same_position(run, run - 1)) ++run;  // the block before's
    for (const std::size_t stop = std::min(n, (b + 1) * kBlock); run < stop; ++out) {
      // The colours and normals are read in sorted order, at random in the file's: asked for
      // ahead, their cache misses overlap instead of following one another.
      if (run + kAhead < n && (normals || colours)) source.prefetch(keys.index(sorted[run + kAhead]));
      std::size_t end = run + 1;
      while (!keep_all && end < n && same_position(end, run)) ++end;
      positions_out[out] = keys.point(sorted[run]);
      if (reading.merged_counts) points.merged[out] = std::uint32_t(end - run);
      // mmetric averages the normals where it merges (--dropDuplicates 2); under 1 the first's is kept.
      if (normals && reading.average_normals && reading.dropdups == 2) {
        std::array<float, 3> sum = {0, 0, 0};  // in single precision, in the sorted order, as mmetric
        for (std::size_t k = run; k < end; ++k) {
          const std::array<float, 3> normal = normal_at(k);
          for (int c = 0; c < 3; ++c) sum[c] += normal[c];
        }
        for (int c = 0; c < 3; ++c) sum[c] /= float(end - run);
        normals_out[out] = sum;
      } else if (normals) {
        normals_out[out] = normal_at(run);
      }
      // Most points: their own colour, without three divisions; under --dropdups 1 the first's.
      if (colours && (end == run + 1 || reading.dropdups == 1)) {
        const std::uint32_t i = keys.index(sorted[run]);
        colours_out[out] = {source.colour(i, 0), source.colour(i, 1), source.colour(i, 2)};
      } else if (colours) {
        // pc_error sums the 8-bit values and divides as integers: the mean, truncated.
        long sum[3] = {0, 0, 0};
        for (std::size_t k = run; k < end; ++k) {
          for (int c = 0; c < 3; ++c) sum[c] += source.colour(keys.index(sorted[k]), c);
        }
        const long count = long(end - run);
        colours_out[out] = {std::uint8_t(sum[0] / count), std::uint8_t(sum[1] / count), std::uint8_t(sum[2] / count)};
      }
      run = end;
    }
  });
  if (first_bad_normal < n || (first_nan_normal < n && !reading.nan_normals)) {  // throws
    const auto i = static_cast<std::uint32_t>(std::min(first_bad_normal.load(), first_nan_normal.load()));
    to_float(cloud.normal_as_read(i), name, "normal", i);
  }
  points.nan_normals = nan_normals;
  points.first_nan_normal = first_nan_normal;
  return points;
}

// `cloud`'s points as pc_error holds them (mpeg_points): checked, sorted and merged.
template <class Cloud>
MpegPoints points_of(Cloud& cloud, const std::string& name, const MpegReading& reading) {
  const std::size_t n = cloud.size();
  // On all cores: the points checked and prepared, and the bits in which they differ from the
  // first. The first point that is not representable (in file order) is the one named.
  std::atomic<std::size_t> first_bad{n};
  using Varying = std::array<std::uint32_t, 3>;
  Varying first;
  if (!cloud.ordered_position(0, first)) to_float(cloud.position(0), name, "point", 0);  // throws
  const Varying varying = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n, 65536), Varying{},
      [&](const tbb::blocked_range<std::size_t>& range, Varying bits) {
        Varying p;
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          if (!cloud.ordered_position(i, p)) {
            keep_least(first_bad, i);
            return bits;
          }
          for (int c = 0; c < 3; ++c) bits[c] |= p[c] ^ first[c];
          cloud.prepare(i);
        }
        return bits;
      },
      [](Varying a, const Varying& b) {
        for (int c = 0; c < 3; ++c) a[c] |= b[c];
        return a;
      });
  if (first_bad < n) to_float(cloud.position(first_bad), name, "point", first_bad);  // throws

  PackedCodec packed;
  KeyLayout& layout = packed.layout;
  layout.first = first;
  for (int c = 0; c < 3; ++c) {
    layout.low[c] = varying[c] == 0 ? 0 : __builtin_ctz(varying[c]);
    layout.width[c] = varying[c] == 0 ? 0 : 32 - __builtin_clz(varying[c]) - layout.low[c];
  }
  while (layout.index_bits < 64 && (std::uint64_t{1} << layout.index_bits) < n) ++layout.index_bits;
  if (layout.bits() <= 64) return sorted_and_merged(cloud, packed, reading, name);
  return sorted_and_merged(cloud, WideCodec{}, reading, name);
}

}  // namespace

MpegPoints mpeg_points(const PointCloud& cloud, const std::string& name, const MpegReading& reading) {
  const bool with_normals = reading.normals;
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
  std::vector<std::array<float, 3>> normals(with_normals && !cloud.normals.empty() ? n : 0);
  std::vector<std::array<std::uint8_t, 4>> colours(cloud.colours.empty() ? 0 : n);
  MemoryCloud memory{&cloud, normals.empty() ? nullptr : normals.data(), colours.empty() ? nullptr : colours.data()};
  return points_of(memory, name, reading);
}

MpegPoints mpeg_points(const PackedPointCloud& packed, const std::string& name, const MpegReading& reading) {
  if (packed.count == 0) throw Error(fmt::format("{}: no points; expected a point cloud", name));
  PackedRecords records{packed, reading.normals};
  return points_of(records, name, reading);
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
  a.nan_normals = normals.nan_normals;
  a.first_nan_normal = normals.first_nan_normal;
}

}  // namespace roving
