// The certified share of A's area within tau of B, piece by piece (see the header).
#include "roving/reference_embree/certified_area_within.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "roving/core/error.h"
#include "roving/core/stopwatch.h"
#include "triangle_piece.h"

namespace roving {
namespace {

// What one piece adds: per tau, its area in units rounded down where it is surely within, rounded
// up where it may be; and whether it is to be split.
struct Verdict {
  std::vector<std::uint64_t> within, undecided;
  bool split = false;
};

}  // namespace

AreaWithin certified_area_within(const TriangleMesh& a, const TriangleMesh& b, const std::vector<double>& thresholds,
                                 double min_length, std::size_t first, std::size_t last, const ProgressFn& progress) {
  if (a.triangle_count() == 0 || b.triangle_count() == 0) {
    throw Error("certified area within tau: expected two meshes with triangles, found an empty one");
  }
  for (const double tau : thresholds) {
    if (!(tau >= 0) || !std::isfinite(tau)) throw Error(fmt::format("--threshold: expected a finite tau >= 0, found {}", tau));
  }
  if (!(min_length > 0) || !std::isfinite(min_length)) {
    throw Error(fmt::format("certified area within tau: expected a positive finite piece length, found {}", min_length));
  }
  if (first > last || last > a.triangle_count()) {
    throw Error(fmt::format("certified area within tau: triangles [{}, {}) are not within A's {}", first, last,
                            a.triangle_count()));
  }
  const Stopwatch watch;
  const std::size_t n = thresholds.size();
  AreaWithin result;
  result.thresholds = thresholds;
  result.within.assign(n, 0);
  result.undecided.assign(n, 0);
  if (n == 0 || a.total_area() <= 0) return result;
  const ClosestPoints closest(b);
  // Every distance below is the kernel's, within this of the exact one: each bound is widened by it.
  double largest_coordinate = 0;
  for (const TriangleMesh* mesh : {&a, &b}) {
    for (const Vec3& p : mesh->positions()) largest_coordinate = std::max(largest_coordinate, p.cwiseAbs().maxCoeff());
  }
  const double error = closest_point_error_bound(largest_coordinate);
  const double units_per_area = 1 / (AreaWithin::kUnit * a.total_area());

  // A piece's verdict from its corners' distances; with its centre's distance to B too where that
  // is known (NaN where not), a tighter lower bound.
  const auto judge = [&](const Piece& piece, double centre_distance) {
    Verdict v{std::vector<std::uint64_t>(n, 0), std::vector<std::uint64_t>(n, 0), false};
    const auto& c = piece.corner;
    const double area = piece.area;
    if (!(area > 0)) return v;  // a degenerate piece has no area
    const double longest = std::max({(c[1] - c[0]).norm(), (c[2] - c[1]).norm(), (c[0] - c[2]).norm()});
    const auto [least, most] = std::minmax({piece.distance[0], piece.distance[1], piece.distance[2]});
    // Every point of a triangle is within its longest edge / sqrt 3 of a corner (the circumradius
    // at most, for the largest angle is >= 60 degrees), and within the longest edge of each.
    const double upper = std::min(piece.upper, most + longest / std::sqrt(3.0)) + error;
    double lower = std::max({0.0, most - longest, least - longest / std::sqrt(3.0)}) - error;
    if (!std::isnan(centre_distance)) {
      // No point of the piece is farther from its centre than its farthest corner (1-Lipschitz).
      const Vec3 centre = (c[0] + c[1] + c[2]) / 3;
      double reach = 0;
      for (const Vec3& corner : c) reach = std::max(reach, (corner - centre).norm());
      lower = std::max(lower, centre_distance - reach - error);
    }
    const bool may_split = longest > min_length && piece.depth < kMaxDepth;
    for (std::size_t k = 0; k < n; ++k) {
      if (upper <= thresholds[k]) {
        v.within[k] = static_cast<std::uint64_t>(std::floor(area));
      } else if (lower <= thresholds[k]) {
        if (may_split) {
          v.split = true;
        } else {
          v.undecided[k] = static_cast<std::uint64_t>(std::ceil(area));
        }
      }
    }
    if (v.split) v.within.assign(n, 0), v.undecided.assign(n, 0);  // its children will say
    return v;
  };

  // Every vertex of the range's triangles: its distance to B and its closest triangle, once.
  const auto& positions = a.positions();
  const auto& triangles = a.triangles();
  std::vector<bool> used(positions.size(), false);
  for (std::size_t t = first; t < last; ++t) {
    for (const int v : triangles[t]) used[v] = true;
  }
  std::vector<ClosestPoints::Found> at_vertex(positions.size());
  tbb::parallel_for(std::size_t{0}, positions.size(), [&](std::size_t v) {
    if (used[v]) at_vertex[v] = closest.query(positions[v]);
  });
  result.distance_queries = static_cast<std::size_t>(std::count(used.begin(), used.end(), true));

  // The triangles in blocks on both cores, each undecided piece split depth first; the blocks'
  // sums are exact, so their order does not matter.
  // 64 triangles a block: a block of a close pair's deep splits takes about 0.1 s (1,024 took 1.5 s on
  // the bunny against its noisy copy at 0.05%), and progress, Ctrl-C's way in, is heard per block.
  constexpr std::size_t kBlock = 64;
  const std::size_t blocks = (last - first + kBlock - 1) / kBlock;
  std::vector<Verdict> block_sum(blocks, Verdict{std::vector<std::uint64_t>(n, 0), std::vector<std::uint64_t>(n, 0)});
  std::vector<std::size_t> block_splits(blocks, 0), block_queries(blocks, 0);
  std::atomic<std::size_t> decided{0};  // A's triangles of the blocks done, for `progress`
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t block) {
    Verdict& sum = block_sum[block];
    std::vector<Piece> stack;
    for (std::size_t t = first + block * kBlock; t < std::min(last, first + (block + 1) * kBlock); ++t) {
      Piece piece;
      piece.area = 0.5 * (positions[triangles[t][1]] - positions[triangles[t][0]])
                             .cross(positions[triangles[t][2]] - positions[triangles[t][0]])
                             .norm() *
                   units_per_area;
      for (int i = 0; i < 3; ++i) {
        const int v = triangles[t][i];
        piece.corner[i] = positions[v];
        piece.distance[i] = at_vertex[v].distance;
        add_candidate(piece, at_vertex[v].triangle);
      }
      bound(piece, closest);
      stack.push_back(piece);
      while (!stack.empty()) {
        Piece p = stack.back();
        stack.pop_back();
        Verdict v = judge(p, std::nan(""));
        if (v.split) {  // before splitting: the triangle of B closest to the piece's centre as a candidate, and
                        // the centre's distance to B
          const ClosestPoints::Found at_centre = closest.query((p.corner[0] + p.corner[1] + p.corner[2]) / 3);
          add_candidate(p, at_centre.triangle);
          bound(p, closest);
          ++block_queries[block];
          v = judge(p, at_centre.distance);
        }
        if (v.split) {
          std::array<std::pair<Vec3, ClosestPoints::Found>, 3> midpoints;
          for (Piece& child : split(p, closest, midpoints)) stack.push_back(std::move(child));
          ++block_splits[block];
          continue;
        }
        for (std::size_t k = 0; k < n; ++k) sum.within[k] += v.within[k], sum.undecided[k] += v.undecided[k];
      }
    }
    const std::size_t done = decided += std::min(last, first + (block + 1) * kBlock) - (first + block * kBlock);
    if (progress) progress("triangles", done, last - first);
  });
  for (std::size_t block = 0; block < blocks; ++block) {
    for (std::size_t k = 0; k < n; ++k) {
      result.within[k] += block_sum[block].within[k];
      result.undecided[k] += block_sum[block].undecided[k];
    }
    result.triangles_split += block_splits[block];
    result.distance_queries += block_queries[block];
  }
  result.distance_queries += 3 * result.triangles_split;
  result.seconds = watch.seconds();
  return result;
}

}  // namespace roving
