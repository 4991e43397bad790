#include "roving/reconstruction/greedy_thinning.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <numeric>

#include "roving/core/error.h"

namespace roving {

// Visiting a shuffled cloud point by point reads memory at random (18 s for 10^7 points), so the
// same answer is reached in rounds over the points in spatial order instead: a point's fate depends
// only on its earlier neighbours (within radius, visited before it); each round keeps the points
// whose earlier neighbours are all dropped and drops those with one kept, until every point is
// decided. That is the sequential result exactly (the greedy independent set of the order), and
// a random order decides nearly everything in a few rounds. Neighbours come from a grid of cells
// at least 2 * radius wide: a ball meets at most two per axis.
std::vector<std::uint8_t> greedy_thinning(const std::vector<Vec3>& points, std::vector<std::uint32_t> rank,
                                          double radius) {
  const std::size_t n = points.size();
  BoundingBox box;
  for (const Vec3& p : points) box.extend(p);
  // Cells at least 2 * radius wide, and few enough that a cell's three coordinates fit 21 bits
  // each: one 64-bit key per cell, none shared. They count from two cells below the box, so that
  // every point's cell and the cells around it are >= 0 however the division rounds (with one
  // cell of margin, a point on the box's face could round into cell 0 and look for neighbours in
  // cell -1).
  const double extent = box.empty() ? 0.0 : box.size().maxCoeff();
  if (!std::isfinite(extent)) throw Error("thinning: the points span more than a double can hold");
  const double cell = std::max(2 * radius, extent / ((1 << 21) - 8));
  const double r2 = radius * radius;
  const Vec3 corner = box.empty() ? Vec3::Zero() : Vec3(box.min - Vec3::Constant(2 * cell));
  const auto coordinate = [&](double v, int a) { return static_cast<std::int64_t>(std::floor((v - corner[a]) / cell)); };
  const auto key = [](std::int64_t x, std::int64_t y, std::int64_t z) {
    return static_cast<std::uint64_t>(x) | static_cast<std::uint64_t>(y) << 21 | static_cast<std::uint64_t>(z) << 42;
  };
  // The points sorted by cell; a cell's points are a run of `sorted`.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> sorted(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const auto& range) {
    for (std::size_t i = range.begin(); i < range.end(); ++i) {
      const Vec3& p = points[i];
      sorted[i] = {key(coordinate(p[0], 0), coordinate(p[1], 1), coordinate(p[2], 2)), static_cast<std::uint32_t>(i)};
    }
  });
  tbb::parallel_sort(sorted.begin(), sorted.end());
  // Positions and ranks in that order, and where each cell's run starts: the neighbour search below
  // then reads memory in runs.
  std::vector<Vec3> position(n);
  std::vector<std::uint32_t> sorted_rank(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const auto& range) {
    for (std::size_t s = range.begin(); s < range.end(); ++s) {
      position[s] = points[sorted[s].second];
      sorted_rank[s] = rank[sorted[s].second];
    }
  });
  std::vector<std::uint32_t>().swap(rank);
  std::vector<std::uint32_t> runs;      // the first place of each cell's run, and n at the end
  std::vector<std::uint64_t> run_keys;  // each run's cell
  std::vector<std::uint32_t> index(n);  // the point at each place
  for (std::size_t s = 0; s < n; ++s) {
    if (s == 0 || sorted[s].first != sorted[s - 1].first) {
      runs.push_back(static_cast<std::uint32_t>(s));
      run_keys.push_back(sorted[s].first);
    }
    index[s] = sorted[s].second;
  }
  runs.push_back(static_cast<std::uint32_t>(n));
  decltype(sorted)().swap(sorted);  // 16 bytes a point, no longer needed
  const std::size_t run_count = run_keys.size();
  // Calls visit(s, t) for each earlier neighbour t of every place s of the runs [first, last), s by s.
  // The 27 cells around a run are found by 9 cursors, one per row (y, z) of cells around it: keys
  // order cells by z, y, then x, so each cursor only moves forward as the runs do.
  const auto for_each_earlier_neighbour = [&](std::size_t first, std::size_t last, auto&& visit) {
    std::array<std::size_t, 9> cursor;
    for (int row = 0; row < 9; ++row) {
      const std::uint64_t k = run_keys[first];
      const std::uint64_t start = k - 1 + (std::uint64_t(row % 3) << 21) + (std::uint64_t(row / 3) << 42) -
                                  (std::uint64_t(1) << 21) - (std::uint64_t(1) << 42);
      cursor[row] = std::lower_bound(run_keys.begin(), run_keys.end(), start) - run_keys.begin();
    }
    for (std::size_t r = first; r < last; ++r) {
      std::array<std::pair<std::uint32_t, std::uint32_t>, 27> around{};  // empty where there is no cell
      for (int row = 0; row < 9; ++row) {
        // The cells (x - 1 .. x + 1, y + dy, z + dz): consecutive keys.
        const std::uint64_t left =
            run_keys[r] - 1 + (std::uint64_t(row % 3) << 21) + (std::uint64_t(row / 3) << 42) -
            (std::uint64_t(1) << 21) - (std::uint64_t(1) << 42);
        std::size_t& c = cursor[row];
        while (c < run_count && run_keys[c] < left) ++c;
        for (std::size_t q = c; q < run_count && run_keys[q] <= left + 2; ++q) {
          around[row * 3 + int(run_keys[q] - left)] = {runs[q], runs[q + 1]};
        }
      }
      const Vec3& any = position[runs[r]];
      const std::array<std::int64_t, 3> cell_of = {coordinate(any[0], 0), coordinate(any[1], 1), coordinate(any[2], 2)};
      for (std::uint32_t s = runs[r]; s < runs[r + 1]; ++s) {
        const Vec3& p = position[s];
        std::array<int, 3> lo, hi;  // the cells the ball around p meets: -1, 0 or 1 per axis
        for (int a = 0; a < 3; ++a) {
          lo[a] = static_cast<int>(coordinate(p[a] - radius, a) - cell_of[a]);
          hi[a] = static_cast<int>(coordinate(p[a] + radius, a) - cell_of[a]);
        }
        for (int z = lo[2]; z <= hi[2]; ++z)
          for (int y = lo[1]; y <= hi[1]; ++y)
            for (int x = lo[0]; x <= hi[0]; ++x) {
              const auto [begin, end] = around[(z + 1) * 9 + (y + 1) * 3 + (x + 1)];
              for (std::uint32_t t = begin; t < end; ++t) {
                if (sorted_rank[t] >= sorted_rank[s]) continue;
                const Vec3& q = position[t];
                const double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
                if (dx * dx + dy * dy + dz * dz <= r2) visit(s, t);
              }
            }
      }
    }
  };
  // Each place's earlier neighbours (CSR): counted, then written.
  std::vector<std::uint64_t> offsets(n + 1, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, run_count, 1024), [&](const auto& range) {
    for_each_earlier_neighbour(range.begin(), range.end(), [&](std::uint32_t s, std::uint32_t) { ++offsets[s + 1]; });
  });
  for (std::size_t s = 0; s < n; ++s) offsets[s + 1] += offsets[s];
  std::vector<std::uint32_t> earlier(offsets.back());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, run_count, 1024), [&](const auto& range) {
    std::uint32_t current = static_cast<std::uint32_t>(n);
    std::uint64_t at = 0;
    for_each_earlier_neighbour(range.begin(), range.end(), [&](std::uint32_t s, std::uint32_t t) {
      if (s != current) current = s, at = offsets[s];
      earlier[at++] = t;
    });
  });
  // Rounds. A status read while another thread writes it is either final (and right) or still
  // undecided (and the point waits a round), so the outcome does not depend on the timing.
  enum : std::uint8_t { kUndecided, kKept, kDropped };
  std::unique_ptr<std::atomic<std::uint8_t>[]> status(new std::atomic<std::uint8_t>[n]);
  for (std::size_t s = 0; s < n; ++s) status[s].store(kUndecided, std::memory_order_relaxed);
  std::vector<std::uint32_t> pending(n), next;
  std::iota(pending.begin(), pending.end(), 0u);
  while (!pending.empty()) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pending.size(), 4096), [&](const auto& range) {
      for (std::size_t k = range.begin(); k < range.end(); ++k) {
        const std::uint32_t s = pending[k];
        std::uint8_t verdict = kKept;
        for (std::uint64_t e = offsets[s]; e < offsets[s + 1]; ++e) {
          const std::uint8_t other = status[earlier[e]].load(std::memory_order_relaxed);
          if (other == kKept) {
            verdict = kDropped;
            break;
          }
          if (other == kUndecided) verdict = kUndecided;
        }
        if (verdict != kUndecided) status[s].store(verdict, std::memory_order_relaxed);
      }
    });
    next.clear();
    for (const std::uint32_t s : pending) {
      if (status[s].load(std::memory_order_relaxed) == kUndecided) next.push_back(s);
    }
    pending.swap(next);
  }
  std::vector<std::uint8_t> keep(n, 0);
  for (std::size_t s = 0; s < n; ++s) keep[index[s]] = status[s].load(std::memory_order_relaxed) == kKept;
  return keep;
}

}  // namespace roving
