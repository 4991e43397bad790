#include "roving/mpeg/lattice_neighbours.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace roving {
namespace {

constexpr std::int32_t kLimit = 1 << 20;  // |coordinate| <= kLimit
constexpr std::int32_t kBias = 1 << 18;   // brick coordinates (within +-2^17) made positive in 21 bits
constexpr std::size_t kCubeShells = 4;    // squared lengths 0 .. 3: the 3^3 cube

struct Offset {
  std::int8_t x, y, z;
};

// Every lattice offset of squared length <= kMaxSquared, shortest first, grouped by length.
struct Shells {
  std::vector<Offset> offsets;
  std::vector<std::uint32_t> end;  // per shell, one past its last offset
  std::vector<int> squared;        // per shell
  // Shells 0 to 3 as bits of the 3^3 cube around a query (LatticeNeighbours::nearest).
  std::array<std::uint32_t, kCubeShells> cube_masks{};
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
      const Offset o = all[k].second;
      if (all[k].first < int(kCubeShells)) {
        s.cube_masks[std::size_t(all[k].first)] |= 1u << (9 * (o.z + 1) + 3 * (o.y + 1) + o.x + 1);
      }
    }
    return s;
  }();
  return table;
}

std::uint64_t brick_key(std::int32_t x, std::int32_t y, std::int32_t z) {
  return std::uint64_t(x + kBias) << 42 | std::uint64_t(y + kBias) << 21 | std::uint64_t(z + kBias);
}

std::size_t hash(std::uint64_t key, int shift) {
  return std::size_t((key * 0x9E3779B97F4A7C15ull) >> shift);
}

}  // namespace

bool LatticeNeighbours::on_lattice(const std::array<float, 3>& q) {
  for (const float c : q) {
    if (!(std::fabs(c) <= float(kLimit)) || std::trunc(c) != c) return false;
  }
  return true;
}

