#include "roving/mpeg/lattice_neighbours.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace roving {
namespace {

constexpr std::int32_t kLimit = 1 << 20;  // |coordinate| <= kLimit
constexpr std::int32_t kBias = 1 << 18;   // brick coordinates (within +-2^17) made positive in 21 bits

struct Offset {
  std::int8_t x, y, z;
};

// Every lattice offset of squared length <= kMaxSquared, shortest first, grouped by length.
struct Shells {
  std::vector<Offset> offsets;
  std::vector<std::uint32_t> end;  // per shell, one past its last offset
  std::vector<int> squared;        // per shell
  // The first shells as bits of the cubes around a query (cube_around): those of the 3^3 cube
  // (squared lengths 0 to 3) and then of the 5^3 cube (4 to 8); `small_end` and `large_end`: the
  // first shell each leaves out.
  std::vector<std::uint32_t> small_masks;
  std::vector<unsigned __int128> large_masks;  // indexed from small_end
  std::size_t small_end = 0, large_end = 0;
};

const Shells& shells() {
  static const Shells table = [] {
    constexpr int r = 8;
    static_assert(r * r == LatticeNeighbours::kMaxSquared, "the offsets reach one brick either way");
    std::vector<std::pair<int, Offset>> all;
    for (int x = -r; x <= r; ++x) {
      for (int y = -r; y <= r; ++y) {
        for (int z = -r; z <= r; ++z) {
          const int squared = x * x + y * y + z * z;
          if (squared <= r * r)
            all.push_back({squared, Offset{std::int8_t(x), std::int8_t(y), std::int8_t(z)}});
        }
      }
    }
    std::stable_sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    Shells s;
    for (std::size_t k = 0; k < all.size(); ++k) {
      s.offsets.push_back(all[k].second);
      if (k + 1 == all.size() || all[k + 1].first != all[k].first) {
        s.end.push_back(std::uint32_t(k + 1));
        s.squared.push_back(all[k].first);
      }
    }
    // Each shell as cube bits, while all its offsets are in the cube.
    const auto within = [&](std::size_t g, int reach) {
      for (std::size_t k = g == 0 ? 0 : s.end[g - 1]; k < s.end[g]; ++k) {
        const Offset o = s.offsets[k];
        if (std::abs(o.x) > reach || std::abs(o.y) > reach || std::abs(o.z) > reach) return false;
      }
      return true;
    };
    const auto bit = [](const Offset& o, int reach) {
      const int side = 2 * reach + 1;
      return side * side * (o.z + reach) + side * (o.y + reach) + o.x + reach;
    };
    for (std::size_t g = 0; within(g, 1); ++g) {
      s.small_masks.push_back(0);
      for (std::size_t k = g == 0 ? 0 : s.end[g - 1]; k < s.end[g]; ++k)
        s.small_masks[g] |= 1u << bit(s.offsets[k], 1);
      s.small_end = g + 1;
    }
    for (std::size_t g = s.small_end; within(g, 2); ++g) {
      s.large_masks.push_back(0);
      for (std::size_t k = s.end[g - 1]; k < s.end[g]; ++k) {
        s.large_masks.back() |= static_cast<unsigned __int128>(1) << bit(s.offsets[k], 2);
      }
      s.large_end = g + 1;
    }
    return s;
  }();
  return table;
}

std::uint64_t brick_key(std::int32_t x, std::int32_t y, std::int32_t z) {
  return std::uint64_t(x + kBias) << 42 | std::uint64_t(y + kBias) << 21 | std::uint64_t(z + kBias);
}

// The voxels within `kReach` of a query at (lx, ly, lz) of its brick, as bits of a cube of side
// 2 kReach + 1 (bit side^2 (dz + kReach) + side (dy + kReach) + dx + kReach: the query's voxel
// + (dx, dy, dz)), read a row at a time: `row(tx, ty, tz)` is row (ty, tz) of the brick holding
// those coordinates (each within -8 .. 15), 8 bits.
template <class Bits, int kReach, class Row>
Bits cube_around(std::int32_t lx, std::int32_t ly, std::int32_t lz, const Row& row) {
  constexpr int side = 2 * kReach + 1;
  Bits cube = 0;
  for (std::int32_t dz = -kReach; dz <= kReach; ++dz) {
    for (std::int32_t dy = -kReach; dy <= kReach; ++dy) {
      const std::int32_t ty = ly + dy, tz = lz + dz;
      std::uint32_t bits = row(lx, ty, tz) << 8;  // bit i: x = i - 8 of the query's brick
      if (lx < kReach) bits |= row(-1, ty, tz);
      if (lx > 7 - kReach) bits |= row(8, ty, tz) << 16;
      cube |= Bits(bits >> (8 + lx - kReach) & ((1u << side) - 1))
              << (side * side * (dz + kReach) + side * (dy + kReach));
    }
  }
  return cube;
}

// Set bits of a word (without asking the compiler for a CPU with POPCNT).
std::uint32_t bit_count(std::uint64_t v) {
  v = v - (v >> 1 & 0x5555555555555555ull);
  v = (v & 0x3333333333333333ull) + (v >> 2 & 0x3333333333333333ull);
  v = (v + (v >> 4)) & 0x0f0f0f0f0f0f0f0full;
  return std::uint32_t((v * 0x0101010101010101ull) >> 56);
}

int lowest_bit(std::uint32_t bits) {
  return __builtin_ctz(bits);
}
int lowest_bit(unsigned __int128 bits) {
  const std::uint64_t low = std::uint64_t(bits);
  return low != 0 ? __builtin_ctzll(low) : 64 + __builtin_ctzll(std::uint64_t(bits >> 64));
}

std::size_t hash(std::uint64_t key, int shift) {
  return std::size_t((key * 0x9E3779B97F4A7C15ull) >> shift);
}

}  // namespace

