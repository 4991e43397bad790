#include "roving/mpeg/lattice_neighbours.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace roving {
namespace {

// Where the compiler can, the bit counts (of the bricks' words, to find a point's place) are the
// CPU's POPCNT, chosen as the program starts: the project's flags ask for no more than x86-64's
// first instructions, which lack it, and counted in software they took a tenth of the search's
// instructions. The functions that count are made twice; cube_around is forced inline into both.
#if defined(__x86_64__) && !defined(__POPCNT__) && defined(__GNUC__) && !defined(__clang__)
#define ROVING_WITH_POPCOUNT __attribute__((target_clones("popcnt", "default")))
#else
#define ROVING_WITH_POPCOUNT
#endif

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
  // The first shells as bits of the cubes around a query (cube_around), a word per layer: those
  // of the 3^3 cube (squared lengths 0 to 3) and then of the 5^3 cube (4 to 8); `small_end` and
  // `large_end`: the first shell each leaves out.
  std::vector<std::array<std::uint64_t, 3>> small_masks;
  std::vector<std::array<std::uint64_t, 5>> large_masks;  // indexed from small_end
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
    const auto add = [](auto& layers, const Offset& o, int reach) {
      layers[std::size_t(o.z + reach)] |= std::uint64_t{1} << (8 * (o.y + reach) + o.x + reach);
    };
    for (std::size_t g = 0; within(g, 1); ++g) {
      s.small_masks.emplace_back();
      for (std::size_t k = g == 0 ? 0 : s.end[g - 1]; k < s.end[g]; ++k) add(s.small_masks.back(), s.offsets[k], 1);
      s.small_end = g + 1;
    }
    for (std::size_t g = s.small_end; within(g, 2); ++g) {
      s.large_masks.emplace_back();
      for (std::size_t k = s.end[g - 1]; k < s.end[g]; ++k) add(s.large_masks.back(), s.offsets[k], 2);
      s.large_end = g + 1;
    }
    return s;
  }();
  return table;
}

std::uint64_t brick_key(std::int32_t x, std::int32_t y, std::int32_t z) {
  return std::uint64_t(x + kBias) << 42 | std::uint64_t(y + kBias) << 21 | std::uint64_t(z + kBias);
}

// A byte repeated in every byte of a word.
constexpr std::uint64_t bytes(std::uint64_t byte) {
  return byte * 0x0101010101010101ull;
}

// The voxels within `kReach` of a query at (lx, ly, lz) of its brick, as a word per layer of a
// cube of side 2 kReach + 1: bit 8 (dy + kReach) + dx + kReach of layer dz + kReach is the query's
// voxel + (dx, dy, dz). A layer is read from the bricks' words whole, a byte per row:
// `word(sx, sy, tz)` is word tz & 7 of the brick (sx, sy, tz >> 3) from the query's (tz within
// -8 .. 15).
template <int kReach, class Word>
__attribute__((always_inline)) inline std::array<std::uint64_t, 2 * kReach + 1> cube_around(
    std::int32_t lx, std::int32_t ly, std::int32_t lz, const Word& word) {
  constexpr int side = 2 * kReach + 1;
  constexpr std::uint64_t lanes = ((std::uint64_t{1} << (8 * side)) - 1) & bytes((1u << side) - 1);
  const std::int32_t first_row = ly - kReach;
  // Rows first_row .. first_row + 2 kReach of layer tz of the bricks sx from the query's, a byte
  // each from the lowest (kReach < 4: they reach into one brick either way at most).
  const auto rows = [&](std::int32_t sx, std::int32_t tz) __attribute__((always_inline)) {
    if (first_row < 0) return word(sx, 0, tz) << (-8 * first_row) | word(sx, -1, tz) >> (64 + 8 * first_row);
    std::uint64_t stack = word(sx, 0, tz) >> (8 * first_row);
    if (ly + kReach > 7) stack |= word(sx, 1, tz) << (64 - 8 * first_row);
    return stack;
  };
  std::array<std::uint64_t, side> cube;
  for (int k = 0; k < side; ++k) {
    const std::int32_t tz = lz + k - kReach;
    const std::uint64_t centre = rows(0, tz);
    std::uint64_t layer;
    if (lx < kReach) {  // bits x < 0 from the brick before in x
      const int shift = kReach - lx;
      layer = (centre << shift & bytes(0xffu << shift & 0xffu)) |
              (rows(-1, tz) >> (8 - shift) & bytes((1u << shift) - 1));
    } else if (lx > 7 - kReach) {  // bits x > 7 from the brick after
      const int shift = lx - kReach;
      layer = (centre >> shift & bytes(0xffu >> shift)) |
              (rows(1, tz) << (8 - shift) & bytes(0xffu << (8 - shift) & 0xffu));
    } else {
      layer = centre >> (lx - kReach);
    }
    cube[std::size_t(k)] = layer & lanes;
  }
  return cube;
}

