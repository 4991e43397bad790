// Nearest points of a voxelised cloud (every coordinate an integer, as codecs' clouds are), found a
// shell at a time: lattice offsets are tried in order of their length against bit masks of the
// occupied voxels, so that the first shell with a point holds every point at the least distance,
// the set pc_error's tie rules ask for (point_cloud_psnr.cpp), at a fraction of a k-d tree's cost.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace roving {

class LatticeNeighbours {
  // One cache line of occupancy: bit (x | y << 3) of word z is voxel (x, y, z) of the brick.
  struct alignas(64) Brick {
    std::array<std::uint64_t, 8> words{};
  };

 public:
  // Offsets searched: squared length up to this (a radius of 8 voxels). A query with no point as
  // near gets no answer here.
  static constexpr int kMaxSquared = 64;
  // The most points of a shell listed; the count goes on beyond.
  static constexpr std::size_t kListed = 32;

  // The index of `points` (integers in single precision, each coordinate within +-2^20, no two
  // equal), or null where they are not such: then a general search must serve.
  static std::unique_ptr<LatticeNeighbours> build(const std::vector<std::array<float, 3>>& points);

  // The points at the least distance from a query.
  struct Shell {
    double squared = 0;                        // that distance squared, exact (an integer)
    std::size_t count = 0;                     // how many points are at it
    std::array<std::uint32_t, kListed> index;  // the first min(count, kListed) of them
  };

  // A thread's view of the occupancy near its queries: the bricks around the last query's, kept
  // while queries fall in the same brick.
  struct Probe {
    std::array<std::int32_t, 3> block{INT32_MIN, INT32_MIN, INT32_MIN};
    std::uint32_t looked_up = 0;        // bit k: near[k] is set (on a new block, one store clears all)
    std::array<const Brick*, 27> near;  // bricks around it, kNoBrick none
  };

  // The nearest shell from `q` (integral, within +-2^20; checked by the caller, as build checks
  // its points), leaving out distance 0 where `skip_zero`; false where no point is within
  // sqrt(kMaxSquared).
  bool nearest(const std::array<float, 3>& q, bool skip_zero, Probe& probe, Shell& shell) const;

  // Whether `q` can be a query: integral and within +-2^20.
  static bool on_lattice(const std::array<float, 3>& q);

 private:
  static const Brick kNoBrick;  // empty: where no brick is
  // Where a brick's points are listed: from `first` in `order_`, `before[z]` of them before word z.
  struct BrickStart {
    std::uint32_t first = 0;
    std::array<std::uint16_t, 8> before{};
  };
  // Open addressing, a key beside its brick so that a lookup reads one cache line.
  struct Slot {
    std::uint64_t key = 0;  // brick key + 1, 0 empty
    std::int32_t brick = -1;
  };
  __attribute__((always_inline)) static std::size_t slot_of(const std::vector<Slot>& table, std::size_t first,
                                                             int bits, std::uint64_t key);
  std::int32_t find(std::uint64_t key) const;  // the brick, -1 none
  // The brick (sx, sy, sz) bricks from the probe's block (each -1, 0 or 1), kNoBrick none.
  const Brick& brick_near(Probe& probe, std::int32_t sx, std::int32_t sy, std::int32_t sz) const;
  // The point at voxel (tx, ty, tz) (brick-local low 3 bits) of brick `brick`, which holds one.
  std::size_t place(std::int32_t brick, std::int32_t tx, std::int32_t ty,
                    std::int32_t tz) const;  // in order_
  std::uint32_t point_in(std::int32_t brick, std::int32_t tx, std::int32_t ty, std::int32_t tz) const;

  std::vector<Brick> bricks_;
  std::vector<BrickStart> starts_;
  std::vector<std::uint32_t> order_;  // the points' indices, brick after brick, voxel order within
  // The bricks of each slab (the bricks of one x) in a table of their own, 2^bits slots from
  // `first` in table_ (0 bits: none): queries in sorted order read the tables of a few slabs at a
  // time, which stay in the cache, where one table of all would be read at random.
  struct Slab {
    std::uint32_t first = 0;
    std::uint8_t bits = 0;
  };
  std::vector<Slab> slabs_;  // from the brick x slab_low_
  std::int32_t slab_low_ = 0;
  std::vector<Slot> table_;
};

}  // namespace roving