bool LatticeNeighbours::on_lattice(const std::array<float, 3>& q) {
  for (const float c : q) {
    if (!(std::fabs(c) <= float(kLimit)) || float(std::int32_t(c)) != c) return false;  // the cast: exact, in range
  }
  return true;
}

std::int32_t LatticeNeighbours::find(std::uint64_t key) const {
  const std::size_t mask = table_.size() - 1;
  for (std::size_t at = hash(key, shift_);; at = (at + 1) & mask) {
    if (table_[at].key == key + 1) return table_[at].brick;
    if (table_[at].key == 0) return -1;
  }
}

inline std::int32_t LatticeNeighbours::find(std::uint64_t key, Probe& probe) const {
  std::pair<std::uint64_t, std::int32_t>& recent = probe.recent[hash(key, 64 - Probe::kRecentBits)];
  if (recent.first != key + 1) recent = {key + 1, find(key)};
  return recent.second;
}

std::unique_ptr<LatticeNeighbours> LatticeNeighbours::build(const std::vector<std::array<float, 3>>& points) {
  if (points.empty() || points.size() > UINT32_MAX) return nullptr;
  if (!std::all_of(points.begin(), points.end(), on_lattice)) return nullptr;
  auto lattice = std::make_unique<LatticeNeighbours>();
  LatticeNeighbours& l = *lattice;
  // The bricks, numbered as first met; the table doubles when half full. They are counted first,
  // then filled, so that they take no more room than they need.
  l.shift_ = 64 - 10;
  l.table_.assign(std::size_t{1} << 10, Slot{});
  const auto insert = [&l](const Slot& slot) {
    const std::size_t mask = l.table_.size() - 1;
    std::size_t at = hash(slot.key - 1, l.shift_);
    while (l.table_[at].key != 0) at = (at + 1) & mask;
    l.table_[at] = slot;
  };
  std::vector<std::int32_t> brick_of(points.size());
  std::uint64_t last_key = ~std::uint64_t{0};
  std::int32_t last_brick = -1, bricks = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::array<float, 3>& p = points[i];
    const std::uint64_t key = brick_key(std::int32_t(p[0]) >> 3, std::int32_t(p[1]) >> 3, std::int32_t(p[2]) >> 3);
    if (key != last_key) {
      std::int32_t brick = l.find(key);
      if (brick < 0) {
        brick = bricks++;
        if (2 * std::size_t(bricks) > l.table_.size()) {  // rehash into twice the room
          std::vector<Slot> table = std::move(l.table_);
          l.table_.assign(2 * table.size(), Slot{});
          --l.shift_;
          for (const Slot& slot : table) {
            if (slot.key != 0) insert(slot);
          }
        }
        insert(Slot{key + 1, brick});
      }
      last_key = key;
      last_brick = brick;
    }
    brick_of[i] = last_brick;
  }
  l.bricks_.resize(std::size_t(bricks));
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::array<float, 3>& p = points[i];
    const std::int32_t x = std::int32_t(p[0]), y = std::int32_t(p[1]), z = std::int32_t(p[2]);
    Brick& b = l.bricks_[std::size_t(brick_of[i])];
    const std::uint64_t bit = std::uint64_t{1} << ((x & 7) | (y & 7) << 3);
    if (b.words[std::size_t(z & 7)] & bit) return nullptr;  // two equal points
    b.words[std::size_t(z & 7)] |= bit;
  }
  // Each brick's points after the bricks before it, in voxel order.
  l.starts_.resize(l.bricks_.size());
  std::uint32_t first = 0;
  for (std::size_t brick = 0; brick < l.bricks_.size(); ++brick) {
    BrickStart& start = l.starts_[brick];
    start.first = first;
    std::uint16_t before = 0;
    for (std::size_t w = 0; w < 8; ++w) {
      start.before[w] = before;
      before = std::uint16_t(before + bit_count(l.bricks_[brick].words[w]));
    }
    first += before;
  }
  l.order_.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::array<float, 3>& p = points[i];
    const std::int32_t x = std::int32_t(p[0]), y = std::int32_t(p[1]), z = std::int32_t(p[2]);
    l.order_[l.place(brick_of[i], x, y, z)] = std::uint32_t(i);
  }
  return lattice;
}