// Set bits of a word: one instruction in the functions made for CPUs with POPCNT
// (ROVING_WITH_POPCOUNT), a call into libgcc in the others.
inline std::uint32_t bit_count(std::uint64_t v) { return std::uint32_t(__builtin_popcountll(v)); }

std::size_t hash(std::uint64_t key, int shift) {
  return std::size_t((key * 0x9E3779B97F4A7C15ull) >> shift);
}

}  // namespace

const LatticeNeighbours::Brick LatticeNeighbours::kNoBrick{};

bool LatticeNeighbours::on_lattice(const std::array<float, 3>& q) {
  for (const float c : q) {
    if (!(std::fabs(c) <= float(kLimit)) || float(std::int32_t(c)) != c) return false;  // the cast: exact, in range
  }
  return true;
}

// Open addressing in table[first, first + 2^bits): the slot holding `key` (as key + 1), or the
// empty one where it would go.
inline std::size_t LatticeNeighbours::slot_of(const std::vector<Slot>& table, std::size_t first, int bits,
                                              std::uint64_t key) {
  const std::size_t mask = (std::size_t{1} << bits) - 1;
  for (std::size_t at = hash(key, 64 - bits);; at = (at + 1) & mask) {
    const Slot& slot = table[first + at];
    if (slot.key == key + 1 || slot.key == 0) return first + at;
  }
}

inline std::int32_t LatticeNeighbours::find(std::uint64_t key) const {
  const std::size_t slab = std::size_t(std::int64_t(key >> 42) - kBias - slab_low_);  // wraps below
  if (slab >= slabs_.size() || slabs_[slab].bits == 0) return -1;
  return table_[slot_of(table_, slabs_[slab].first, slabs_[slab].bits, key)].brick;
}

ROVING_WITH_POPCOUNT std::unique_ptr<LatticeNeighbours> LatticeNeighbours::build(
    const std::vector<std::array<float, 3>>& points) {
  if (points.empty() || points.size() > UINT32_MAX) return nullptr;
  if (!std::all_of(points.begin(), points.end(), on_lattice)) return nullptr;
  auto lattice = std::make_unique<LatticeNeighbours>();
  LatticeNeighbours& l = *lattice;
  // The bricks, numbered as first met, through one table of all (doubled when 5/8 full; sorted
  // points come back to the bricks of the voxels a few steps of x before: those are looked up in
  // a small cache first). They are counted first, then filled, so that they take no more room than
  // they need.
  std::vector<Slot> all(std::size_t{1} << 10);
  int all_bits = 10;
  std::vector<std::uint64_t> keys;  // per brick
  std::vector<std::int32_t> brick_of(points.size());
  constexpr int kRecentBits = 12;
  std::vector<std::pair<std::uint64_t, std::int32_t>> recent(std::size_t{1} << kRecentBits, {0, -1});
  std::uint64_t last_key = ~std::uint64_t{0};
  std::int32_t last_brick = -1;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::array<float, 3>& p = points[i];
    const std::uint64_t key = brick_key(std::int32_t(p[0]) >> 3, std::int32_t(p[1]) >> 3, std::int32_t(p[2]) >> 3);
    if (key != last_key) {
      std::pair<std::uint64_t, std::int32_t>& seen = recent[hash(key, 64 - kRecentBits)];
      std::int32_t brick = seen.first == key + 1 ? seen.second : all[slot_of(all, 0, all_bits, key)].brick;
      if (brick < 0) {
        brick = std::int32_t(keys.size());
        keys.push_back(key);
        if (8 * keys.size() > 5 * all.size()) {  // rehash into twice the room
          all.assign(2 * all.size(), Slot{});
          ++all_bits;
          for (std::size_t b = 0; b < keys.size(); ++b) {
            all[slot_of(all, 0, all_bits, keys[b])] = {keys[b] + 1, std::int32_t(b)};
          }
        } else {
          all[slot_of(all, 0, all_bits, key)] = {key + 1, brick};
        }
      }
      seen = {key + 1, brick};
      last_key = key;
      last_brick = brick;
    }
    brick_of[i] = last_brick;
  }
  all = {};
  // Each slab's bricks into a table of its own, at most 5/8 full.
  const auto slab_x = [](std::uint64_t key) { return std::int32_t(key >> 42) - kBias; };
  const auto [low, high] = std::minmax_element(keys.begin(), keys.end());  // by x first
  l.slab_low_ = slab_x(*low);
  l.slabs_.assign(std::size_t(slab_x(*high) - l.slab_low_ + 1), Slab{});
  std::vector<std::uint32_t> slab_bricks(l.slabs_.size(), 0);
  for (const std::uint64_t key : keys) ++slab_bricks[std::size_t(slab_x(key) - l.slab_low_)];
  std::size_t slots = 0;
  for (std::size_t slab = 0; slab < l.slabs_.size(); ++slab) {
    if (slab_bricks[slab] == 0) continue;
    int bits = 1;
    while (8 * std::size_t(slab_bricks[slab]) > 5 * (std::size_t{1} << bits)) ++bits;
    l.slabs_[slab] = {std::uint32_t(slots), std::uint8_t(bits)};
    slots += std::size_t{1} << bits;
    if (slots > UINT32_MAX) return nullptr;  // past a billion bricks: the general search serves
  }
  l.table_.assign(slots, Slot{});
  for (std::size_t b = 0; b < keys.size(); ++b) {
    const Slab& slab = l.slabs_[std::size_t(slab_x(keys[b]) - l.slab_low_)];
    l.table_[slot_of(l.table_, slab.first, slab.bits, keys[b])] = {keys[b] + 1, std::int32_t(b)};
  }
  const std::int32_t bricks = std::int32_t(keys.size());
  keys = {};
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

