// The share of A's area within a distance tau of B, certified: the area that is surely within and
// the area that may be, for each of several tau (precision and recall as area fractions). Embree's
// headers stay inside the .cpp.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "roving/core/distance_method.h"
#include "roving/core/triangle_mesh.h"

namespace roving {

// Areas in fixed point, units of 2^-60 of A's total area: sums of pieces are then exact, so that
// shards covering A add up to the whole run's figures bit for bit, whatever the order.
struct AreaWithin {
  static constexpr double kUnit = 0x1p-60;
  std::vector<double> thresholds;
  std::vector<std::uint64_t> within;     // per tau: area surely within tau of B (rounded down)
  std::vector<std::uint64_t> undecided;  // per tau: area that may be within tau (rounded up)
  std::size_t distance_queries = 0;      // closest-point queries on B made
  std::size_t triangles_split = 0;       // subdivisions of A's triangles the bounds needed
  double seconds = 0;

  // The share of A's area within thresholds[k] of B lies in [lower(k), upper(k)] (the pieces' areas,
  // each rounded, may add up to a little over 1: a share is at most 1).
  double lower(std::size_t k) const { return std::min(1.0, static_cast<double>(within[k]) * kUnit); }
  double upper(std::size_t k) const { return std::min(1.0, static_cast<double>(within[k] + undecided[k]) * kUnit); }
};

// Over A's triangles [first, last), the distance to B's triangles bounded piece by piece: above by
// the convexity bound of certified_hausdorff.h over the triangles of B closest to the piece's
// corners and centre (or by a corner's distance plus the piece's reach, 1-Lipschitz); below by a
// corner's distance less the reach, and, where that does not decide, by its centre's distance less
// the centre's reach. Every distance is the robust kernel's (core/geometry.h), each bound widened
// by its stated error, which also covers the rounding of the midpoints the splits place; a piece's
// area is a fourth of its parent's, exactly (tests/exact_oracle_test.cpp holds the shares to an
// exact oracle on degenerate and thin triangles). A piece
// is within tau where its upper bound is <= tau, beyond where its lower bound is > tau, and split
// in four otherwise while it is longer than `min_length` (> 0) and fewer than kMaxDepth splits
// from its triangle: the work per triangle is bounded, and the same whatever the range. What is
// left is undecided. Both cores (TBB). `progress` hears ("triangles", done, last - first) as blocks
// of A's triangles are decided (what it throws stops the work and is rethrown: Ctrl-C's way in).
// Throws roving::Error on an empty mesh, a threshold that is not finite and >= 0, a bad length or a
// range outside A.
AreaWithin certified_area_within(const TriangleMesh& a, const TriangleMesh& b, const std::vector<double>& thresholds,
                                 double min_length, std::size_t first, std::size_t last,
                                 const ProgressFn& progress = {});

constexpr int kMaxDepth = 6;  // at most 4^6 = 4096 pieces of one triangle

}  // namespace roving