inline std::int32_t LatticeNeighbours::brick_near(Probe& probe, std::int32_t tx, std::int32_t ty,
                                                  std::int32_t tz) const {
  const std::size_t around = std::size_t(((tx >> 3) + 1) * 9 + ((ty >> 3) + 1) * 3 + (tz >> 3) + 1);
  std::int32_t& brick = probe.near[around];
  if (brick == -2) {
    brick = find(
        brick_key(probe.block[0] + (tx >> 3), probe.block[1] + (ty >> 3), probe.block[2] + (tz >> 3)), probe);
  }
  return brick;
}

inline std::size_t LatticeNeighbours::place(std::int32_t brick, std::int32_t tx, std::int32_t ty,
                                            std::int32_t tz) const {
  const BrickStart& start = starts_[std::size_t(brick)];
  const std::uint64_t word = bricks_[std::size_t(brick)].words[std::size_t(tz & 7)];
  const int bit = (tx & 7) | (ty & 7) << 3;
  return start.first + start.before[std::size_t(tz & 7)] + bit_count(word & ((std::uint64_t{1} << bit) - 1));
}

inline std::uint32_t LatticeNeighbours::point_in(std::int32_t brick, std::int32_t tx, std::int32_t ty,
                                                 std::int32_t tz) const {
  return order_[place(brick, tx, ty, tz)];
}

bool LatticeNeighbours::nearest(const std::array<float, 3>& q, bool skip_zero, Probe& probe,
                                Shell& shell) const {
  const std::int32_t x = std::int32_t(q[0]), y = std::int32_t(q[1]), z = std::int32_t(q[2]);
  const std::array<std::int32_t, 3> block{x >> 3, y >> 3, z >> 3};
  if (block != probe.block) {
    probe.block = block;
    probe.near.fill(-2);
  }
  const std::int32_t lx = x & 7, ly = y & 7, lz = z & 7;  // offsets from here reach -8 .. 15
  const Shells& s = shells();

  // The nearest shells read at once from the bricks' bits: within the 3^3 cube, then the 5^3.
  const auto row = [&](std::int32_t tx, std::int32_t ty, std::int32_t tz) {
    const std::int32_t brick = brick_near(probe, tx, ty, tz);
    if (brick < 0) return 0u;
    return std::uint32_t(bricks_[std::size_t(brick)].words[std::size_t(tz & 7)] >> ((ty & 7) * 8)) & 0xffu;
  };
  // The first shell from `first` with a bit in `cube`, listed; false where none.
  const auto list = [&](auto cube, const auto& masks, std::size_t first, std::size_t end, int reach) {
    const int side = 2 * reach + 1;
    for (std::size_t g = std::max(first, skip_zero ? std::size_t{1} : std::size_t{0}); g < end; ++g) {
      auto found = cube & masks[g - first];
      if (found == 0) continue;
      std::size_t count = 0;
      for (; found != 0; found &= found - 1, ++count) {
        const int bit = lowest_bit(found);
        const std::int32_t tx = lx + bit % side - reach, ty = ly + bit / side % side - reach,
                           tz = lz + bit / (side * side) - reach;
        shell.index[count] = point_in(brick_near(probe, tx, ty, tz), tx, ty, tz);
      }
      shell.squared = s.squared[g];
      shell.count = count;
      return true;
    }
    return false;
  };
  if (list(cube_around<std::uint32_t, 1>(lx, ly, lz, row), s.small_masks, 0, s.small_end, 1)) return true;
  if (list(cube_around<unsigned __int128, 2>(lx, ly, lz, row), s.large_masks, s.small_end, s.large_end, 2)) {
    return true;
  }

  // Farther shells offset by offset.
  for (std::size_t g = s.large_end; g < s.end.size(); ++g) {
    std::size_t count = 0;
    for (std::size_t k = s.end[g - 1]; k < s.end[g]; ++k) {
      const Offset o = s.offsets[k];
      const std::int32_t tx = lx + o.x, ty = ly + o.y, tz = lz + o.z;
      const std::int32_t brick = brick_near(probe, tx, ty, tz);
      if (brick < 0) continue;
      const Brick& b = bricks_[std::size_t(brick)];
      if (!(b.words[std::size_t(tz & 7)] >> ((tx & 7) | (ty & 7) << 3) & 1)) continue;
      if (count < kListed) shell.index[count] = point_in(brick, tx, ty, tz);
      ++count;
    }
    if (count > 0) {
      shell.squared = s.squared[g];
      shell.count = count;
      return true;
    }
  }
  return false;
}

}  // namespace roving