inline const LatticeNeighbours::Brick& LatticeNeighbours::brick_near(Probe& probe, std::int32_t sx, std::int32_t sy,
                                                                     std::int32_t sz) const {
  const int k = (sx + 1) * 9 + (sy + 1) * 3 + sz + 1;
  const Brick*& brick = probe.near[std::size_t(k)];
  if (!(probe.looked_up >> k & 1)) {
    probe.looked_up |= std::uint32_t{1} << k;
    const std::int32_t index = find(brick_key(probe.block[0] + sx, probe.block[1] + sy, probe.block[2] + sz));
    brick = index < 0 ? &kNoBrick : &bricks_[std::size_t(index)];
  }
  return *brick;
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

ROVING_WITH_POPCOUNT bool LatticeNeighbours::nearest(const std::array<float, 3>& q, bool skip_zero, Probe& probe,
                                              Shell& shell) const {
  const std::int32_t x = std::int32_t(q[0]), y = std::int32_t(q[1]), z = std::int32_t(q[2]);
  const std::array<std::int32_t, 3> block{x >> 3, y >> 3, z >> 3};
  if (block != probe.block) {
    probe.block = block;
    probe.looked_up = 0;
  }
  const std::int32_t lx = x & 7, ly = y & 7, lz = z & 7;  // offsets from here reach -8 .. 15
  const Shells& s = shells();

  // The nearest shells read at once from the bricks' bits: within the 3^3 cube, then the 5^3.
  const auto word = [&](std::int32_t sx, std::int32_t sy, std::int32_t tz) __attribute__((always_inline)) {
    return brick_near(probe, sx, sy, tz >> 3).words[std::size_t(tz & 7)];
  };
  const auto brick_index = [&](std::int32_t tx, std::int32_t ty, std::int32_t tz) {
    return std::int32_t(&brick_near(probe, tx >> 3, ty >> 3, tz >> 3) - bricks_.data());
  };
  // The first shell from `first` with a bit in `cube`, listed; false where none.
  const auto list = [&](const auto& cube, const auto& masks, std::size_t first, std::size_t end, int reach) {
    for (std::size_t g = std::max(first, skip_zero ? std::size_t{1} : std::size_t{0}); g < end; ++g) {
      const auto& mask = masks[g - first];
      std::uint64_t any = 0;
      for (std::size_t k = 0; k < cube.size(); ++k) any |= cube[k] & mask[k];
      if (any == 0) continue;
      std::size_t count = 0;
      for (std::size_t k = 0; k < cube.size(); ++k) {
        for (std::uint64_t found = cube[k] & mask[k]; found != 0; found &= found - 1, ++count) {
          const int bit = __builtin_ctzll(found);
          const std::int32_t tx = lx + (bit & 7) - reach, ty = ly + (bit >> 3) - reach, tz = lz + int(k) - reach;
          shell.index[count] = point_in(brick_index(tx, ty, tz), tx, ty, tz);
        }
      }
      shell.squared = s.squared[g];
      shell.count = count;
      return true;
    }
    return false;
  };
  if (list(cube_around<1>(lx, ly, lz, word), s.small_masks, 0, s.small_end, 1)) return true;
  if (list(cube_around<2>(lx, ly, lz, word), s.large_masks, s.small_end, s.large_end, 2)) return true;

  // Farther shells offset by offset.
  for (std::size_t g = s.large_end; g < s.end.size(); ++g) {
    std::size_t count = 0;
    for (std::size_t k = s.end[g - 1]; k < s.end[g]; ++k) {
      const Offset o = s.offsets[k];
      const std::int32_t tx = lx + o.x, ty = ly + o.y, tz = lz + o.z;
      const Brick& b = brick_near(probe, tx >> 3, ty >> 3, tz >> 3);  // kNoBrick: no bit set
      if (!(b.words[std::size_t(tz & 7)] >> ((tx & 7) | (ty & 7) << 3) & 1)) continue;
      if (count < kListed) shell.index[count] = point_in(std::int32_t(&b - bricks_.data()), tx, ty, tz);
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