std::int32_t LatticeNeighbours::find(std::uint64_t key) const {
  const std::size_t mask = keys_.size() - 1;
  for (std::size_t at = hash(key, shift_);; at = (at + 1) & mask) {
    if (keys_[at] == key + 1) return slots_[at];
    if (keys_[at] == 0) return -1;
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
  // The bricks, numbered as first met; the table doubles when half full.
  l.shift_ = 64 - 10;
  l.keys_.assign(std::size_t{1} << 10, 0);
  l.slots_.assign(l.keys_.size(), -1);
  const auto insert = [&l](std::uint64_t key, std::int32_t slot) {
    const std::size_t mask = l.keys_.size() - 1;
    std::size_t at = hash(key, l.shift_);
    while (l.keys_[at] != 0) at = (at + 1) & mask;
    l.keys_[at] = key + 1;
    l.slots_[at] = slot;
  };
  std::vector<std::int32_t> brick_of(points.size());
  std::uint64_t last_key = ~std::uint64_t{0};
  std::int32_t last_brick = -1;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::array<float, 3>& p = points[i];
    const std::int32_t x = std::int32_t(p[0]), y = std::int32_t(p[1]), z = std::int32_t(p[2]);
    const std::uint64_t key = brick_key(x >> 3, y >> 3, z >> 3);
    if (key != last_key) {
      std::int32_t brick = l.find(key);
      if (brick < 0) {
        brick = std::int32_t(l.bricks_.size());
        l.bricks_.emplace_back();
        if (2 * l.bricks_.size() > l.keys_.size()) {  // rehash into twice the room
          std::vector<std::uint64_t> keys = std::move(l.keys_);
          std::vector<std::int32_t> slots = std::move(l.slots_);
          l.keys_.assign(2 * keys.size(), 0);
          l.slots_.assign(l.keys_.size(), -1);
          --l.shift_;
          for (std::size_t k = 0; k < keys.size(); ++k) {
            if (keys[k] != 0) insert(keys[k] - 1, slots[k]);
          }
        }
        insert(key, brick);
      }
      last_key = key;
      last_brick = brick;
    }
    brick_of[i] = last_brick;
    Brick& b = l.bricks_[std::size_t(last_brick)];
    const std::uint64_t bit = std::uint64_t{1} << ((x & 7) | (y & 7) << 3);
    if (b.words[std::size_t(z & 7)] & bit) return nullptr;  // two equal points
    b.words[std::size_t(z & 7)] |= bit;
  }
  // Each brick's points after the bricks before it, in voxel order.
  std::uint32_t first = 0;
  for (Brick& b : l.bricks_) {
    b.first = first;
    std::uint16_t before = 0;
    for (std::size_t w = 0; w < 8; ++w) {
      b.before[w] = before;
      before = std::uint16_t(before + __builtin_popcountll(b.words[w]));
    }
    first += before;
  }
  l.order_.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::array<float, 3>& p = points[i];
    const std::int32_t x = std::int32_t(p[0]), y = std::int32_t(p[1]), z = std::int32_t(p[2]);
    const Brick& b = l.bricks_[std::size_t(brick_of[i])];
    const std::uint64_t word = b.words[std::size_t(z & 7)];
    const int bit = (x & 7) | (y & 7) << 3;
    l.order_[b.first + b.before[std::size_t(z & 7)] +
             std::uint32_t(__builtin_popcountll(word & ((std::uint64_t{1} << bit) - 1)))] = std::uint32_t(i);
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

inline std::uint32_t LatticeNeighbours::point_in(const Brick& b, std::int32_t tx, std::int32_t ty,
                                                 std::int32_t tz) const {
  const std::uint64_t word = b.words[std::size_t(tz & 7)];
  const int bit = (tx & 7) | (ty & 7) << 3;
  return order_[b.first + b.before[std::size_t(tz & 7)] +
                std::uint32_t(__builtin_popcountll(word & ((std::uint64_t{1} << bit) - 1)))];
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

  // Shells 0 to 3 (the 3^3 voxels around q) read at once, row by row from the bricks' masks:
  // bit 9 (dz + 1) + 3 (dy + 1) + dx + 1 of `cube` is voxel q + (dx, dy, dz).
  std::uint32_t cube = 0;
  for (std::int32_t dz = -1; dz <= 1; ++dz) {
    const std::int32_t tz = lz + dz;
    for (std::int32_t dy = -1; dy <= 1; ++dy) {
      const std::int32_t ty = ly + dy;
      const auto row = [&](std::int32_t tx) {  // x = 0 .. 7 of the brick holding tx
        const std::int32_t brick = brick_near(probe, tx, ty, tz);
        if (brick < 0) return 0u;
        return std::uint32_t(bricks_[std::size_t(brick)].words[std::size_t(tz & 7)] >> ((ty & 7) * 8)) &
               0xffu;
      };
      std::uint32_t bits = row(lx) << 1;  // bit i: x = i - 1 of q's brick
      if (lx == 0) bits |= row(-1) >> 7;
      if (lx == 7) bits |= (row(8) & 1u) << 9;
      cube |= (bits >> lx & 7u) << (9 * (dz + 1) + 3 * (dy + 1));
    }
  }
  for (std::size_t g = skip_zero ? 1 : 0; g < kCubeShells; ++g) {
    std::uint32_t found = cube & s.cube_masks[g];
    if (found == 0) continue;
    std::size_t count = 0;
    for (; found != 0; found &= found - 1, ++count) {
      const int bit = __builtin_ctz(found);
      const std::int32_t tx = lx + bit % 3 - 1, ty = ly + bit / 3 % 3 - 1, tz = lz + bit / 9 - 1;
      shell.index[count] = point_in(bricks_[std::size_t(brick_near(probe, tx, ty, tz))], tx, ty, tz);
    }
    shell.squared = s.squared[g];
    shell.count = count;
    return true;
  }

  // Farther shells offset by offset.
  for (std::size_t g = kCubeShells; g < s.end.size(); ++g) {
    std::size_t count = 0;
    for (std::size_t k = s.end[g - 1]; k < s.end[g]; ++k) {
      const Offset o = s.offsets[k];
      const std::int32_t tx = lx + o.x, ty = ly + o.y, tz = lz + o.z;
      const std::int32_t brick = brick_near(probe, tx, ty, tz);
      if (brick < 0) continue;
      const Brick& b = bricks_[std::size_t(brick)];
      if (!(b.words[std::size_t(tz & 7)] >> ((tx & 7) | (ty & 7) << 3) & 1)) continue;
      if (count < kListed) shell.index[count] = point_in(b, tx, ty, tz);
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
